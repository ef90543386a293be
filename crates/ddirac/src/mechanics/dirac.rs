//! Unreduced (+) and (−) discrete Lagrange–Dirac equations (paper §2.3.2).
//!
//! In the unconstrained case both read, in position–momentum form,
//!
//! ```text
//! (+):  q_k^+ = q_{k+1},  p_k = −D1 L_d(q_k, q_k^+),  p_{k+1} = D2 L_d(q_k, q_k^+)
//! (−):  q_{k+1}^- = q_k,  p_k = −D1 L_d(q_{k+1}^-, q_{k+1}),  p_{k+1} = D2 L_d(q_{k+1}^-, q_{k+1})
//! ```
//!
//! which is the same map (the discrete Euler–Lagrange equations): given (q_k, p_k), solve the first
//! momentum equation for q_{k+1} by Newton's method (Jacobian D1 D2 L_d), then evaluate p_{k+1}.
//! Degenerate Lagrangians are allowed as long as D1 D2 L_d is invertible.
//!
//! The unknowns are the chart increments z = q_{k+1} − q_k.

use crate::Scalar;
use nalgebra::SVector;

use crate::scheme::{Scheme, StepEquations};
use crate::{DiscreteLagrangian, System};

/// The position–momentum discrete Euler–Lagrange map, shared by the (+) and (−) variants.
pub(crate) struct LagrangeDirac<S> {
    pub ld: DiscreteLagrangian<S>,
}

impl<S: System<N> + Clone, const N: usize> Scheme<N> for LagrangeDirac<S> {
    fn base(&self, q: &[f64; N]) -> [f64; N] {
        *q
    }

    fn resized(&self, step: f64) -> Self {
        Self { ld: DiscreteLagrangian::new(self.ld.system.clone(), self.ld.rule, step) }
    }

    fn generating<D, B>(&self, base: &[B; N], a: &[D; N], b: &[D; N]) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Copy,
    {
        self.ld.eval_local(base, a, b)
    }

    /// p_k + D1 L_d = 0, p_{k+1} = D2 L_d.
    fn equations(&self) -> StepEquations<N> {
        StepEquations { sign: [1.0; N], advances: [true; N], eliminable: [false; N] }
    }

    fn increment(&self, z: &SVector<f64, N>) -> [f64; N] {
        (*z).into()
    }

    fn unknowns(&self, dq: &[f64; N]) -> SVector<f64, N> {
        SVector::from(*dq)
    }

    fn momenta_from_p(&self, p: &[f64; N]) -> [f64; N] {
        *p
    }

    fn p_from_momenta(&self, momenta: &[f64; N]) -> [f64; N] {
        *momenta
    }
}

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

use crate::dim::{Dim, Entry};
use crate::mechanics::lagrangian::Lagrangian;
use crate::scheme::{Scheme, StepEquations};
use crate::{DiscreteLagrangian, Scalar};

/// The position–momentum discrete Euler–Lagrange map, shared by the (+) and (−) variants.
pub(crate) struct LagrangeDirac<S, Dm> {
    pub ld: DiscreteLagrangian<S>,
    /// The number of coordinates.
    pub dim: Dm,
}

impl<S: Lagrangian<Dm> + Clone, Dm: Dim> Scheme<Dm> for LagrangeDirac<S, Dm> {
    fn base(&self, q: &Dm::Array<f64>) -> Dm::Array<f64> {
        q.clone()
    }

    fn resized(&self, step: f64) -> Self {
        Self { ld: DiscreteLagrangian::new(self.ld.system.clone(), self.ld.rule, step), dim: self.dim }
    }

    fn generating<D, B>(&self, base: &Dm::Array<B>, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        self.ld.eval_in::<Dm, D, B>(base, a, b)
    }

    /// p_k + D1 L_d = 0, p_{k+1} = D2 L_d.
    fn equations(&self) -> StepEquations<Dm> {
        let dim = self.dim;
        StepEquations { sign: dim.array(|_| 1.0), advances: dim.array(|_| true), eliminable: dim.array(|_| false) }
    }

    fn increment(&self, z: &Dm::Vector) -> Dm::Array<f64> {
        self.dim.array(|i| z[i])
    }

    fn unknowns(&self, dq: &Dm::Array<f64>) -> Dm::Vector {
        self.dim.vector(|i| dq[i])
    }

    fn momenta_from_p(&self, p: &Dm::Array<f64>) -> Dm::Array<f64> {
        p.clone()
    }

    fn p_from_momenta(&self, momenta: &Dm::Array<f64>) -> Dm::Array<f64> {
        momenta.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::{Dynamic, Fixed};
    use crate::scheme::testing::{assert_alike, AsDynamic};
    use crate::systems::PendulumChain;
    use crate::{Differentiation, Rule};

    #[test]
    fn unreduced_steps_are_alike_in_a_fixed_and_a_dynamic_dimension() {
        const N: usize = 5;
        let chain = PendulumChain::<N>::default();
        let q: [f64; N] = std::array::from_fn(|i| 0.4 * (i as f64 + 1.0).sin());
        let p: [f64; N] = std::array::from_fn(|i| 0.1 * i as f64);
        for choice in [Differentiation::Dual, Differentiation::Compiled] {
            for rule in [Rule::Midpoint, Rule::Trapezoid] {
                let fixed = LagrangeDirac { ld: DiscreteLagrangian::new(chain, rule, 0.01), dim: Fixed::<N> };
                let dynamic = LagrangeDirac {
                    ld: DiscreteLagrangian::new(AsDynamic::<_, N>(chain), rule, 0.01),
                    dim: Dynamic(N),
                };
                let method = crate::Method { rule, differentiation: choice, ..crate::Method::default() };
                assert_alike(&chain, &fixed, &dynamic, &method, q, p, 30);
            }
        }
    }
}

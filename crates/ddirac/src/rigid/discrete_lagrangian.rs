//! The discrete Lagrangian of a step on SO(3) × S, as a function of the step's Lie algebra element.
//!
//! A step from (R_k, s_k) to (R_{k+1}, s_{k+1}) with R_{k+1} = R_k cay(ζ) (see [`super::so3`]) has
//! the body velocity ξ = ζ/h and the shape velocity v = (s_{k+1} − s_k)/h, and the rules of the
//! abelian engine ([`Rule`]) become
//!
//! ```text
//! left       L_d = h ℓ(R_k, ξ, s_k, v)
//! right      L_d = h ℓ(R_{k+1}, ξ, s_{k+1}, v)
//! midpoint   L_d = h ℓ(R_k cay(half(ζ)), ξ, (s_k + s_{k+1})/2, v)        (the group midpoint)
//! trapezoid  L_d = h/2 [ℓ(R_k, ξ, s_k, v) + ℓ(R_{k+1}, ξ, s_{k+1}, v)]
//! ```
//!
//! Midpoint and trapezoid are symmetric (the adjoint step from R_{k+1} back to R_k has ζ' = −ζ, since
//! cay(−ζ) = cay(ζ)⁻¹ and half(−ζ) = −half(ζ)), hence of order 2; left and right are of order 1.
//! The trapezoid with a kinetic energy ½⟨Ω, 𝕀Ω⟩ is the Lie group variational integrator of Lee, Leok
//! and McClamroch with the Cayley map in place of the exponential.
//!
//! The step equations need the derivative of L_d along a variation of the attitude R_k ↦ R_k exp(η̂)
//! (left trivialized, with R_{k+1} = R_k exp(η̂) cay(ζ) following it), along ζ and along both shape
//! ends, and the second derivatives of these with respect to the unknowns (ζ, s_{k+1}). All come from
//! one function of two blocks of m = 6 + n arguments ([`PairFunction`]), evaluated on the engine's
//! dual numbers:
//!
//! ```text
//! a = (η, ζ_a, s_k)      b = (ζ_b, s_{k+1}, 0, 0, 0)      ζ = ζ_a + ζ_b,  R_k exp(η̂) ≈ R_k (I + η̂)
//! ```
//!
//! so that ∂f/∂a holds the three gradients of the residual, ∂f/∂b the gradient in s_{k+1} of the next
//! momenta, and the mixed block ∂²f/∂a∂b every entry of the Jacobian (ζ in both blocks gives the
//! Hessian in ζ). The first-order substitute I + η̂ for exp(η̂) is exact for these derivatives, which
//! are of first order in η. A reduced step (the Lagrangian invariant under every rotation) evaluates ℓ
//! at R = I and has no η.

use super::so3::{self, Matrix3};
use super::system::RigidSystem;
use crate::dim::{Dim, Dynamic, PairFunction};
use crate::{Rule, Scalar};

/// The discrete Lagrangian of one step from a fixed attitude R_k, as the [`PairFunction`] described in
/// the module documentation.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepLagrangian<'s, S> {
    pub system: &'s S,
    /// R_k.
    pub attitude: Matrix3<f64>,
    /// The step h.
    pub h: f64,
    pub rule: Rule,
    /// Evaluate ℓ at R = I with no variation η (a reduced step).
    pub reduced: bool,
    /// Shape coordinates n.
    pub shape: usize,
}

impl<S: RigidSystem> StepLagrangian<'_, S> {
    /// The dimension of each block, 6 + n.
    pub fn dim(&self) -> Dynamic {
        Dynamic(6 + self.shape)
    }

    /// The blocks a and b at the unknowns (ζ, s_{k+1}) from s_k: η = 0, ζ_a = ζ, ζ_b = 0.
    pub fn blocks(&self, unknowns: &[f64], s: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.shape;
        let a = self.dim().array(|i| match i {
            0..3 => 0.0,
            3..6 => unknowns[i - 3],
            _ => s[i - 6],
        });
        let b = self.dim().array(|i| if (3..3 + n).contains(&i) { unknowns[i] } else { 0.0 });
        (a, b)
    }

    fn l<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D {
        self.system.lagrangian(r, omega, s, v)
    }
}

impl<S: RigidSystem> PairFunction<Dynamic> for StepLagrangian<'_, S> {
    fn eval<D: Scalar>(&self, a: &Vec<D>, b: &Vec<D>) -> D {
        let n = self.shape;
        let h = self.h;
        let zeta = [a[3] + b[0], a[4] + b[1], a[5] + b[2]];
        let r0: Matrix3<D> = if self.reduced {
            so3::identity()
        } else {
            let rk = self.attitude.map(|row| row.map(D::from));
            let mut varied = so3::hat(&[a[0], a[1], a[2]]);
            for (i, row) in varied.iter_mut().enumerate() {
                row[i] += D::one();
            }
            so3::mul(&rk, &varied)
        };
        let xi = zeta.map(|z| z / h);
        let s0 = &a[6..6 + n];
        let s1 = &b[3..3 + n];
        let v: Vec<D> = (0..n).map(|i| (s1[i] - s0[i]) / h).collect();
        match self.rule {
            Rule::Left => self.l(&r0, &xi, s0, &v) * h,
            Rule::Right => self.l(&so3::mul(&r0, &so3::cayley(&zeta)), &xi, s1, &v) * h,
            Rule::Midpoint => {
                let rm = so3::mul(&r0, &so3::cayley(&so3::half(&zeta)));
                let sm: Vec<D> = (0..n).map(|i| (s0[i] + s1[i]) * 0.5).collect();
                self.l(&rm, &xi, &sm, &v) * h
            }
            Rule::Trapezoid => {
                let r1 = so3::mul(&r0, &so3::cayley(&zeta));
                (self.l(&r0, &xi, s0, &v) + self.l(&r1, &xi, s1, &v)) * (0.5 * h)
            }
        }
    }
}

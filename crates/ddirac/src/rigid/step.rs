//! The discrete Hamilton–Pontryagin (Lagrange–Dirac) step on SO(3) × S, unreduced and reduced.
//!
//! With L_d(R_k, ζ_k, s_k, s_{k+1}) the discrete Lagrangian of a step ([`super::discrete_lagrangian`]),
//! variations δR_k = R_k η̂_k and δζ_k = dcay⁻¹_{ζ_k}(−η_k + F_k η_{k+1}) (F_k = cay(ζ_k)) make the
//! discrete action stationary when, with μ_k = (dcay⁻¹_{ζ_k})ᵀ ∂L_d/∂ζ_k,
//!
//! ```text
//! Π_k     = μ_k − ∂L_d/∂η_k                      (discrete Legendre, left end)     residual r_g
//! p_k     = −∂L_d/∂s_k                                                              residual r_s
//! Π_{k+1} = F_kᵀ μ_k,   p_{k+1} = ∂L_d/∂s_{k+1}  (right end)
//! R_{k+1} = R_k F_k                              (reconstruction)
//! ```
//!
//! (Bou-Rabee & Marsden's discrete Hamilton–Pontryagin principle on a Lie group, left trivialized, in
//! the Cayley retraction; Π is the body angular momentum, the costate of Ω.) Given (R_k, Π_k, s_k,
//! p_k), Newton's method solves r_g = r_s = 0 for the unknowns (ζ_k, s_{k+1}). Where ℓ is invariant
//! under every rotation of space, ∂L_d/∂η = 0 and ℓ needs no R: the same equations on
//! (s, ζ, Π) are the discrete Lagrange–Poincaré (Euler–Poincaré without shape) equations, whose
//! body momentum is carried by conjugation, Π_{k+1} = F_kᵀ (Π_k + ∂L_d/∂η_k) = F_kᵀ Π_k, so that the
//! Casimir |Π| is kept to round-off; R is reconstructed alongside (`StepLagrangian::reduced`).
//!
//! The Jacobian of r_g in ζ has, besides (dcay⁻¹)ᵀ ∂²L_d/∂ζ² − ∂²L_d/∂η∂ζ, the derivative of
//! (dcay⁻¹_ζ)ᵀ g = g + ½ ζ × g + ¼ ζ ⟨ζ, g⟩ at fixed g = ∂L_d/∂ζ: −½ ĝ + ¼ (⟨ζ, g⟩ I + ζ gᵀ).

use nalgebra::{DMatrix, DVector};

use super::discrete_lagrangian::StepLagrangian;
use super::so3::{self, Matrix3};
use super::system::RigidSystem;
use crate::dim::{first_or_mixed, Dynamic, FirstDerivatives};
use crate::newton::{self, KeptJacobian, NewtonFailure, NewtonOptions, NewtonStats};

/// The state a step starts from.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Point {
    /// R_k.
    pub r: Matrix3<f64>,
    /// Π_k.
    pub pi: [f64; 3],
    /// s_k.
    pub s: Vec<f64>,
    /// p_k.
    pub p: Vec<f64>,
}

/// One step's equations from a [`Point`] with step h.
pub(crate) struct StepEquations<'s, S> {
    pub f: StepLagrangian<'s, S>,
    pub from: &'s Point,
}

impl<S: RigidSystem> StepEquations<'_, S> {
    /// The residual (r_g, r_s) at the unknowns x = (ζ, s_{k+1}), with its Jacobian when asked, and the
    /// first derivatives it came from.
    pub fn evaluate(
        &self,
        x: &DVector<f64>,
        with_jacobian: bool,
    ) -> (DVector<f64>, Option<DMatrix<f64>>, FirstDerivatives<Dynamic>) {
        let n = self.f.shape;
        let (a, b) = self.f.blocks(x.as_slice(), &self.from.s);
        let (d, mixed) = first_or_mixed(self.f.dim(), &self.f, &a, &b, with_jacobian);
        let t = Trivialized::new([x[0], x[1], x[2]], [d.da[3], d.da[4], d.da[5]]);
        let mu = t.momentum();
        let mut r = DVector::zeros(3 + n);
        for i in 0..3 {
            r[i] = mu[i] - d.da[i] - self.from.pi[i];
        }
        for i in 0..n {
            r[3 + i] = d.da[6 + i] + self.from.p[i];
        }
        let jacobian = mixed.map(|h| {
            DMatrix::from_fn(3 + n, 3 + n, |i, j| {
                if i < 3 {
                    let e = t.transported(i, |l| h[(3 + l, j)]) - h[(i, j)];
                    if j < 3 {
                        e + t.correction(i, j)
                    } else {
                        e
                    }
                } else {
                    h[(6 + i - 3, j)]
                }
            })
        });
        (r, jacobian, d)
    }

    /// The momenta at the end of the step from the derivatives at its solution x:
    /// Π_{k+1} = F_kᵀ μ_k with μ_k = Π_k + ∂L_d/∂η_k (r_g = 0), and p_{k+1} = ∂L_d/∂s_{k+1}. Written
    /// with Π_k rather than with μ_k's own formula, the body momentum of a reduced step is carried by
    /// the rotation F_kᵀ alone, so that |Π| (and the spatial R Π of an invariant ℓ) is kept to
    /// round-off whatever the Newton tolerance, as the abelian engine keeps its momentum map.
    pub fn momenta_next(&self, x: &DVector<f64>, d: &FirstDerivatives<Dynamic>) -> ([f64; 3], Vec<f64>) {
        let zeta = [x[0], x[1], x[2]];
        let mu = [0, 1, 2].map(|i| self.from.pi[i] + d.da[i]);
        let pi = so3::apply_transpose(&so3::cayley(&zeta), &mu);
        (pi, (0..self.f.shape).map(|i| d.db[3 + i]).collect())
    }

    /// Solves the step from the predicted unknowns `x` (ζ, s_{k+1}), which hold the solution on
    /// success, and returns the next point.
    pub fn solve(
        &self,
        x: &mut DVector<f64>,
        options: &NewtonOptions,
        kept: &mut KeptJacobian<Dynamic>,
    ) -> Result<(Point, NewtonStats), NewtonFailure> {
        let scale = self.from.pi.iter().chain(&self.from.p).fold(0.0f64, |m, x| m.max(x.abs()));
        let mut last = None;
        let stats = newton::solve_with(x, scale, options, kept, |x, with_jacobian| {
            let (r, j, d) = self.evaluate(x, with_jacobian);
            last = Some(d);
            (r, j)
        })?;
        let d = last.expect("Newton's method evaluates the residual at its root");
        let (pi, p) = self.momenta_next(x, &d);
        let f = so3::cayley(&[x[0], x[1], x[2]]);
        let r = orthonormalized(&so3::mul(&self.from.r, &f));
        let s = (0..self.f.shape).map(|i| x[3 + i]).collect();
        Ok((Point { r, pi, s, p }, stats))
    }
}

/// The left-trivialized momentum μ = (dcay⁻¹_ζ)ᵀ g of the gradient g = ∂L_d/∂ζ, and what the
/// Jacobian of the residual r_g = μ − ∂L_d/∂η − Π_k in ζ needs of it: (dcay⁻¹_ζ)ᵀ applied to a column
/// of second derivatives, and the derivative of (dcay⁻¹_ζ)ᵀ g at fixed g, −½ ĝ + ¼ (⟨ζ, g⟩ I + ζ gᵀ).
pub(crate) struct Trivialized {
    zeta: [f64; 3],
    g: [f64; 3],
    /// (dcay⁻¹_ζ)ᵀ.
    bt: Matrix3<f64>,
}

impl Trivialized {
    pub fn new(zeta: [f64; 3], g: [f64; 3]) -> Self {
        Self { zeta, g, bt: so3::transpose(&so3::dcay_inverse(&zeta)) }
    }

    /// μ = (dcay⁻¹_ζ)ᵀ g.
    pub fn momentum(&self) -> [f64; 3] {
        so3::apply(&self.bt, &self.g)
    }

    /// Row i of (dcay⁻¹_ζ)ᵀ times the column l ↦ `column(l)`.
    pub fn transported(&self, i: usize, column: impl Fn(usize) -> f64) -> f64 {
        (0..3).map(|l| self.bt[i][l] * column(l)).sum()
    }

    /// Entry (i, j) of ∂((dcay⁻¹_ζ)ᵀ g)/∂ζ at fixed g.
    pub fn correction(&self, i: usize, j: usize) -> f64 {
        let (zeta, g) = (&self.zeta, &self.g);
        let gh = so3::hat(g);
        let diagonal = if i == j { so3::dot(zeta, g) } else { 0.0 };
        -0.5 * gh[i][j] + 0.25 * (zeta[i] * g[j] + diagonal)
    }
}

/// R (3I − RᵀR)/2: one Newton step of the polar decomposition, which takes the round-off of a product
/// of rotations (of order ε) back to order ε², so that RᵀR = I holds to round-off over any run.
pub(crate) fn orthonormalized(r: &Matrix3<f64>) -> Matrix3<f64> {
    let rtr = so3::mul(&so3::transpose(r), r);
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = if i == j { 1.5 } else { 0.0 } - 0.5 * rtr[i][j];
        }
    }
    so3::mul(r, &c)
}

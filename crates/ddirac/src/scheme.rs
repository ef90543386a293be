//! A scheme is a residual: the step equations of one integrator, in chart-local unknowns z.
//!
//! The generic stepper ([`crate::integrator`]) owns the predictor, the Newton solve, step statistics
//! and failure reporting; a scheme only says how to evaluate its residual and Jacobian, how the
//! momenta advance, and how the solved unknowns move the configuration (reconstruction).

use nalgebra::{SMatrix, SVector};

/// One evaluation of a scheme's step equations at a trial point z.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Evaluation<const N: usize> {
    /// The residual r(z).
    pub residual: SVector<f64, N>,
    /// Its Jacobian ∂r/∂z, when it was asked for.
    pub jacobian: Option<SMatrix<f64, N, N>>,
    /// L_d(q_k, q_{k+1}) at the trial point (the paper's discrete energy).
    pub discrete_energy: f64,
    /// The scheme momenta at k + 1 if z is accepted.
    pub momenta_next: [f64; N],
}

/// The step equations of an integrator.
///
/// *Scheme momenta* are the scheme's own momentum variables: p for the unreduced schemes,
/// (w, μ) = λ̂_d(q, p) for the reduced ones, stored at the positions of the x and g coordinates.
pub(crate) trait Scheme<const N: usize> {
    /// The chart base for a step from a configuration whose chart base is `q`.
    fn base(&self, q: &[f64; N]) -> [f64; N];

    /// Residual, by-products and, if `with_jacobian`, the Jacobian at the trial unknowns `z`.
    fn evaluate(&self, base: &[f64; N], momenta: &[f64; N], z: &SVector<f64, N>, with_jacobian: bool) -> Evaluation<N>;

    /// The configuration increment q_{k+1} − q_k produced by the unknowns `z` (reconstruction).
    fn increment(&self, z: &SVector<f64, N>) -> [f64; N];

    /// The unknowns that produce a configuration increment (the inverse of [`Scheme::increment`]).
    fn unknowns(&self, dq: &[f64; N]) -> SVector<f64, N>;

    /// Scheme momenta from canonical momenta p.
    fn momenta_from_p(&self, p: &[f64; N]) -> [f64; N];

    /// Canonical momenta p from scheme momenta.
    fn p_from_momenta(&self, momenta: &[f64; N]) -> [f64; N];
}

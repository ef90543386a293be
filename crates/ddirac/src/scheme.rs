//! A scheme is a residual: the step equations of one integrator, in chart-local unknowns z.
//!
//! The generic stepper ([`crate::integrator`]) owns the predictor, the Newton solve, step statistics
//! and failure reporting; a scheme only says how to evaluate its residual and Jacobian, how the
//! momenta advance, and how the solved unknowns move the configuration (reconstruction).

use nalgebra::{SMatrix, SVector};
use num_dual::DualNum;

use crate::ad::{self, FirstDerivatives, PairFunction};
use crate::compiled::{CompileError, CompiledPair, Traced};
use crate::{DerivativePath, Differentiation};

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

    /// The generating function f(base, a, b) of the step: its derivatives at a = 0, b = z give the
    /// residual, the next momenta and the Jacobian ([`Scheme::evaluate`]). The base is a variable
    /// too when the function is traced for [`crate::compiled`].
    fn generating<D, B>(&self, base: &[B; N], a: &[D; N], b: &[D; N]) -> D
    where
        D: DualNum<Primitive = f64> + Copy + std::ops::Add<B, Output = D>,
        B: Copy;

    /// Residual, by-products and the Jacobian, if `mixed` is given, from the generating function's
    /// derivatives `d` and mixed block `mixed` at the trial unknowns.
    fn evaluate(&self, momenta: &[f64; N], d: &FirstDerivatives<N>, mixed: Option<SMatrix<f64, N, N>>)
        -> Evaluation<N>;

    /// The configuration increment q_{k+1} − q_k produced by the unknowns `z` (reconstruction).
    fn increment(&self, z: &SVector<f64, N>) -> [f64; N];

    /// The unknowns that produce a configuration increment (the inverse of [`Scheme::increment`]).
    fn unknowns(&self, dq: &[f64; N]) -> SVector<f64, N>;

    /// Scheme momenta from canonical momenta p.
    fn momenta_from_p(&self, p: &[f64; N]) -> [f64; N];

    /// Canonical momenta p from scheme momenta.
    fn p_from_momenta(&self, momenta: &[f64; N]) -> [f64; N];
}

/// Under [`Differentiation::Auto`], runs of fewer steps use dual numbers: tracing and compiling take
/// about 1 ms for four coordinates (more for many), what compiled steps save over about two thousand.
pub(crate) const AUTO_MIN_STEPS: usize = 5000;

/// How a run evaluates its scheme's generating function: compiled native code or dual numbers.
pub(crate) enum StepDerivatives<const N: usize> {
    Compiled(Box<CompiledPair<N>>),
    Dual,
}

impl<const N: usize> StepDerivatives<N> {
    /// Compiles the derivatives of `scheme` when `choice` allows it, checking them against dual numbers
    /// at the first step's base and predictor. Under [`Differentiation::Auto`] a failure means dual
    /// numbers (the reason goes into the path); under [`Differentiation::Compiled`] it is an error.
    pub fn new(
        scheme: &impl Scheme<N>,
        choice: Differentiation,
        steps: usize,
        base: &[f64; N],
        z: &[f64; N],
    ) -> Result<(Self, DerivativePath), CompileError> {
        if choice == Differentiation::Dual {
            return Ok((Self::Dual, DerivativePath::Dual { reason: None }));
        }
        if choice == Differentiation::Auto && steps < AUTO_MIN_STEPS {
            let reason = format!("{steps} steps: compiling costs more than it saves below {AUTO_MIN_STEPS}");
            return Ok((Self::Dual, DerivativePath::Dual { reason: Some(reason) }));
        }
        let compiled = CompiledPair::new(|base, a, b| scheme.generating::<Traced, Traced>(base, a, b), base, z)
            .and_then(|c| {
                let dual = ad::mixed(&Generating { scheme, base }, &[0.0; N], z);
                let first = FirstDerivatives { value: dual.value, da: dual.da, db: dual.db };
                c.check_against(base, z, (first, dual.dadb), 1e-9).map(|()| c)
            });
        match (compiled, choice) {
            (Ok(c), _) => {
                let (residual, jacobian) = c.instructions;
                Ok((Self::Compiled(Box::new(c)), DerivativePath::Compiled { residual, jacobian }))
            }
            (Err(e), Differentiation::Auto) => Ok((Self::Dual, DerivativePath::Dual { reason: Some(e.to_string()) })),
            (Err(e), _) => Err(e),
        }
    }

    /// The generating function's value, first derivatives and, if `with_mixed`, mixed block at
    /// (`base`, 0, `z`).
    #[inline]
    pub fn first_or_mixed(
        &self,
        scheme: &impl Scheme<N>,
        base: &[f64; N],
        z: &SVector<f64, N>,
        with_mixed: bool,
    ) -> (FirstDerivatives<N>, Option<SMatrix<f64, N, N>>) {
        match self {
            Self::Compiled(c) => c.first_or_mixed(base, &(*z).into(), with_mixed),
            Self::Dual => ad::first_or_mixed(&Generating { scheme, base }, &[0.0; N], &(*z).into(), with_mixed),
        }
    }
}

/// A scheme's generating function at a fixed base, as a function of the two blocks.
struct Generating<'s, Sc, const N: usize> {
    scheme: &'s Sc,
    base: &'s [f64; N],
}

impl<Sc: Scheme<N>, const N: usize> PairFunction<N> for Generating<'_, Sc, N> {
    #[inline]
    fn eval<D: DualNum<Primitive = f64> + Copy>(&self, a: &[D; N], b: &[D; N]) -> D {
        self.scheme.generating(self.base, a, b)
    }
}

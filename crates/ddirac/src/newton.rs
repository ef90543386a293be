//! Newton's method for a square nonlinear system `r(z) = 0` with Jacobian `J(z)`.
//!
//! The solver knows no mechanics: a scheme hands it a closure that evaluates the residual, and the
//! Jacobian when asked, at a point; it returns the root together with the iteration count and the
//! residual norm, or a [`NewtonFailure`] saying why it stopped.
//!
//! [`solve_with`] runs either classical Newton (a fresh Jacobian at every iterate) or the chord
//! variant (the default): a factorized Jacobian is reused for later corrections, and by the next
//! solve ([`KeptJacobian`]), as long as each correction reduces the residual by [`CONTRACTION`];
//! otherwise it is re-evaluated where the correction started. Chord iterates converge linearly, so
//! after the first iterate that passes the test one more correction brings it to round-off, as a
//! classical step would; both stop on the same test. A residual without its Jacobian costs a
//! fraction of one with it (see `ad`), the more so the more coordinates.

use crate::dim::{Column, Dim, MatrixOf};
use crate::linalg::Factorization;

/// Tolerance and iteration limit of the Newton solver.
///
/// The solver takes at least one correction: the starting point (a predictor) is accepted only
/// after a correction from it passed the test, so a loose tolerance cannot accept a predictor far
/// from the root.
///
/// ```
/// let options = ddirac::NewtonOptions { tolerance: 1e-10, ..Default::default() };
/// assert_eq!(options.max_iterations, 50);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Convergence threshold. The iteration stops when `‖r‖∞ ≤ tolerance · max(residual_scale, 1)`
    /// (the floor 1 lowered to ‖J‖ (1 + ‖z‖∞) for a system whose Jacobian is that small, see
    /// [`NewtonOptions::threshold_at`]) or when the last correction satisfies
    /// `‖δz‖∞ ≤ tolerance · (1 + ‖z‖∞)`.
    pub tolerance: f64,
    /// Largest number of Newton corrections before the step is declared failed.
    pub max_iterations: usize,
    /// Evaluate the Jacobian once per solve and reuse it while the residual contracts (chord
    /// Newton); `false` evaluates it at every iterate (classical Newton).
    pub reuse_jacobian: bool,
}

impl NewtonOptions {
    /// The residual test's threshold `tolerance · max(residual_scale, 1)`.
    pub fn threshold(&self, residual_scale: f64) -> f64 {
        self.tolerance * residual_scale.max(1.0)
    }

    /// The residual test's threshold where the Jacobian's largest entry ‖J‖ is known, at the
    /// iterate z: `tolerance · max(residual_scale, min(1, ‖J‖ (1 + ‖z‖∞)))`. The floor 1 of
    /// [`NewtonOptions::threshold`] is an absolute size of the residual (a momentum); for a system
    /// of tiny scale (an electron's mass in SI units gives ‖J‖ ≈ 10⁻²⁸) every residual is below it,
    /// so the floor follows the residual that a correction of relative size 1 would remove.
    ///
    /// ```
    /// let options = ddirac::NewtonOptions::default();
    /// assert_eq!(options.threshold_at(0.0, Some(50.0), 1.0), options.threshold(0.0));
    /// assert_eq!(options.threshold_at(0.0, Some(5e-29), 1.0), 1e-12 * 1e-28);
    /// ```
    pub fn threshold_at(&self, residual_scale: f64, jacobian_scale: Option<f64>, z_scale: f64) -> f64 {
        let floor = jacobian_scale.map_or(1.0, |j| (j * (1.0 + z_scale)).min(1.0));
        self.tolerance * residual_scale.max(floor)
    }
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50, reuse_jacobian: true }
    }
}

/// Keep Jacobians across solves when one costs at least this many residuals.
pub const ACROSS_SOLVES: usize = 7;

/// A reused Jacobian is replaced when a correction reduces ‖r‖∞ by less than this factor.
pub const CONTRACTION: f64 = 0.25;

/// What the solver reports on success.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonStats {
    /// Number of Newton corrections (linear solves) taken.
    pub iterations: usize,
    /// `‖r‖∞` at the accepted point.
    pub residual: f64,
    /// Number of Jacobians evaluated and factorized.
    pub jacobians: usize,
}

/// Why the solver stopped without a root.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureReason {
    /// The iteration limit was reached.
    NotConverged,
    /// The Jacobian could not be factorized.
    SingularJacobian,
    /// The residual or the Jacobian contained NaN or infinity.
    NonFinite,
}

impl std::fmt::Display for FailureReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FailureReason::NotConverged => "no convergence within the iteration limit",
            FailureReason::SingularJacobian => "the Jacobian is singular",
            FailureReason::NonFinite => "a non-finite value appeared in the residual or Jacobian",
        })
    }
}

/// A failed solve: the reason, the corrections taken and the last residual norm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonFailure {
    /// Why the iteration stopped.
    pub reason: FailureReason,
    /// Corrections taken before stopping.
    pub iterations: usize,
    /// `‖r‖∞` at the last evaluated point (NaN if it was not finite).
    pub residual: f64,
}

/// Solves `r(z) = 0` by classical Newton starting from `z`, which holds the root on success.
///
/// `eval(z)` returns the residual and its Jacobian. `residual_scale` sets the units of the residual
/// test (see [`NewtonOptions::tolerance`]). `z` is an `SVector<f64, N>` or a `DVector<f64>`
/// ([`Column`]).
///
/// ```
/// use nalgebra::{SMatrix, SVector};
/// // z² = 2
/// let mut z = SVector::<f64, 1>::new(1.0);
/// let stats = ddirac::newton::solve(&mut z, 1.0, &Default::default(), |z| {
///     (SVector::<f64, 1>::new(z[0] * z[0] - 2.0), SMatrix::<f64, 1, 1>::new(2.0 * z[0]))
/// })
/// .unwrap();
/// assert!((z[0] - 2f64.sqrt()).abs() < 1e-14);
/// assert!(stats.iterations <= 6);
/// ```
pub fn solve<V: Column>(
    z: &mut V,
    residual_scale: f64,
    options: &NewtonOptions,
    mut eval: impl FnMut(&V) -> (V, MatrixOf<V>),
) -> Result<NewtonStats, NewtonFailure> {
    let options = NewtonOptions { reuse_jacobian: false, ..*options };
    let mut kept = KeptJacobian::new(z.dim());
    solve_with(z, residual_scale, &options, &mut kept, |z, _| {
        let (r, j) = eval(z);
        (r, Some(j))
    })
}

/// The factorized Jacobian a chord solve leaves for the next one, with how well it served.
#[derive(Debug, Clone)]
pub struct KeptJacobian<Dm: Dim> {
    /// The storage of the factorization, once there is one.
    lu: Option<Factorization<Dm>>,
    /// Whether `lu` holds the factorized Jacobian of the last solve (else only storage to reuse).
    usable: bool,
    corrections: usize,
    relative_cost: usize,
    /// The vectors of a solve, kept so that a solve allocates nothing.
    work: Option<Work<Dm>>,
}

/// The vectors a chord solve works in.
#[derive(Debug, Clone)]
struct Work<Dm: Dim> {
    /// The correction δz.
    delta: Dm::Vector,
    /// z before the correction, to undo it.
    previous: Dm::Vector,
    /// The substitutions' scratch.
    y: Dm::Array<f64>,
}

impl<Dm: Dim> Work<Dm> {
    fn new(dim: Dm) -> Self {
        Self { delta: dim.zeros(), previous: dim.zeros(), y: dim.array(|_| 0.0) }
    }
}

/// `to` = `from`, entry by entry (no allocation).
fn copy<Dm: Dim>(dim: Dm, from: &Dm::Vector, to: &mut Dm::Vector) {
    for i in 0..dim.n() {
        to[i] = from[i];
    }
}

/// The cost of a Jacobian in residuals when both come from dual numbers for `n` unknowns, estimated
/// by the flop counts of a product of the dual numbers that compute them: (3n² + 4n + 1) / (4n + 1)
/// (see `ad`).
///
/// ```
/// assert_eq!(ddirac::newton::dual_relative_cost(8), 6);
/// assert_eq!(ddirac::newton::dual_relative_cost(9), 7);
/// ```
pub fn dual_relative_cost(n: usize) -> usize {
    (3 * n * n + 4 * n + 1) / (4 * n + 1)
}

/// The cost of a Jacobian in residuals for `n` unknowns when both are compiled programs of
/// `residual` and `jacobian` instructions: the program and a factorization (about 15 n³
/// instructions, measured for n = 4) against the program and a solve (about 10 n²).
///
/// ```
/// // (400 + 15 · 4³) / (100 + 10 · 4²) = 1360 / 260
/// assert_eq!(ddirac::newton::compiled_relative_cost(4, 100, 400), 5);
/// ```
pub fn compiled_relative_cost(n: usize, residual: usize, jacobian: usize) -> usize {
    (jacobian + 15 * n * n * n) / (residual + 10 * n * n).max(1)
}

impl<Dm: Dim> KeptJacobian<Dm> {
    /// Nothing kept yet for `dim` unknowns; a Jacobian costs what [`dual_relative_cost`] says.
    pub fn new(dim: Dm) -> Self {
        Self::with_relative_cost(dual_relative_cost(dim.n()))
    }

    /// Nothing kept yet; a Jacobian with its factorization costs `relative_cost` residuals with their
    /// solve.
    pub fn with_relative_cost(relative_cost: usize) -> Self {
        Self { lu: None, usable: false, corrections: 0, relative_cost, work: None }
    }

    /// Factorizes the Jacobian `j` of `dim` unknowns into the storage kept (allocated the first time).
    fn factorize(&mut self, dim: Dm, j: &Dm::Matrix) {
        self.usable = match &mut self.lu {
            Some(lu) => lu.refactor(j, 1e-14),
            None => {
                self.lu = Factorization::new(dim, j, 1e-14);
                self.lu.is_some()
            }
        };
    }

    /// The factorized Jacobian, if one is held.
    fn current(&self) -> Option<&Factorization<Dm>> {
        self.lu.as_ref().filter(|_| self.usable)
    }

    /// Whether a Jacobian is kept from one solve to the next at all: when it costs at least
    /// [`ACROSS_SOLVES`] residuals (n ≥ 9 with dual numbers). Below, a fresh Jacobian at the start of
    /// each solve costs about as much as the extra chord corrections it saves, and gives iterates
    /// closer to classical Newton's.
    pub fn across_solves(&self) -> bool {
        self.relative_cost >= ACROSS_SOLVES
    }

    /// A kept Jacobian starts the next solve while the previous one needed at most this many
    /// corrections: two plus the relative cost.
    pub fn budget(&self) -> usize {
        2 + self.relative_cost
    }
}

/// Solves `r(z) = 0` starting from `z`, which holds the root on success, by classical or chord
/// Newton ([`NewtonOptions::reuse_jacobian`]).
///
/// `eval(z, with_jacobian)` returns the residual, and the Jacobian when `with_jacobian` is true.
/// The last call is always at the returned root. `residual_scale` sets the units of the residual
/// test (see [`NewtonOptions::tolerance`]). With chord Newton and many unknowns
/// ([`KeptJacobian::across_solves`]), `kept` carries the factorized Jacobian from one solve to the
/// next (the steps of a run): a solve starts from it while the previous solve needed at most
/// [`KeptJacobian::budget`] corrections, and from a fresh one otherwise.
///
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use ddirac::{dim::Fixed, newton::{solve_with, KeptJacobian}};
/// // z³ = 2 from z = 1.2: one Jacobian serves every correction.
/// let (mut z, mut kept) = (SVector::<f64, 1>::new(1.2), KeptJacobian::new(Fixed));
/// let stats = solve_with(&mut z, 1.0, &Default::default(), &mut kept, |z, with_jacobian| {
///     let r = SVector::<f64, 1>::new(z[0].powi(3) - 2.0);
///     (r, with_jacobian.then(|| SMatrix::<f64, 1, 1>::new(3.0 * z[0] * z[0])))
/// })
/// .unwrap();
/// assert!((z[0] - 2f64.cbrt()).abs() < 1e-14);
/// assert_eq!(stats.jacobians, 1);
/// assert!(stats.iterations > 2);
/// ```
pub fn solve_with<V: Column>(
    z: &mut V,
    residual_scale: f64,
    options: &NewtonOptions,
    kept: &mut KeptJacobian<V::Dim>,
    eval: impl FnMut(&V, bool) -> (V, Option<MatrixOf<V>>),
) -> Result<NewtonStats, NewtonFailure> {
    solve_in(z.dim(), z, residual_scale, options, kept, eval)
}

/// [`solve_with`] for unknowns of the dimension `dim` (for callers generic over the dimension).
pub(crate) fn solve_in<Dm: Dim>(
    dim: Dm,
    z: &mut Dm::Vector,
    residual_scale: f64,
    options: &NewtonOptions,
    kept: &mut KeptJacobian<Dm>,
    eval: impl FnMut(&Dm::Vector, bool) -> (Dm::Vector, Option<Dm::Matrix>),
) -> Result<NewtonStats, NewtonFailure> {
    let reuse = options.reuse_jacobian && kept.across_solves() && kept.usable && kept.corrections <= kept.budget();
    if !reuse {
        kept.usable = false;
    }
    let mut work = kept.work.take().unwrap_or_else(|| Work::new(dim));
    let result = chord(dim, z, residual_scale, options, kept, &mut work, eval);
    kept.work = Some(work);
    match &result {
        Ok(stats) => kept.corrections = stats.iterations,
        Err(_) => kept.usable = false,
    }
    result
}

fn chord<Dm: Dim>(
    dim: Dm,
    z: &mut Dm::Vector,
    residual_scale: f64,
    options: &NewtonOptions,
    kept: &mut KeptJacobian<Dm>,
    work: &mut Work<Dm>,
    mut eval: impl FnMut(&Dm::Vector, bool) -> (Dm::Vector, Option<Dm::Matrix>),
) -> Result<NewtonStats, NewtonFailure> {
    let (mut iterations, mut jacobians) = (0, 0);
    let mut evaluate = |kept: &mut KeptJacobian<Dm>, z: &Dm::Vector, with_jacobian: bool, iterations| {
        let (r, jac) = eval(z, with_jacobian);
        let residual = Dm::amax(&r);
        let finite =
            residual.is_finite() && jac.as_ref().is_none_or(|j| Dm::matrix_entries(j).iter().all(|x| x.is_finite()));
        if !finite {
            let residual = if residual.is_finite() { residual } else { f64::NAN };
            return Err(NewtonFailure { reason: FailureReason::NonFinite, iterations, residual });
        }
        if let Some(j) = jac {
            kept.factorize(dim, &j);
        }
        Ok((r, residual))
    };
    let mut fresh = kept.current().is_none();
    let (mut r, mut residual) = evaluate(kept, z, fresh, iterations)?;
    jacobians += usize::from(fresh);
    let threshold = options.threshold_at(residual_scale, kept.current().map(Factorization::scale), Dm::amax(z));
    let mut small_correction = false;
    // Whether the last correction used a reused Jacobian, and whether it was the final polish.
    let (mut stale, mut polished) = (false, false);
    loop {
        if residual <= threshold || small_correction {
            // The first iterate to pass the test may be only just within it: the starting point
            // itself (a predictor whose residual is small only because the tolerance is loose), after
            // a reused Jacobian (linear convergence), or after a fresh one from a good predictor when
            // the correction was not yet tiny. One more correction brings it to round-off, as the
            // overshoot of a second classical Newton step would: a root is never the starting point
            // unchecked by a correction.
            let settled = iterations > 0 && !stale && small_correction;
            if settled || polished || iterations >= options.max_iterations {
                return Ok(NewtonStats { iterations, residual, jacobians });
            }
            polished = true;
        }
        if iterations >= options.max_iterations {
            return Err(NewtonFailure { reason: FailureReason::NotConverged, iterations, residual });
        }
        let solved = match kept.current().filter(|lu| lu.is_regular()) {
            Some(lu) => {
                lu.solve_into(&r, &mut work.y, &mut work.delta);
                Dm::entries(&work.delta).iter().all(|x| x.is_finite())
            }
            None => false,
        };
        if !solved {
            if fresh {
                return Err(NewtonFailure { reason: FailureReason::SingularJacobian, iterations, residual });
            }
            // The reused Jacobian does not fit here: evaluate one at this iterate and retry.
            (r, residual) = evaluate(kept, z, true, iterations)?;
            (fresh, jacobians) = (true, jacobians + 1);
            continue;
        }
        copy(dim, z, &mut work.previous);
        let previous = residual;
        *z -= &work.delta;
        iterations += 1;
        small_correction = Dm::amax(&work.delta) <= options.tolerance * (1.0 + Dm::amax(z));
        stale = !fresh;
        fresh = !options.reuse_jacobian;
        let trial = evaluate(kept, z, fresh, iterations);
        jacobians += usize::from(fresh);
        let contracted = matches!(trial, Ok((_, res)) if res <= threshold || res <= CONTRACTION * previous);
        if stale && !contracted && !polished {
            // A reused Jacobian that does not contract the residual (or leads out of the domain):
            // undo the correction and evaluate the Jacobian where it started.
            copy(dim, &work.previous, z);
            (r, residual) = evaluate(kept, z, true, iterations)?;
            (fresh, jacobians, small_correction) = (true, jacobians + 1, false);
            continue;
        }
        (r, residual) = trial?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{SMatrix, SVector};

    #[test]
    fn quadratic_convergence_on_a_2d_system() {
        // x² + y² = 4, x = y  →  x = y = √2
        let mut z = SVector::<f64, 2>::new(1.0, 2.0);
        let stats = solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
            let r = SVector::<f64, 2>::new(z[0] * z[0] + z[1] * z[1] - 4.0, z[0] - z[1]);
            let j = SMatrix::<f64, 2, 2>::new(2.0 * z[0], 2.0 * z[1], 1.0, -1.0);
            (r, j)
        })
        .unwrap();
        assert!((z[0] - 2f64.sqrt()).abs() < 1e-14 && (z[1] - 2f64.sqrt()).abs() < 1e-14);
        assert!(stats.iterations <= 6, "{stats:?}");
    }

    #[test]
    fn singular_jacobian_is_reported() {
        let mut z = SVector::<f64, 1>::new(0.0);
        let err = solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
            (SVector::<f64, 1>::new(z[0] * z[0] + 1.0), SMatrix::<f64, 1, 1>::new(2.0 * z[0]))
        })
        .unwrap_err();
        assert_eq!(err.reason, FailureReason::SingularJacobian);
    }

    #[test]
    fn no_root_hits_the_iteration_limit() {
        let mut z = SVector::<f64, 1>::new(0.3);
        let options = NewtonOptions { max_iterations: 7, ..Default::default() };
        let err = solve(&mut z, 1.0, &options, |z| {
            (SVector::<f64, 1>::new(z[0] * z[0] + 1.0), SMatrix::<f64, 1, 1>::new(2.0 * z[0]))
        })
        .unwrap_err();
        assert_eq!(err.reason, FailureReason::NotConverged);
        assert_eq!(err.iterations, 7);
    }

    #[test]
    fn nan_is_caught() {
        let mut z = SVector::<f64, 1>::new(-1.0);
        let err = solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
            (SVector::<f64, 1>::new(z[0].sqrt()), SMatrix::<f64, 1, 1>::new(1.0))
        })
        .unwrap_err();
        assert_eq!(err.reason, FailureReason::NonFinite);
    }

    /// The same chord solves in a fixed and in a dynamic dimension, with one `KeptJacobian` each
    /// carried across them (its storage reused): the same iterates, statistics and roots, bit for bit.
    #[test]
    fn chord_solves_keep_their_storage_and_agree_across_dimensions() {
        use crate::dim::{Dynamic, Fixed};
        use nalgebra::{DMatrix, DVector};
        // r_i = z_i³ + 0.5 z_{i+1} − c_i: a Jacobian that changes along the iterates.
        fn r(z: &[f64], c: f64) -> Vec<f64> {
            (0..z.len()).map(|i| z[i].powi(3) + 0.5 * z[(i + 1) % z.len()] - c * (i as f64 + 1.0)).collect()
        }
        fn j(z: &[f64]) -> Vec<f64> {
            let n = z.len();
            let mut m = vec![0.0; n * n];
            for i in 0..n {
                m[i + n * i] += 3.0 * z[i] * z[i];
                m[i + n * ((i + 1) % n)] += 0.5;
            }
            m
        }
        let options = NewtonOptions::default();
        let mut fixed_kept = KeptJacobian::with_relative_cost(ACROSS_SOLVES);
        let mut dynamic_kept = KeptJacobian::with_relative_cost(ACROSS_SOLVES);
        let (mut zf, mut zd) = (SVector::<f64, 3>::new(1.0, 1.1, 1.2), DVector::from_column_slice(&[1.0, 1.1, 1.2]));
        for c in [1.0, 1.05, 1.1, 3.0, 3.02] {
            let fixed = solve_in(Fixed::<3>, &mut zf, 1.0, &options, &mut fixed_kept, |z, with| {
                (
                    SVector::from_column_slice(&r(z.as_slice(), c)),
                    with.then(|| SMatrix::from_column_slice(&j(z.as_slice()))),
                )
            })
            .unwrap();
            let dynamic = solve_in(Dynamic(3), &mut zd, 1.0, &options, &mut dynamic_kept, |z, with| {
                (DVector::from_vec(r(z.as_slice(), c)), with.then(|| DMatrix::from_vec(3, 3, j(z.as_slice()))))
            })
            .unwrap();
            assert_eq!(fixed, dynamic, "c = {c}");
            assert_eq!(zf.as_slice(), zd.as_slice(), "c = {c}");
            assert!(r(zd.as_slice(), c).iter().all(|x| x.abs() < 1e-12), "c = {c}");
        }
        assert!(dynamic_kept.work.is_some() && fixed_kept.work.is_some());
        assert!(dynamic_kept.current().is_some());
    }
}

//! Newton's method for a square nonlinear system `r(z) = 0` with Jacobian `J(z)`.
//!
//! The solver knows no mechanics: a scheme hands it a closure that evaluates the residual and the
//! Jacobian at a point, and it returns the root together with the iteration count and the residual
//! norm, or a [`NewtonFailure`] saying why it stopped.

use nalgebra::{SMatrix, SVector};

/// Tolerance and iteration limit of the Newton solver.
///
/// ```
/// let options = ddirac::NewtonOptions { tolerance: 1e-10, ..Default::default() };
/// assert_eq!(options.max_iterations, 50);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Convergence threshold. The iteration stops when `‖r‖∞ ≤ tolerance · residual_scale` or when
    /// the last correction satisfies `‖δz‖∞ ≤ tolerance · (1 + ‖z‖∞)`.
    pub tolerance: f64,
    /// Largest number of Newton corrections before the step is declared failed.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50 }
    }
}

/// What the solver reports on success.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonStats {
    /// Number of Newton corrections (linear solves) taken.
    pub iterations: usize,
    /// `‖r‖∞` at the accepted point.
    pub residual: f64,
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

impl FailureReason {
    /// What a user can try about it.
    pub fn hint(self) -> &'static str {
        match self {
            FailureReason::NotConverged => "try a smaller step, a looser tolerance or more iterations",
            FailureReason::SingularJacobian => {
                "the step equations are degenerate here: for a reduced run check that the Lagrangian is \
                 invariant (`ddirac check`); otherwise try a smaller step"
            }
            FailureReason::NonFinite => "try a smaller step; check the Lagrangian for singular points",
        }
    }
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

/// Solves `r(z) = 0` starting from `z`, which holds the root on success.
///
/// `eval(z)` returns the residual and its Jacobian. `residual_scale` sets the units of the residual
/// test (see [`NewtonOptions::tolerance`]).
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
pub fn solve<const N: usize>(
    z: &mut SVector<f64, N>,
    residual_scale: f64,
    options: &NewtonOptions,
    mut eval: impl FnMut(&SVector<f64, N>) -> (SVector<f64, N>, SMatrix<f64, N, N>),
) -> Result<NewtonStats, NewtonFailure> {
    let threshold = options.tolerance * residual_scale.max(1.0);
    let mut iterations = 0;
    let mut small_correction = false;
    loop {
        let (r, jac) = eval(z);
        let residual = r.amax();
        if !residual.is_finite() || jac.iter().any(|x| !x.is_finite()) {
            let residual = if residual.is_finite() { residual } else { f64::NAN };
            return Err(NewtonFailure { reason: FailureReason::NonFinite, iterations, residual });
        }
        if residual <= threshold || small_correction {
            return Ok(NewtonStats { iterations, residual });
        }
        if iterations >= options.max_iterations {
            return Err(NewtonFailure { reason: FailureReason::NotConverged, iterations, residual });
        }
        let delta = crate::linalg::solve(jac, r, 1e-14)
            .filter(|(d, rank)| *rank == N && d.iter().all(|x| x.is_finite()))
            .map(|(d, _)| d);
        let Some(delta) = delta else {
            return Err(NewtonFailure { reason: FailureReason::SingularJacobian, iterations, residual });
        };
        *z -= delta;
        iterations += 1;
        small_correction = delta.amax() <= options.tolerance * (1.0 + z.amax());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}

//! Checks a problem before running it, without integrating: the invariance of L_d (the hypothesis
//! of reduction, paper §4), the connection axioms (Definition 2.1), the regularity of the Legendre
//! transform and whether the initial momentum lies on the primary constraint p = ∂L/∂v.

use crate::integrator::Setup;
use crate::mechanics::legendre;
use crate::reduction::invariance::{invariance_deviations, INVARIANCE_TOLERANCE};
use crate::{DiscreteLagrangian, Error, InitialMomentum, Method, Problem, System};

/// Relative tolerance of the primary-constraint check.
pub const CONSTRAINT_TOLERANCE: f64 = 1e-8;

/// The findings of [`check`].
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// For each group coordinate, the largest relative change of L_d under its translation.
    pub invariance: Vec<(String, f64)>,
    /// The tolerance the invariance deviations are compared with.
    pub invariance_tolerance: f64,
    /// The connection axioms hold (errors are returned by [`check`] itself).
    pub connection_axioms: bool,
    /// Rank of ∂²L/∂v² at (q0, v0); the Legendre transform is regular when it equals the number of
    /// coordinates.
    pub legendre_rank: usize,
    /// Number of coordinates.
    pub coordinates: usize,
    /// ‖∂L/∂v(q0, v0) − p0‖∞ for the velocity v0 that fits p0 best.
    pub constraint_mismatch: f64,
    /// Whether the initial momentum was given as a velocity (then it is consistent by construction).
    pub momentum_from_velocity: bool,
}

impl CheckReport {
    /// Whether L_d is invariant under every group translation.
    pub fn invariant(&self) -> bool {
        self.invariance.iter().all(|(_, d)| *d <= self.invariance_tolerance)
    }

    /// Whether the Legendre transform is regular (L non-degenerate).
    pub fn regular(&self) -> bool {
        self.legendre_rank == self.coordinates
    }

    /// Whether p0 satisfies the primary constraint p = ∂L/∂v to [`CONSTRAINT_TOLERANCE`] (relative).
    pub fn momentum_consistent(&self, p0_scale: f64) -> bool {
        self.constraint_mismatch <= CONSTRAINT_TOLERANCE * (1.0 + p0_scale)
    }
}

/// Checks `problem` and `method` for `system` without integrating.
///
/// Returns an error for input that [`crate::integrate`] would refuse outright (sizes, non-finite
/// values, a connection of the wrong shape); findings that only matter for some methods (a
/// non-invariant L_d, a degenerate Lagrangian, an inconsistent p0) are reported, not refused.
///
/// ```
/// use ddirac::{check, Method, systems::ChargedParticle};
/// let report = check(&ChargedParticle::default(), &ChargedParticle::paper_problem(100), &Method::default()).unwrap();
/// assert!(report.invariant() && report.regular());
/// assert!(report.constraint_mismatch < 1e-12);
/// ```
pub fn check<S: System<N>, const N: usize>(
    system: &S,
    problem: &Problem,
    method: &Method,
) -> Result<CheckReport, Error> {
    let setup = Setup::new(system, problem, method)?;
    let ld = DiscreteLagrangian::new(system, method.rule, problem.step);
    let names = system.coordinates();
    let invariance = invariance_deviations(&ld, &setup.split, &setup.q0, &setup.dq0)
        .into_iter()
        .map(|(j, d)| (names[j].name.clone(), d))
        .collect();
    let (v0, constraint_mismatch) = legendre::velocity(system, &setup.q0, &setup.p0);
    Ok(CheckReport {
        invariance,
        invariance_tolerance: INVARIANCE_TOLERANCE,
        connection_axioms: true,
        legendre_rank: legendre::rank(system, &setup.q0, &v0),
        coordinates: N,
        constraint_mismatch,
        momentum_from_velocity: matches!(problem.initial, InitialMomentum::Velocity(_)),
    })
}

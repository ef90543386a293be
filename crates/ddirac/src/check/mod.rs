//! The hypotheses of a run, tested before its first step without integrating: the invariance of L_d
//! (the hypothesis of reduction, paper §4), the 2π-periodicity of L in its angles (charts on S¹,
//! §6), the connection axioms (Definition 2.1), the regularity of the Legendre transform and whether
//! the initial momentum lies on the primary constraint p = ∂L/∂v.
//!
//! With an atlas, each chart is tested too ([`charts`]): its maps inverse on its domain, its quality
//! honest about where its Legendre map is regular, its group coordinates symmetries and its angles
//! periods of L.
//!
//! [`check`] reports the findings; [`CheckReport::verdict`] says what a run of a method makes of
//! them. [`crate::Stepper::new`] calls the same tests and verdicts before its first step, so a run
//! refuses exactly what the check refuses, with the same error.

mod charts;

use crate::diagnostics::{Warning, WarningKind};
use crate::dim::Dim;
use crate::mechanics::lagrangian::{Borrowed, SystemIn};
use crate::mechanics::legendre;
use crate::periodicity::{periodicity_deviations, PERIODICITY_TOLERANCE};
use crate::reduction::invariance::{invariance_deviations, INVARIANCE_TOLERANCE};
use crate::sampling::{self, Deviation, ENOUGH};
use crate::setup::Setup;
use crate::{DiscreteLagrangian, Error, Hypothesis, InitialMomentum, Method, Problem};

pub(crate) use charts::atlas_verdict;
pub use charts::{ChartFinding, ROUND_TRIP_TOLERANCE};

/// Relative tolerance of the primary-constraint check.
pub const CONSTRAINT_TOLERANCE: f64 = 1e-8;

/// The test of one hypothesis on one coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// The coordinate's name.
    pub coordinate: String,
    /// The largest relative deviation over the sampled pairs.
    pub deviation: f64,
    /// How many pairs near the initial data had a finite L_d (a verdict needs [`ENOUGH`]).
    pub samples: usize,
}

impl Finding {
    fn new(names: &[crate::Coordinate], d: Deviation) -> Self {
        Self { coordinate: names[d.coordinate].name.clone(), deviation: d.deviation, samples: d.samples }
    }

    /// Whether enough pairs had a finite L_d for a verdict.
    pub fn decided(&self) -> bool {
        self.samples >= ENOUGH
    }

    /// Whether the test was decided and passed with `tolerance`.
    pub fn holds(&self, tolerance: f64) -> bool {
        self.decided() && self.deviation <= tolerance
    }

    /// Whether the test was decided and failed with `tolerance`.
    pub fn fails(&self, tolerance: f64) -> bool {
        self.decided() && !self.holds(tolerance)
    }
}

/// The findings of [`check`].
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// For each group coordinate, the invariance of L_d under its translation.
    pub invariance: Vec<Finding>,
    /// The tolerance the invariance deviations are compared with.
    pub invariance_tolerance: f64,
    /// For each angle coordinate, the 2π-periodicity of L_d in it.
    pub periodicity: Vec<Finding>,
    /// The tolerance the periodicity deviations are compared with.
    pub periodicity_tolerance: f64,
    /// The connection axioms hold (errors are returned by [`check`] itself).
    pub connection_axioms: bool,
    /// Rank of ∂²L/∂v² at (q0, v0); the Legendre transform is regular when it equals the number of
    /// coordinates.
    pub legendre_rank: usize,
    /// Number of coordinates.
    pub coordinates: usize,
    /// ‖∂L/∂v(q0, v0) − p0‖∞ for the velocity v0 that fits p0 best.
    pub constraint_mismatch: f64,
    /// ‖p0‖∞, the scale of the mismatch.
    pub p0_scale: f64,
    /// Whether the initial momentum was given as a velocity (then it is consistent by construction).
    pub momentum_from_velocity: bool,
    /// The tests of each chart of the atlas after the main one (empty without an atlas).
    pub charts: Vec<ChartFinding>,
}

impl CheckReport {
    /// Whether L_d is invariant under every group translation (decided on enough samples).
    pub fn invariant(&self) -> bool {
        self.invariance.iter().all(|f| f.holds(self.invariance_tolerance))
    }

    /// Whether L_d is 2π-periodic in every angle coordinate (decided on enough samples).
    pub fn periodic(&self) -> bool {
        self.periodicity.iter().all(|f| f.holds(self.periodicity_tolerance))
    }

    /// Whether the Legendre transform is regular (L non-degenerate).
    pub fn regular(&self) -> bool {
        self.legendre_rank == self.coordinates
    }

    /// Whether p0 satisfies the primary constraint p = ∂L/∂v to [`CONSTRAINT_TOLERANCE`] (relative to
    /// 1 + ‖p0‖∞); always when p0 came from velocities.
    pub fn momentum_consistent(&self) -> bool {
        self.momentum_from_velocity || self.constraint_mismatch <= CONSTRAINT_TOLERANCE * (1.0 + self.p0_scale)
    }

    /// What a run of `method` makes of these findings: the error that refuses it, or the warnings it
    /// runs with.
    ///
    /// Refused: an angle in which L is not 2π-periodic (or where that could not be tested); a reduced
    /// method without group coordinates, or with an L_d that is not invariant or whose invariance
    /// could not be tested (unless `method.check_invariance` is off: then the run goes on with a
    /// warning); a degenerate Lagrangian with p0 off the primary constraint.
    pub fn verdict(&self, method: &Method) -> Result<Vec<Warning>, Error> {
        let mut warnings = vec![];
        for f in &self.periodicity {
            if f.fails(self.periodicity_tolerance) {
                return Err(Error::NotPeriodic {
                    coordinate: f.coordinate.clone(),
                    deviation: f.deviation,
                    tolerance: self.periodicity_tolerance,
                });
            }
            if !f.decided() {
                return Err(self.undecided(&f.coordinate, Hypothesis::Periodicity));
            }
        }
        if method.reduced {
            if self.invariance.is_empty() {
                return Err(Error::NoSymmetry);
            }
            for f in &self.invariance {
                let error = if f.fails(self.invariance_tolerance) {
                    Error::NotInvariant {
                        coordinate: f.coordinate.clone(),
                        deviation: f.deviation,
                        tolerance: self.invariance_tolerance,
                    }
                } else if !f.decided() {
                    self.undecided(&f.coordinate, Hypothesis::Invariance)
                } else {
                    continue;
                };
                if method.check_invariance {
                    return Err(error);
                }
                let (kind, consequence) = match error {
                    Error::NotInvariant { .. } => (WarningKind::NotInvariant, "is not conserved"),
                    _ => (WarningKind::InvarianceUndecided, "may not be conserved"),
                };
                let message = format!(
                    "reducing although {error}, because `check_invariance` is off: the reduced equations hold μ \
                     constant although the true momentum map {consequence}, so the trajectory and its momentum-map \
                     drift (zero by construction) may not describe this Lagrangian"
                );
                warnings.push(Warning::new(kind, None, message));
            }
        }
        if !self.regular() && !self.momentum_consistent() {
            return Err(Error::OffPrimaryConstraint {
                rank: self.legendre_rank,
                coordinates: self.coordinates,
                mismatch: self.constraint_mismatch,
            });
        }
        charts::verdict(&self.charts, method, &mut warnings)?;
        Ok(warnings)
    }

    fn undecided(&self, coordinate: &str, hypothesis: Hypothesis) -> Error {
        Error::Undecided {
            hypothesis,
            coordinate: coordinate.to_owned(),
            samples: self.invariance.iter().chain(&self.periodicity).map(|f| f.samples).min().unwrap_or(0),
            wanted: sampling::WANTED,
        }
    }
}

/// Checks `problem` and `method` for `system` without integrating.
///
/// Returns an error for input that [`crate::integrate`] would refuse outright (sizes, non-finite
/// values, a connection of the wrong shape); the findings that depend on the method are judged by
/// [`CheckReport::verdict`].
///
/// ```
/// use ddirac::{check, Method, systems::ChargedParticle};
/// let report = check(&ChargedParticle::default(), &ChargedParticle::paper_problem(100), &Method::default()).unwrap();
/// assert!(report.invariant() && report.regular() && report.periodic());
/// assert!(report.constraint_mismatch < 1e-12);
/// ```
pub fn check<S: SystemIn<Dm>, Dm: Dim>(system: &S, problem: &Problem, method: &Method) -> Result<CheckReport, Error> {
    crate::stack::enough(system.dim(), || {
        let setup = Setup::new(system, problem, method)?;
        let mut report = findings(system, problem, method, &setup);
        report.charts = charts::chart_findings(system, problem, method.rule, charts::main_regular(system, problem));
        Ok(report)
    })
}

/// The findings of [`check`] for a run already set up.
pub(crate) fn findings<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    problem: &Problem,
    method: &Method,
    setup: &Setup<Dm>,
) -> CheckReport {
    let dim = system.dim();
    let ld = DiscreteLagrangian::new(Borrowed(system), method.rule, problem.step);
    let names = system.coordinates();
    let samples = sampling::near(&ld, &setup.q0, &setup.dq0);
    let invariance = invariance_deviations(&ld, &setup.split, &samples)
        .into_iter()
        .map(|d| Finding::new(names.as_ref(), d))
        .collect();
    let periodicity =
        periodicity_deviations(&ld, &samples).into_iter().map(|d| Finding::new(names.as_ref(), d)).collect();
    let (v0, constraint_mismatch) = legendre::velocity_in(dim, system, &setup.q0, &setup.p0);
    CheckReport {
        invariance,
        invariance_tolerance: INVARIANCE_TOLERANCE,
        periodicity,
        periodicity_tolerance: PERIODICITY_TOLERANCE,
        connection_axioms: true,
        legendre_rank: legendre::rank_in(dim, system, &setup.q0, &v0),
        coordinates: dim.n(),
        constraint_mismatch,
        p0_scale: setup.p0.as_ref().iter().fold(0.0f64, |m, v| m.max(v.abs())),
        momentum_from_velocity: matches!(problem.initial, InitialMomentum::Velocity(_)),
        charts: vec![],
    }
}

//! The hypotheses of a run's atlas (paper §6: "a compatible chart" is one whose maps φ to the main
//! chart and ψ = φ⁻¹ from it are inverse diffeomorphisms on its domain): tested for each chart on
//! points sampled over its domain, as a run relies on them wherever it goes.
//!
//! - its maps are inverse: ψ(φ(q')) = q' to [`ROUND_TRIP_TOLERANCE`] (relative) at every sampled
//!   point q' of the chart (angles up to whole turns);
//! - its quality does not claim a singular chart: where it is at least [`BLEND_FROM`] (where the
//!   chart has weight in the run's glued discrete Lagrangian, [`crate::blend`]), ∂²L/∂v² of the
//!   Lagrangian in the chart has full rank, when the main chart's has at the initial data;
//! - its group coordinates are symmetries of L in the chart (the invariance test of a reduced run,
//!   [`crate::reduction::invariance`]) and its angles periods of it ([`crate::periodicity`]), on pairs
//!   near its best sampled point.
//!
//! The points: main-chart points whose angles are drawn over a whole turn and whose other coordinates
//! within (1 + |q0|)/2 of the initial configuration, taken into the chart by ψ; those where the
//! chart's quality is positive and finite (its domain) are kept.

use crate::atlas::{round_trip_distance, InChart};
use crate::blend::BLEND_FROM;
use crate::chart::nearest_turns;
use crate::diagnostics::{Warning, WarningKind};
use crate::dim::Dim;
use crate::error::ChartProblem;
use crate::mechanics::lagrangian::{Borrowed, SystemIn};
use crate::mechanics::legendre;
use crate::periodicity::periodicity_deviations;
use crate::periodicity::PERIODICITY_TOLERANCE;
use crate::reduction::invariance::invariance_deviations;
use crate::reduction::invariance::INVARIANCE_TOLERANCE;
use crate::sampling::{self, Uniform};
use crate::{CoordinateKind, DiscreteLagrangian, Error, Hypothesis, InitialMomentum, Method, Problem, Rule, Split};

use super::Finding;

/// How far (relative to 1 + |q'|∞) ψ(φ(q')) may be from q' at a point of a chart's domain: the maps
/// are inverse to round-off.
pub const ROUND_TRIP_TOLERANCE: f64 = 1e-9;

/// Main-chart points drawn for each chart.
const POINTS: usize = 96;

/// The quality below which a point counts as outside a chart's domain (at its singular set).
const DOMAIN_FLOOR: f64 = 1e-3;

/// Points of quality at least [`BLEND_FROM`] at which the Legendre map is tested, at most.
const REGULARITY_POINTS: usize = 8;

/// The tests of one chart of the atlas (index 1 onwards; 0 is the main chart).
#[derive(Debug, Clone, PartialEq)]
pub struct ChartFinding {
    /// The chart's name.
    pub name: String,
    /// Sampled points in the chart's domain (quality positive and finite).
    pub points: usize,
    /// The largest |ψ(φ(q')) − q'|∞ / (1 + |q'|∞) over them (infinite where φ(q') is not finite).
    pub round_trip: f64,
    /// The chart point where it was largest.
    pub worst: Vec<f64>,
    /// A chart point where the quality is at least [`BLEND_FROM`] but ∂²L/∂v² is singular, and the
    /// quality there.
    pub singular_where_good: Option<(Vec<f64>, f64)>,
    /// For each group coordinate of the chart, the invariance of L_d in the chart.
    pub invariance: Vec<Finding>,
    /// For each angle of the chart, the 2π-periodicity of L_d in it.
    pub periodicity: Vec<Finding>,
}

impl ChartFinding {
    /// Whether the chart's maps are inverse on every sampled point of its domain.
    pub fn inverse(&self) -> bool {
        self.points > 0 && self.round_trip <= ROUND_TRIP_TOLERANCE
    }
}

/// The tests of every chart of `system`'s atlas after the main one, for `problem` (its initial
/// configuration and step) and the quadrature `rule`; `main_regular` says whether the main chart's Legendre map is regular at the
/// initial data (the regularity test applies only then).
pub(crate) fn chart_findings<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    problem: &Problem,
    rule: Rule,
    main_regular: bool,
) -> Vec<ChartFinding> {
    let dim = system.dim();
    let kinds = system.coordinates();
    let q0 = dim.array(|i| problem.q0[i]);
    let mut uniform = Uniform::new();
    let mains: Vec<Dm::Array<f64>> = (0..POINTS)
        .map(|_| {
            dim.array(|i| match kinds[i].kind {
                CoordinateKind::Angle => std::f64::consts::PI * uniform.next(),
                CoordinateKind::Real => q0[i] + 0.5 * (1.0 + q0[i].abs()) * uniform.next(),
            })
        })
        .collect();
    system
        .charts()
        .into_iter()
        .enumerate()
        .map(|(i, (name, coordinates))| {
            let chart = i + 1;
            let in_chart = InChart::new(Borrowed(system), chart);
            let chart_kinds = dim.array(|j| coordinates[j].kind);
            let mut finding = ChartFinding {
                name,
                points: 0,
                round_trip: 0.0,
                worst: vec![],
                singular_where_good: None,
                invariance: vec![],
                periodicity: vec![],
            };
            let mut best: Option<(Dm::Array<f64>, f64)> = None;
            let mut tested = 0;
            for main in &mains {
                let here = system.main_to_chart(chart, main);
                let quality = system.chart_quality(chart, &here);
                let finite = here.as_ref().iter().all(|x| x.is_finite());
                if !(finite && quality.is_finite() && quality > DOMAIN_FLOOR) {
                    continue;
                }
                finding.points += 1;
                let there_and_back = system.main_to_chart(chart, &system.chart_to_main(chart, &here));
                let back = nearest_turns(there_and_back, &here, &chart_kinds);
                let apart = round_trip_distance(here.as_ref(), back.as_ref());
                if apart > finding.round_trip || finding.worst.is_empty() {
                    finding.round_trip = finding.round_trip.max(apart);
                    finding.worst = here.as_ref().to_vec();
                }
                if main_regular && quality >= BLEND_FROM && tested < REGULARITY_POINTS {
                    tested += 1;
                    let rank = legendre::rank_in(dim, &in_chart, &here, &dim.array(|_| 0.0));
                    if rank < dim.n() && finding.singular_where_good.is_none() {
                        finding.singular_where_good = Some((here.as_ref().to_vec(), quality));
                    }
                }
                if best.as_ref().is_none_or(|(_, b)| quality > *b) {
                    best = Some((here, quality));
                }
            }
            if let Some((point, _)) = best {
                let ld = DiscreteLagrangian::new(Borrowed(&in_chart), rule, problem.step);
                let samples = sampling::near(&ld, &point, &dim.array(|_| 0.0));
                let split = Split::new(coordinates.as_ref());
                let names = coordinates.as_ref();
                finding.invariance =
                    invariance_deviations(&ld, &split, &samples).into_iter().map(|d| Finding::new(names, d)).collect();
                finding.periodicity =
                    periodicity_deviations(&ld, &samples).into_iter().map(|d| Finding::new(names, d)).collect();
            }
            finding
        })
        .collect()
}

/// What a run of `method` makes of the findings of its atlas's charts: the error that refuses it, or
/// the warnings it runs with (added to `warnings`). Only a run that switches charts (`method.atlas`)
/// relies on them. Refused: a chart whose maps are not inverse on its domain (or that has no domain
/// among the sampled points), whose quality is high where its Legendre map is singular, whose angles
/// are not periods of L; for a reduced run, a chart whose group coordinates are not symmetries of L
/// (a warning instead when `method.check_invariance` is off).
pub(crate) fn verdict(charts: &[ChartFinding], method: &Method, warnings: &mut Vec<Warning>) -> Result<(), Error> {
    if !method.atlas {
        return Ok(());
    }
    for c in charts {
        let refused = |problem: ChartProblem| Error::Chart { chart: c.name.clone(), problem };
        if c.points == 0 {
            return Err(refused(ChartProblem::NoDomain { points: POINTS }));
        }
        if !c.inverse() {
            let (deviation, at, tolerance) = (c.round_trip, c.worst.clone(), ROUND_TRIP_TOLERANCE);
            return Err(refused(ChartProblem::NotInverse { deviation, at, tolerance }));
        }
        if let Some((at, quality)) = &c.singular_where_good {
            return Err(refused(ChartProblem::SingularWhereGood { at: at.clone(), quality: *quality }));
        }
        for f in &c.periodicity {
            let (coordinate, deviation, tolerance) = (f.coordinate.clone(), f.deviation, PERIODICITY_TOLERANCE);
            if f.fails(tolerance) {
                return Err(refused(ChartProblem::NotPeriodic { coordinate, deviation, tolerance }));
            }
            if !f.decided() {
                let hypothesis = Hypothesis::Periodicity;
                return Err(refused(ChartProblem::Undecided { hypothesis, coordinate, samples: f.samples }));
            }
        }
        if !method.reduced {
            continue;
        }
        for f in &c.invariance {
            let (coordinate, deviation, tolerance) = (f.coordinate.clone(), f.deviation, INVARIANCE_TOLERANCE);
            let (problem, kind) = if f.fails(tolerance) {
                (ChartProblem::NotInvariant { coordinate, deviation, tolerance }, WarningKind::NotInvariant)
            } else if !f.decided() {
                let hypothesis = Hypothesis::Invariance;
                (
                    ChartProblem::Undecided { hypothesis, coordinate, samples: f.samples },
                    WarningKind::InvarianceUndecided,
                )
            } else {
                continue;
            };
            if method.check_invariance {
                return Err(refused(problem));
            }
            let message = format!(
                "reducing although, in chart `{}`, {problem}, because `check_invariance` is off: the steps in that \
                 chart hold μ constant although the true momentum map may change there, so the trajectory may not \
                 describe this Lagrangian",
                c.name
            );
            warnings.push(Warning::new(kind, None, message));
        }
    }
    Ok(())
}

/// The verdict on the atlas of `system` for a run of `problem` by `method` (see [`verdict`]), what
/// the run applies before its first step: the same findings and the same verdict as [`super::check`]
/// and [`super::CheckReport::verdict`].
pub(crate) fn atlas_verdict<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    problem: &Problem,
    method: &Method,
) -> Result<Vec<Warning>, Error> {
    let mut warnings = vec![];
    if !method.atlas || system.charts().is_empty() {
        return Ok(warnings);
    }
    let findings = chart_findings(system, problem, method.rule, main_regular(system, problem));
    verdict(&findings, method, &mut warnings)?;
    Ok(warnings)
}

/// Whether the main chart's Legendre map is regular at the initial data of `problem` (given as a
/// velocity, or as a momentum whose best-fitting velocity is taken).
pub(crate) fn main_regular<S: SystemIn<Dm>, Dm: Dim>(system: &S, problem: &Problem) -> bool {
    let dim = system.dim();
    let q0 = dim.array(|i| problem.q0[i]);
    let v0 = match &problem.initial {
        InitialMomentum::Velocity(v) => dim.array(|i| v[i]),
        InitialMomentum::Momentum(p) => legendre::velocity_in(dim, system, &q0, &dim.array(|i| p[i])).0,
    };
    let v0 = dim.array(|i| if v0[i].is_finite() { v0[i] } else { 0.0 });
    legendre::rank_in(dim, system, &q0, &v0) == dim.n()
}

//! The chart watch: signs that a run's coordinates have become singular, or that its step no longer
//! resolves the motion, where the scheme itself cannot tell (paper §6: a chart is good only away
//! from its singular set).
//!
//! Two tests, both cheap where nothing is wrong:
//!
//! - every step, whether an angle's advance was not resolved by the step ([`AngleWatch`]: a few
//!   operations per angle, no branch): more than [`MAX_ANGLE_STEP`], or a *kick* — an advance of
//!   more than [`KICK`] times the angle's typical advance in the run so far (and not negligible,
//!   [`NEGLIGIBLE_ADVANCE`]) that differs from the step before by more than half of the larger of the
//!   two: the angle's rate changed by its own size within one step, which a step that resolves the
//!   motion never does (over a passage of duration τ, the rate changes by about h/τ of itself per
//!   step). A pole passage that the step does not resolve turns the azimuth by a fraction of the π
//!   it turns in the flow, in one step, between steps that barely move it;
//! - at such a step, and where Newton's method fails or the energy jumps, how near to singular the
//!   Legendre map ∂²L/∂v² is ([`legendre::conditioning`], one evaluation of its Hessian), against the
//!   start of the run: near a pole of spherical coordinates its smallest pivot falls like sin²θ,
//!   along the azimuth.
//!
//! A step can also cross a singular set without a kick: the discrete motion goes straight through
//! the singular point of the coordinates while the flow turns around it (Euler angles (φ, θ, ψ) of
//! a top passing 3e-4 rad from upright at h = 0.01: θ changes sign, φ and ψ advance 4–20 times their
//! typical amount with rates that change by more than half in a step, where the flow turns each by
//! about π in 1e-4 s). So a *soft kick* — the same test with [`SOFT_KICK`] in place of [`KICK`] —
//! is reported when the Legendre map at the step has fallen below [`LEGENDRE_DROP`] of its value at
//! the start as well, and is otherwise an ordinary step (it counts towards the typical advance): away
//! from a singular set a rate that changes by half within a step is a fast but resolved motion, while
//! near one it is the start of a passage the step does not resolve (the azimuth of a spherical
//! pendulum with a small L_z, which doubles its rate from step to step on its way to the pole).

use crate::dim::Dim;
use crate::mechanics::lagrangian::SystemIn;
use crate::mechanics::legendre;
use crate::{CoordinateKind, SingularLegendre};

/// The largest advance of an angle in one step, in radians, that a run accepts without a warning. A
/// second-order step that turns an angle by a radian resolves a period with about six steps.
pub const MAX_ANGLE_STEP: f64 = 1.0;

/// The Legendre map counts as near-singular where its pivot ratio ([`legendre::conditioning`]) has
/// fallen below this fraction of the ratio at the start of the run.
pub const LEGENDRE_DROP: f64 = 1e-2;

/// How many times an angle's typical advance (its mean over the run's earlier steps) a step's advance
/// must exceed to count as a kick.
pub const KICK: f64 = 100.0;

/// How many times an angle's typical advance a step's advance must exceed, with its rate changing by
/// more than half within the step, to count as a soft kick: reported only where the Legendre map
/// is near-singular as well (module documentation).
pub const SOFT_KICK: f64 = 3.0;

/// An advance (radians) below which no kick is reported: it moves a point of a unit sphere by less
/// than a millionth of the radius.
pub const NEGLIGIBLE_ADVANCE: f64 = 1e-6;

/// Steps before the typical advance means enough for the kick test.
const WARM_UP: usize = 4;

/// The angles' advances in the run so far: which coordinates are angles, the last step's advance
/// (signed) and the sum of their sizes over the steps without a kick, and how many those were.
#[derive(Debug)]
pub(super) struct AngleWatch<Dm: Dim> {
    angles: Vec<usize>,
    last: Dm::Array<f64>,
    sum: Dm::Array<f64>,
    steps: usize,
}

/// `clone_from` reuses the list of angles: the stepper of an atlas saves a step's progress at every
/// step, without allocating.
impl<Dm: Dim> Clone for AngleWatch<Dm> {
    fn clone(&self) -> Self {
        Self { angles: self.angles.clone(), last: self.last.clone(), sum: self.sum.clone(), steps: self.steps }
    }

    fn clone_from(&mut self, source: &Self) {
        self.angles.clone_from(&source.angles);
        self.last.clone_from(&source.last);
        self.sum.clone_from(&source.sum);
        self.steps = source.steps;
    }
}

/// An angle whose advance the step did not resolve: which, by how much, how many times its typical
/// advance (`None` while there is none yet), and whether only as a soft kick (to be confirmed by the
/// Legendre map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Unresolved {
    pub(super) angle: usize,
    pub(super) by: f64,
    pub(super) times_typical: Option<f64>,
    pub(super) soft: bool,
}

impl<Dm: Dim> AngleWatch<Dm> {
    /// The watch over the coordinates of `kinds` that are angles.
    pub(super) fn new(kinds: &Dm::Array<CoordinateKind>) -> Self {
        let dim = Dm::of(kinds);
        let angles = (0..dim.n()).filter(|&i| kinds[i] == CoordinateKind::Angle).collect();
        Self { angles, last: dim.array(|_| 0.0), sum: dim.array(|_| 0.0), steps: 0 }
    }

    /// Takes the step `dq` and says whether an angle's advance was not resolved: more than
    /// [`MAX_ANGLE_STEP`], a kick, or a soft kick. Branch-free over the angles: it runs every step.
    #[inline(always)]
    pub(super) fn watch(&mut self, dq: &Dm::Array<f64>) -> Option<Unresolved> {
        let steps = self.steps as f64;
        let warm = self.steps >= WARM_UP;
        let (mut unresolved, mut soft) = (false, false);
        for &i in &self.angles {
            let (advance, last) = (dq[i], self.last[i]);
            let size = advance.abs();
            let turned = warm & ((advance - last).abs() > 0.5 * size.max(last.abs())) & (size > NEGLIGIBLE_ADVANCE);
            unresolved |= (turned & (size * steps > KICK * self.sum[i])) | (size > MAX_ANGLE_STEP);
            soft |= turned & (size * steps > SOFT_KICK * self.sum[i]);
        }
        let found = (unresolved | soft).then(|| Unresolved { soft: !unresolved, ..self.unresolved(dq) });
        // A soft kick is an ordinary step unless the Legendre map confirms it: it counts towards the
        // typical advance.
        let counted = if unresolved { 0.0 } else { 1.0 };
        for &i in &self.angles {
            self.last[i] = dq[i];
            self.sum[i] += counted * dq[i].abs();
        }
        self.steps += usize::from(!unresolved);
        found
    }

    /// The angle of the largest advance relative to its typical one (or, before there is a typical
    /// advance, of the largest advance) in the step `dq`.
    #[cold]
    fn unresolved(&self, dq: &Dm::Array<f64>) -> Unresolved {
        let typical = |i: usize| (self.steps > 0).then(|| self.sum[i] / self.steps as f64);
        // An advance beyond MAX_ANGLE_STEP first, then the largest relative to the typical one.
        let measure = |i: usize| {
            let size = dq[i].abs();
            (size > MAX_ANGLE_STEP, typical(i).map_or(size, |t| if size == 0.0 { 0.0 } else { size / t }))
        };
        let order = |i: usize, j: usize| {
            let ((a, x), (b, y)) = (measure(i), measure(j));
            a.cmp(&b).then(x.total_cmp(&y))
        };
        let angle = self.angles.iter().copied().max_by(|&i, &j| order(i, j)).unwrap_or(0);
        let by = dq[angle];
        let times_typical = typical(angle).filter(|t| *t > 0.0).map(|t| by.abs() / t);
        Unresolved { angle, by, times_typical, soft: false }
    }
}

/// Why the coordinates may be to blame at (q, v): the Legendre map's pivot ratio and the coordinate
/// it degenerates along, when the ratio has fallen below [`LEGENDRE_DROP`] of `at_start` (a regular
/// start; a Lagrangian degenerate from the start has nothing to compare with).
#[cold]
pub(super) fn singular_chart<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    at_start: f64,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> Option<SingularLegendre> {
    if at_start.is_nan() || at_start <= 0.0 || v.as_ref().iter().any(|x| !x.is_finite()) {
        return None;
    }
    let (ratio, along) = legendre::conditioning_in(system.dim(), system, q, v);
    (ratio < LEGENDRE_DROP * at_start).then(|| SingularLegendre {
        coordinate: system.coordinates()[along].name.clone(),
        ratio,
        at_start,
    })
}

//! The chart watch: signs that a run's coordinates have become singular, or that its step no longer
//! resolves the motion, where the scheme itself cannot tell (paper §6: a chart is good only away
//! from its singular set).
//!
//! Two tests, both cheap where nothing is wrong:
//!
//! - every step, whether an angle advanced by more than [`MAX_ANGLE_STEP`] ([`races`]: N products
//!   and comparisons, no branch);
//! - at such a step, and where Newton's method fails or the energy jumps, how near to singular the
//!   Legendre map ∂²L/∂v² is ([`legendre::conditioning`], one evaluation of its Hessian), against the
//!   start of the run: near a pole of spherical coordinates its smallest pivot falls like sin²θ,
//!   along the azimuth.

use crate::dim::Dim;
use crate::mechanics::lagrangian::SystemIn;
use crate::mechanics::legendre;
use crate::CoordinateKind;

/// The largest advance of an angle in one step, in radians, that a run accepts without a warning. A
/// second-order step that turns an angle by a radian resolves a period with about six steps.
pub const MAX_ANGLE_STEP: f64 = 1.0;

/// The Legendre map counts as near-singular where its pivot ratio ([`legendre::conditioning`]) has
/// fallen below this fraction of the ratio at the start of the run.
pub const LEGENDRE_DROP: f64 = 1e-2;

/// Whether an angle advanced by more than [`MAX_ANGLE_STEP`] in the step `dq`; `angles` is 1 at the
/// angles and 0 elsewhere. Branch-free over the coordinates: it runs every step.
#[inline(always)]
pub(super) fn races(angles: &[f64], dq: &[f64]) -> bool {
    let mut largest = 0.0f64;
    for (a, d) in angles.iter().zip(dq) {
        let turned = a * d.abs();
        largest = if turned > largest { turned } else { largest };
    }
    largest > MAX_ANGLE_STEP
}

/// The angle that advanced most in the step `dq`, and by how much.
#[cold]
pub(super) fn fastest_angle(kinds: &[CoordinateKind], dq: &[f64]) -> (usize, f64) {
    let angles = (0..kinds.len()).filter(|&i| kinds[i] == CoordinateKind::Angle);
    let i = angles.max_by(|&i, &j| dq[i].abs().total_cmp(&dq[j].abs())).unwrap_or(0);
    (i, dq[i])
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
) -> Option<String> {
    if at_start.is_nan() || at_start <= 0.0 || v.as_ref().iter().any(|x| !x.is_finite()) {
        return None;
    }
    let (ratio, along) = legendre::conditioning_in(system.dim(), system, q, v);
    (ratio < LEGENDRE_DROP * at_start).then(|| {
        let coordinates = system.coordinates();
        let name = &coordinates[along].name;
        format!(
            "the Legendre map ∂²L/∂v² is near-singular here (its smallest pivot is {ratio:.1e} of its largest, \
             against {at_start:.1e} at the start), along `{name}`: the coordinates are singular nearby (a pole \
             of spherical coordinates, say), so `{name}` and its momentum are ill-conditioned"
        )
    })
}

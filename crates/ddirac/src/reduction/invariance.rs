//! The hypothesis of reduction: L_d(q0 + a, q1 + a) = L_d(q0, q1) for every translation a of the
//! group coordinates (paper §4, opening of `sec:reducedequations`).
//!
//! The check takes pairs (q0, q1) near the first step where L_d is defined ([`crate::sampling`])
//! and, for each group coordinate g alone, measures two deviations relative to the slope of L_d
//! there, ‖(D1 L_d, D2 L_d)‖∞:
//!
//! - infinitesimal: |∂L_d/∂q0_g + ∂L_d/∂q1_g|, zero exactly when L_d is invariant to first order;
//! - finite: |L_d(q0 + s e_g, q1 + s e_g) − L_d(q0, q1)| / |s| for a shift s of order one, less the
//!   rounding error of the two values.
//!
//! Both are unchanged when L is shifted by a constant or multiplied by a factor. A shifted value that
//! is not finite counts as an infinite deviation, and a verdict needs at least
//! [`sampling::ENOUGH`](crate::sampling::ENOUGH) pairs where L_d is finite: with fewer the check
//! could not decide, and a reduced run is refused unless the check is explicitly turned off.

use crate::sampling::{self, Sample, Uniform};
use crate::{DiscreteLagrangian, Split, System};

/// Relative tolerance of the invariance deviation.
pub const INVARIANCE_TOLERANCE: f64 = 1e-9;

/// The outcome of a test of one coordinate over the sampled pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    /// Index of the coordinate.
    pub coordinate: usize,
    /// The largest relative deviation over the pairs (0 when there were none).
    pub deviation: f64,
    /// How many pairs had a finite L_d.
    pub samples: usize,
}

impl Deviation {
    /// Whether enough pairs were found for a verdict.
    pub fn decided(&self) -> bool {
        self.samples >= sampling::ENOUGH
    }
}

/// The deviation of a moved value from a sample's value, relative to `shift` times the sample's
/// slope, after the rounding error of both values is taken off; infinite when `moved` is not finite.
pub fn relative_change<const N: usize>(sample: &Sample<N>, moved: f64, shift: f64) -> f64 {
    if !moved.is_finite() {
        return f64::INFINITY;
    }
    let change = ((moved - sample.derivatives.value).abs() - sampling::rounding(sample, moved, shift)).max(0.0);
    ratio(change, shift.abs() * sample.slope())
}

/// `numerator / scale`, with 0/0 = 0 and x/0 = ∞.
pub(crate) fn ratio(numerator: f64, scale: f64) -> f64 {
    match (numerator, scale) {
        (0.0, _) => 0.0,
        (n, s) if s > 0.0 => n / s,
        _ => f64::INFINITY,
    }
}

/// The invariance deviation of L_d under translations of each group coordinate alone, over the
/// pairs `samples` (from [`sampling::near`]): one [`Deviation`] per group coordinate, in the order of
/// `split.group`.
pub fn invariance_deviations<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<'_, S>,
    split: &Split,
    samples: &[Sample<N>],
) -> Vec<Deviation> {
    let mut uniform = Uniform::new();
    split
        .group
        .iter()
        .map(|&g| {
            let worst = samples.iter().fold(0.0f64, |worst, sample| {
                let infinitesimal = ratio((sample.derivatives.da[g] + sample.derivatives.db[g]).abs(), sample.slope());
                let u = uniform.next();
                let shift = u.signum() * (0.25 + 2.75 * u.abs());
                let (mut s0, mut s1) = (sample.q0, sample.q1);
                s0[g] += shift;
                s1[g] += shift;
                let finite = relative_change(sample, ld.value(&s0, &s1), shift);
                worst.max(infinitesimal).max(finite)
            });
            Deviation { coordinate: g, deviation: worst, samples: samples.len() }
        })
        .collect()
}

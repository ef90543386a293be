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
//! [`ENOUGH`](crate::sampling::ENOUGH) pairs where L_d is finite: with fewer the check
//! could not decide, and a reduced run is refused unless the check is explicitly turned off.

use crate::dim::Dim;
use crate::mechanics::lagrangian::Lagrangian;
use crate::sampling::{ratio, relative_change, Deviation, Sample, Uniform};
use crate::{DiscreteLagrangian, Split};

/// Relative tolerance of the invariance deviation.
pub const INVARIANCE_TOLERANCE: f64 = 1e-9;

/// The invariance deviation of L_d under translations of each group coordinate alone, over the
/// pairs `samples` (from [`crate::sampling::near`]): one [`Deviation`] per group coordinate, in the order of
/// `split.group`.
pub fn invariance_deviations<S: Lagrangian<Dm>, Dm: Dim>(
    ld: &DiscreteLagrangian<S>,
    split: &Split,
    samples: &[Sample<Dm>],
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
                let (mut s0, mut s1) = (sample.q0.clone(), sample.q1.clone());
                s0[g] += shift;
                s1[g] += shift;
                let finite = relative_change(sample, ld.value_in::<Dm>(&s0, &s1), shift);
                worst.max(infinitesimal).max(finite)
            });
            Deviation { coordinate: g, deviation: worst, samples: samples.len() }
        })
        .collect()
}

//! The hypothesis of an angle coordinate: L is 2π-periodic in it, so that the chart may wrap it to
//! (−π, π] (paper §6, charts on S¹) without changing the motion.
//!
//! Tested on pairs near the first step where L_d is defined ([`crate::sampling`]): the change of
//! L_d(q0 + 2π e_i, q1 + 2π e_i) against L_d(q0, q1), relative to 2π times the slope of L_d there,
//! after the rounding error of both values is taken off (so that shifting L by a constant or scaling
//! it changes nothing).

use std::f64::consts::TAU;

use crate::dim::Dim;
use crate::mechanics::lagrangian::SystemIn;
use crate::sampling::{relative_change, Deviation, Sample};
use crate::{CoordinateKind, DiscreteLagrangian};

/// Relative tolerance of the periodicity deviation.
pub const PERIODICITY_TOLERANCE: f64 = 1e-9;

/// The periodicity deviation of L_d in each angle coordinate alone, over the pairs `samples`: one
/// [`Deviation`] per angle, in coordinate order.
pub fn periodicity_deviations<S: SystemIn<Dm>, Dm: Dim>(
    ld: &DiscreteLagrangian<S>,
    samples: &[Sample<Dm>],
) -> Vec<Deviation> {
    let coordinates = ld.system.coordinates();
    (0..coordinates.as_ref().len())
        .filter(|&i| coordinates[i].kind == CoordinateKind::Angle)
        .map(|i| {
            let worst = samples.iter().fold(0.0f64, |worst, sample| {
                let (mut s0, mut s1) = (sample.q0.clone(), sample.q1.clone());
                s0[i] += TAU;
                s1[i] += TAU;
                worst.max(relative_change(sample, ld.value_in::<Dm>(&s0, &s1), TAU))
            });
            Deviation { coordinate: i, deviation: worst, samples: samples.len() }
        })
        .collect()
}

//! The hypothesis of reduction: L_d(q0 + a, q1 + a) = L_d(q0, q1) for every translation a of the
//! group coordinates (paper §4, opening of `sec:reducedequations`).
//!
//! The check samples pseudo-random points near a given configuration and random shifts of each group
//! coordinate alone, and compares L_d before and after, relative to the size of L_d's terms.

use crate::{DiscreteLagrangian, Error, Split, System};

/// Relative tolerance of [`check_invariance`].
pub const INVARIANCE_TOLERANCE: f64 = 1e-9;

/// The largest relative change of L_d under translations of each group coordinate alone, sampled
/// near `q` with increments of the size `dq`: one `(coordinate index, deviation)` per group coordinate.
pub fn invariance_deviations<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<'_, S>,
    split: &Split,
    q: &[f64; N],
    dq: &[f64; N],
) -> Vec<(usize, f64)> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut deviations = Vec::with_capacity(split.n_g());
    for &gj in &split.group {
        let mut worst = 0.0f64;
        for _ in 0..16 {
            let q0: [f64; N] = std::array::from_fn(|i| q[i] + uniform() * (1.0 + q[i].abs()) * 0.5);
            let q1: [f64; N] = std::array::from_fn(|i| q0[i] + dq[i] * (1.0 + 0.5 * uniform()) + uniform() * 1e-3);
            let shift = uniform() * 3.0;
            let (mut s0, mut s1) = (q0, q1);
            s0[gj] += shift;
            s1[gj] += shift;
            let (before, after) = (ld.value(&q0, &q1), ld.value(&s0, &s1));
            let scale = before.abs().max(after.abs()).max(ld.step * f64::MIN_POSITIVE.sqrt());
            let deviation = if before.is_finite() && after.is_finite() { (before - after).abs() / scale } else { 0.0 };
            worst = worst.max(deviation);
        }
        deviations.push((gj, worst));
    }
    deviations
}

/// Checks that L_d is invariant under translation of each group coordinate (see
/// [`invariance_deviations`]) to [`INVARIANCE_TOLERANCE`]. Names the first group coordinate that
/// breaks it.
pub fn check_invariance<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<'_, S>,
    split: &Split,
    q: &[f64; N],
    dq: &[f64; N],
) -> Result<(), Error> {
    let names = ld.system.coordinates();
    match invariance_deviations(ld, split, q, dq).into_iter().find(|&(_, d)| d > INVARIANCE_TOLERANCE) {
        Some((gj, deviation)) => {
            Err(Error::NotInvariant { coordinate: names[gj].name.clone(), deviation, tolerance: INVARIANCE_TOLERANCE })
        }
        None => Ok(()),
    }
}

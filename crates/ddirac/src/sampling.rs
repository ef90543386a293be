//! Pairs (q0, q1) near the initial data where L_d is defined: the points at which the hypotheses of
//! a run (invariance of L_d under the group, paper §4; periodicity of L in its angles, §6) are tested.
//!
//! The first pair is the first step itself, (q0, q0 + h·v0). The others are pseudo-random, in balls
//! around it that shrink whenever a candidate falls where L_d or its gradient is not finite (outside
//! the domain of a `sqrt`, across a singular potential), so that a Lagrangian defined only on a
//! small neighbourhood of the initial data is still tested there and never passes for want of points.

use nalgebra::SVector;

use crate::ad::FirstDerivatives;
use crate::dim::Fixed;
use crate::{DiscreteLagrangian, System};

/// How many pairs a verdict wants.
pub const WANTED: usize = 16;
/// The fewest pairs with a finite L_d on which a verdict may rest.
pub const ENOUGH: usize = 4;
/// Relative radii of the balls the candidates are drawn from, largest first.
const RADII: [f64; 6] = [0.5, 5e-2, 5e-3, 5e-4, 5e-5, 5e-6];
/// Candidates drawn per radius before it shrinks.
const TRIES: usize = 24;

/// A pair (q0, q1) with L_d and its gradient there, all finite.
#[derive(Debug, Clone, Copy)]
pub struct Sample<const N: usize> {
    /// The first configuration.
    pub q0: [f64; N],
    /// The second configuration.
    pub q1: [f64; N],
    /// L_d(q0, q1), D1 L_d and D2 L_d.
    pub derivatives: FirstDerivatives<Fixed<N>>,
}

impl<const N: usize> Sample<N> {
    /// ‖(D1 L_d, D2 L_d)‖∞: the size of L_d's change per unit move, the scale of every deviation.
    pub fn slope(&self) -> f64 {
        self.derivatives.da.amax().max(self.derivatives.db.amax())
    }
}

/// A deterministic xorshift generator of numbers in [−1, 1).
pub(crate) struct Uniform(u64);

impl Uniform {
    pub(crate) fn new() -> Self {
        Self(0x9E37_79B9_7F4A_7C15)
    }

    pub(crate) fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// L_d and its gradient at (q0, q1), if all are finite.
pub fn sample<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    q0: [f64; N],
    q1: [f64; N],
) -> Option<Sample<N>> {
    let d1 = SVector::from(std::array::from_fn(|i| q1[i] - q0[i]));
    let derivatives = ld.first_derivatives_local(&q0, &SVector::zeros(), &d1);
    let finite =
        derivatives.value.is_finite() && derivatives.da.iter().chain(derivatives.db.iter()).all(|v| v.is_finite());
    finite.then_some(Sample { q0, q1, derivatives })
}

/// Up to [`WANTED`] pairs near (q, q + dq) where L_d and its gradient are finite, the first step
/// (q, q + dq) first when it is one of them. Fewer are returned only when no more could be found.
pub fn near<S: System<N>, const N: usize>(ld: &DiscreteLagrangian<S>, q: &[f64; N], dq: &[f64; N]) -> Vec<Sample<N>> {
    let mut uniform = Uniform::new();
    let first_step = std::array::from_fn(|i| q[i] + dq[i]);
    let mut samples: Vec<Sample<N>> = sample(ld, *q, first_step).into_iter().collect();
    for radius in RADII {
        for _ in 0..TRIES {
            if samples.len() >= WANTED {
                return samples;
            }
            let q0: [f64; N] = std::array::from_fn(|i| q[i] + uniform.next() * (1.0 + q[i].abs()) * radius);
            let q1 = std::array::from_fn(|i| {
                q0[i] + dq[i] * (1.0 + 0.5 * uniform.next()) + uniform.next() * radius * 2e-3 * (1.0 + q[i].abs())
            });
            samples.extend(sample(ld, q0, q1));
        }
        if samples.len() >= WANTED {
            break;
        }
    }
    samples
}

/// The rounding error of L_d(q0 + s, q1 + s) − L_d(q0, q1) for a move s of one coordinate: the last
/// digits of both values, and of the moved arguments as L_d's slope carries them.
pub fn rounding<const N: usize>(sample: &Sample<N>, moved: f64, shift: f64) -> f64 {
    let position = sample.q0.iter().chain(&sample.q1).fold(0.0f64, |m, v| m.max(v.abs()));
    64.0 * f64::EPSILON
        * (sample.derivatives.value.abs().max(moved.abs()) + sample.slope() * (position + shift.abs()) * N as f64)
}

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
        self.samples >= ENOUGH
    }
}

/// The deviation of a moved value from a sample's value, relative to `shift` times the sample's
/// slope, after the rounding error of both values is taken off; infinite when `moved` is not finite.
pub fn relative_change<const N: usize>(sample: &Sample<N>, moved: f64, shift: f64) -> f64 {
    if !moved.is_finite() {
        return f64::INFINITY;
    }
    let change = ((moved - sample.derivatives.value).abs() - rounding(sample, moved, shift)).max(0.0);
    ratio(change, shift.abs() * sample.slope())
}

/// `numerator / scale`, with 0/0 = 0 and x/0 = ∞.
pub fn ratio(numerator: f64, scale: f64) -> f64 {
    match (numerator, scale) {
        (0.0, _) => 0.0,
        (n, s) if s > 0.0 => n / s,
        _ => f64::INFINITY,
    }
}

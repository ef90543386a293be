//! Pairs (q0, q1) near the initial data where L_d is defined: the points at which the hypotheses of
//! a run (invariance of L_d under the group, paper §4; periodicity of L in its angles, §6) are tested.
//!
//! The first pair is the first step itself, (q0, q0 + h·v0). The others are pseudo-random, in balls
//! around it that shrink whenever a candidate falls where L_d or its gradient is not finite (outside
//! the domain of a `sqrt`, across a singular potential), so that a Lagrangian defined only on a
//! small neighbourhood of the initial data is still tested there and never passes for want of points.

use crate::dim::Dim;
use crate::dim::FirstDerivatives;
use crate::mechanics::lagrangian::Lagrangian;
use crate::DiscreteLagrangian;

/// How many pairs a verdict wants.
pub const WANTED: usize = 16;
/// The fewest pairs with a finite L_d on which a verdict may rest.
pub const ENOUGH: usize = 4;
/// Relative radii of the balls the candidates are drawn from, largest first.
const RADII: [f64; 6] = [0.5, 5e-2, 5e-3, 5e-4, 5e-5, 5e-6];
/// Candidates drawn per radius before it shrinks.
const TRIES: usize = 24;

/// A pair (q0, q1) with L_d and its gradient there, all finite.
#[derive(Debug, Clone)]
pub struct Sample<Dm: Dim> {
    /// The first configuration.
    pub q0: Dm::Array<f64>,
    /// The second configuration.
    pub q1: Dm::Array<f64>,
    /// L_d(q0, q1), D1 L_d and D2 L_d.
    pub derivatives: FirstDerivatives<Dm>,
}

impl<Dm: Dim> Sample<Dm> {
    /// ‖(D1 L_d, D2 L_d)‖∞: the size of L_d's change per unit move, the scale of every deviation.
    pub fn slope(&self) -> f64 {
        Dm::amax(&self.derivatives.da).max(Dm::amax(&self.derivatives.db))
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
pub fn sample<S: Lagrangian<Dm>, Dm: Dim>(
    ld: &DiscreteLagrangian<S>,
    q0: Dm::Array<f64>,
    q1: Dm::Array<f64>,
) -> Option<Sample<Dm>> {
    let dim = Dm::of(&q0);
    let d1 = dim.array(|i| q1[i] - q0[i]);
    let derivatives = ld.first_derivatives_in(&q0, &dim.array(|_| 0.0), &d1);
    let finite = derivatives.value.is_finite()
        && Dm::entries(&derivatives.da).iter().chain(Dm::entries(&derivatives.db)).all(|v| v.is_finite());
    finite.then_some(Sample { q0, q1, derivatives })
}

/// Up to [`WANTED`] pairs near (q, q + dq) where L_d and its gradient are finite, the first step
/// (q, q + dq) first when it is one of them. Fewer are returned only when no more could be found.
pub fn near<S: Lagrangian<Dm>, Dm: Dim>(
    ld: &DiscreteLagrangian<S>,
    q: &Dm::Array<f64>,
    dq: &Dm::Array<f64>,
) -> Vec<Sample<Dm>> {
    let dim = Dm::of(q);
    let mut uniform = Uniform::new();
    let first_step = dim.array(|i| q[i] + dq[i]);
    let mut samples: Vec<Sample<Dm>> = sample(ld, q.clone(), first_step).into_iter().collect();
    for radius in RADII {
        for _ in 0..TRIES {
            if samples.len() >= WANTED {
                return samples;
            }
            let q0: Dm::Array<f64> = dim.array(|i| q[i] + uniform.next() * (1.0 + q[i].abs()) * radius);
            let q1 = dim.array(|i| {
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
pub fn rounding<Dm: Dim>(sample: &Sample<Dm>, moved: f64, shift: f64) -> f64 {
    let n = sample.q0.as_ref().len();
    let position = sample.q0.as_ref().iter().chain(sample.q1.as_ref()).fold(0.0f64, |m, v| m.max(v.abs()));
    64.0 * f64::EPSILON
        * (sample.derivatives.value.abs().max(moved.abs()) + sample.slope() * (position + shift.abs()) * n as f64)
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
pub fn relative_change<Dm: Dim>(sample: &Sample<Dm>, moved: f64, shift: f64) -> f64 {
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

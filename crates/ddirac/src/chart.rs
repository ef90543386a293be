//! Configurations in retraction-compatible charts (paper §6).
//!
//! Each step is solved in a chart centred at the current point: the unknowns are the increments
//! q_{k+1} − q_k, and L_d is evaluated at `base + offset` (see
//! [`DiscreteLagrangian::eval_local`](crate::DiscreteLagrangian::eval_local)). For an angle on S¹
//! the base is kept in (−π, π] and the full turns are counted separately, so that a long run whose
//! angle reaches thousands of radians evaluates the Lagrangian as accurately as on the first step.
//! Output shows angles continuous (unwrapped) by default, or wrapped to (−π, π].

use std::f64::consts::{PI, TAU};

use crate::CoordinateKind;

/// Wraps an angle to (−π, π].
///
/// ```
/// use std::f64::consts::PI;
/// assert_eq!(ddirac::chart::wrap(3.0 * PI / 2.0), -PI / 2.0);
/// assert_eq!(ddirac::chart::wrap(-PI), PI);
/// ```
pub fn wrap(angle: f64) -> f64 {
    let r = angle.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

/// A configuration: its chart base (angles wrapped) and the full turns of each angle.
///
/// ```
/// use ddirac::{chart::Configuration, CoordinateKind};
/// let mut c = Configuration::new([3.0, 3.0], [CoordinateKind::Real, CoordinateKind::Angle]);
/// c.advance(&[1.0, 1.0]);
/// assert_eq!(c.unwrapped(), [4.0, 4.0]);
/// assert!((c.base()[1] - (4.0 - std::f64::consts::TAU)).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration<const N: usize> {
    base: [f64; N],
    turns: [i64; N],
    kinds: [CoordinateKind; N],
}

impl<const N: usize> Configuration<N> {
    /// A configuration at `q` (angles may be given unwrapped).
    pub fn new(q: [f64; N], kinds: [CoordinateKind; N]) -> Self {
        let mut c = Self { base: [0.0; N], turns: [0; N], kinds };
        c.advance(&q);
        c
    }

    /// Moves by the increments `dq`, re-centring each angle's chart.
    pub fn advance(&mut self, dq: &[f64; N]) {
        for (((base, turns), kind), d) in self.base.iter_mut().zip(&mut self.turns).zip(&self.kinds).zip(dq) {
            let moved = *base + d;
            *base = match kind {
                CoordinateKind::Real => moved,
                CoordinateKind::Angle if -PI < moved && moved <= PI => moved,
                CoordinateKind::Angle => {
                    let wrapped = wrap(moved);
                    *turns += ((moved - wrapped) / TAU).round() as i64;
                    wrapped
                }
            };
        }
    }

    /// The chart base: real coordinates as they are, angles in (−π, π].
    pub fn base(&self) -> &[f64; N] {
        &self.base
    }

    /// Angles continued through full turns.
    pub fn unwrapped(&self) -> [f64; N] {
        std::array::from_fn(|i| self.base[i] + TAU * self.turns[i] as f64)
    }

    /// The configuration for output: unwrapped, or with angles in (−π, π].
    pub fn output(&self, wrap_angles: bool) -> [f64; N] {
        if wrap_angles {
            self.base
        } else {
            self.unwrapped()
        }
    }
}

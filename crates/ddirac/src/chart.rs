//! Configurations in retraction-compatible charts (paper §6).
//!
//! Each step is solved in a chart centred at the current point: the unknowns are the increments
//! q_{k+1} − q_k, and L_d is evaluated at `base + offset` (see
//! [`DiscreteLagrangian::eval_local`](crate::DiscreteLagrangian::eval_local)). For an angle on S¹
//! the base is kept in (−π, π] and the full turns are counted separately, so that a long run whose
//! angle reaches thousands of radians evaluates the Lagrangian as accurately as on the first step.
//! Output shows angles continuous (unwrapped) by default, or wrapped to (−π, π].

use std::f64::consts::{PI, TAU};

use crate::dim::{Dim, Fixed};
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

/// A configuration: its chart base (angles wrapped) and the full turns of each angle, in a dimension
/// ([`Configuration`] for a fixed one).
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigurationIn<Dm: Dim> {
    base: Dm::Array<f64>,
    turns: Dm::Array<i64>,
    kinds: Dm::Array<CoordinateKind>,
}

/// A configuration of `N` coordinates.
///
/// ```
/// use ddirac::{chart::Configuration, CoordinateKind};
/// let mut c = Configuration::new([3.0, 3.0], [CoordinateKind::Real, CoordinateKind::Angle]);
/// c.advance(&[1.0, 1.0]);
/// assert_eq!(c.unwrapped(), [4.0, 4.0]);
/// assert!((c.base()[1] - (4.0 - std::f64::consts::TAU)).abs() < 1e-15);
/// ```
pub type Configuration<const N: usize> = ConfigurationIn<Fixed<N>>;

impl<Dm: Dim> ConfigurationIn<Dm> {
    /// A configuration at `q` (angles may be given unwrapped).
    pub fn new(q: Dm::Array<f64>, kinds: Dm::Array<CoordinateKind>) -> Self {
        let dim = Dm::of(&q);
        let mut c = Self { base: dim.array(|_| 0.0), turns: dim.array(|_| 0), kinds };
        c.advance(&q);
        c
    }

    /// Moves by the increments `dq`, re-centring each angle's chart.
    #[inline(always)]
    pub fn advance(&mut self, dq: &Dm::Array<f64>) {
        // Every coordinate moves; an angle that leaves (−π, π] is re-centred after, off the path of a
        // step (no branch per coordinate).
        let (base, kinds) = (self.base.as_mut(), self.kinds.as_ref());
        let mut outside = false;
        for ((base, kind), d) in base.iter_mut().zip(kinds).zip(dq.as_ref()) {
            let moved = *base + d;
            *base = moved;
            outside |= (*kind == CoordinateKind::Angle) & !(-PI < moved && moved <= PI);
        }
        if outside {
            self.recentre();
        }
    }

    /// Wraps each angle outside (−π, π] into it, counting its full turns.
    #[cold]
    fn recentre(&mut self) {
        let (base, turns, kinds) = (self.base.as_mut(), self.turns.as_mut(), self.kinds.as_ref());
        for ((base, turns), kind) in base.iter_mut().zip(turns).zip(kinds) {
            let moved = *base;
            if *kind == CoordinateKind::Angle && !(-PI < moved && moved <= PI) {
                let wrapped = wrap(moved);
                *turns += ((moved - wrapped) / TAU).round() as i64;
                *base = wrapped;
            }
        }
    }

    /// The chart base: real coordinates as they are, angles in (−π, π].
    pub fn base(&self) -> &Dm::Array<f64> {
        &self.base
    }

    /// The kinds of the coordinates.
    pub fn kinds(&self) -> &Dm::Array<CoordinateKind> {
        &self.kinds
    }

    /// Angles continued through full turns.
    pub fn unwrapped(&self) -> Dm::Array<f64> {
        let turns = self.turns.as_ref();
        Dm::of(&self.base).array(|i| self.base[i] + TAU * turns[i] as f64)
    }

    /// The configuration for output: unwrapped, or with angles in (−π, π].
    pub fn output(&self, wrap_angles: bool) -> Dm::Array<f64> {
        if wrap_angles {
            self.base.clone()
        } else {
            self.unwrapped()
        }
    }
}

/// Main-chart coordinates `q` moved by whole turns of their angles to the representative nearest
/// `near` (the default of [`System::nearest_in_main`](crate::System::nearest_in_main)).
///
/// ```
/// use ddirac::{chart::nearest_turns, CoordinateKind::{Angle, Real}};
/// let q = nearest_turns([0.1, 0.1], &[6.3, 6.3], &[Angle, Real]);
/// assert_eq!(q, [0.1 + std::f64::consts::TAU, 0.1]);
/// ```
pub fn nearest_turns<A: AsMut<[f64]>>(mut q: A, near: &impl AsRef<[f64]>, kinds: &impl AsRef<[CoordinateKind]>) -> A {
    for ((q, near), kind) in q.as_mut().iter_mut().zip(near.as_ref()).zip(kinds.as_ref()) {
        if *kind == CoordinateKind::Angle {
            *q += TAU * ((*near - *q) / TAU).round();
        }
    }
    q
}

/// √x where x > 0, else 0 (with zero derivatives): the distance to a chart's edge, such as
/// √(1 − x² − y²) for the horizontal coordinates of a hemisphere, on any scalar.
///
/// ```
/// assert_eq!(ddirac::chart::root_or_zero(0.25), 0.5);
/// assert_eq!(ddirac::chart::root_or_zero(-0.25), 0.0);
/// ```
pub fn root_or_zero<D: num_dual::DualNum<Primitive = f64> + Copy>(x: D) -> D {
    if x.re() > 0.0 {
        x.sqrt()
    } else {
        D::zero()
    }
}

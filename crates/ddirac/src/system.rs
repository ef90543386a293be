//! A mechanical system: its coordinates, its Lagrangian L(q, v) and the symmetry that translates its
//! group coordinates.
//!
//! The configuration space is Q = Σ × G in coordinates q = (x, g) (paper §2.2.1): shape coordinates
//! x ∈ Σ and group coordinates g ∈ G, where G is abelian and acts by translation of g. Coordinates keep
//! the order the system gives them; [`Split`] offers named views of the x and g entries.

use crate::coordinate::{Coordinate, CoordinateKind};
use crate::Scalar;

/// A Lagrangian system with `N` coordinates.
///
/// The Lagrangian is written once, generically over the scalar, so that automatic differentiation
/// gives every derivative the integrators need. Write it for `D: DualNum<Primitive = f64> + Copy`
/// (num-dual's trait, re-exported as [`crate::num_dual`]): the trait asks for [`Scalar`], which adds
/// only what compiled derivatives use, and an implementation may ask for less.
///
/// ```
/// use ddirac::{Coordinate, System};
/// use num_dual::DualNum;
///
/// /// A free particle on a line: L = ½ m v².
/// struct Free { m: f64 }
/// impl System<1> for Free {
///     fn coordinates(&self) -> [Coordinate; 1] { [Coordinate::group("x")] }
///     fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, _q: &[D; 1], v: &[D; 1]) -> D {
///         v[0] * v[0] * (0.5 * self.m)
///     }
/// }
/// assert_eq!(Free { m: 2.0 }.lagrangian(&[0.0], &[3.0]), 9.0);
/// ```
pub trait System<const N: usize> {
    /// The coordinates, in the order of `q` and `v`.
    fn coordinates(&self) -> [Coordinate; N];

    /// The Lagrangian L(q, v).
    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D;

    /// The exact motion from `(q0, p0)` at time `t`, on the coordinates it is known for.
    ///
    /// Systems without a closed-form solution keep the default, `None`.
    fn exact_solution(&self, _q0: &[f64; N], _p0: &[f64; N], _t: f64) -> Option<[Option<f64>; N]> {
        None
    }

    /// The other charts of the system's atlas (paper §6), numbered from 1 in this order; chart 0 is
    /// the main chart, that of [`System::coordinates`] and [`System::lagrangian`]. A run switches to
    /// the best chart where the current one degrades ([`System::chart_quality`]) and reports every row
    /// in the main chart. Systems without an atlas keep the default, none. See [`crate::atlas`].
    fn charts(&self) -> Vec<Chart<N>> {
        Vec::new()
    }

    /// The main chart's coordinates of the point whose coordinates in chart `chart` (≥ 1) are `q`:
    /// the map φ of the chart, generic over the scalar (the chart's Lagrangian is L ∘ Tφ).
    fn chart_to_main<D: Scalar>(&self, _chart: usize, q: &[D; N]) -> [D; N] {
        *q
    }

    /// The coordinates in chart `chart` (≥ 1) of the point whose main-chart coordinates are `q`: the
    /// inverse ψ = φ⁻¹, generic over the scalar.
    fn main_to_chart<D: Scalar>(&self, _chart: usize, q: &[D; N]) -> [D; N] {
        *q
    }

    /// The Lagrangian L ∘ Tφ of chart `chart` (≥ 1) written out, where the system has a cheaper form
    /// of it than the composition; `None`, the default, means the composition
    /// ([`crate::atlas::InChart`]). It must be the same function: a system that gives it holds it
    /// against the composition in a test, as a hand-written derivative is held against AD.
    fn chart_lagrangian<D: Scalar>(&self, _chart: usize, _q: &[D; N], _v: &[D; N]) -> Option<D> {
        None
    }

    /// How good chart `chart` (0 for the main chart) is at the point whose coordinates in it are `q`:
    /// about 1 where the chart is regular, falling to 0 at its singular set (|sin θ| for spherical
    /// coordinates with polar angle θ).
    ///
    /// Written over any scalar, as the Lagrangian is: where two charts are both good, a run glues their
    /// discrete Lagrangians with weights that are smooth functions of these measures
    /// ([`crate::blend`]), and differentiates them.
    fn chart_quality<D: Scalar>(&self, _chart: usize, _q: &[D; N]) -> D {
        D::one()
    }

    /// Main-chart coordinates `q` of a point, moved to the representative nearest `near` (the last
    /// reported point), so that the reported motion is continuous across chart switches; `kinds` are
    /// those of the main chart's coordinates. The default moves each angle by whole turns; a main chart whose angles are periodic together (ϑ1 ± π,
    /// ϑ2 ∓ π of the double spherical pendulum) says so here.
    fn nearest_in_main(&self, q: [f64; N], near: &[f64; N], kinds: &[CoordinateKind; N]) -> [f64; N] {
        crate::chart::nearest_turns(q, near, kinds)
    }
}

/// A chart of a system's atlas other than the main one: its name and its coordinates, with their
/// roles (the group coordinates translated by the same symmetry as the main chart's) and kinds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Chart<const N: usize> {
    /// The chart's name, for messages.
    pub name: String,
    /// The chart's coordinates.
    pub coordinates: [Coordinate; N],
}

/// A reference to a system is the system: the engine holds systems by value, so that it can hold a
/// borrowed system and a system of its own (a chart of its atlas) alike.
impl<S: System<N> + ?Sized, const N: usize> System<N> for &S {
    fn coordinates(&self) -> [Coordinate; N] {
        (**self).coordinates()
    }

    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        (**self).lagrangian(q, v)
    }

    fn exact_solution(&self, q0: &[f64; N], p0: &[f64; N], t: f64) -> Option<[Option<f64>; N]> {
        (**self).exact_solution(q0, p0, t)
    }

    fn charts(&self) -> Vec<Chart<N>> {
        (**self).charts()
    }

    #[inline(always)]
    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        (**self).chart_to_main(chart, q)
    }

    #[inline(always)]
    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        (**self).main_to_chart(chart, q)
    }

    #[inline(always)]
    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &[D; N], v: &[D; N]) -> Option<D> {
        (**self).chart_lagrangian(chart, q, v)
    }

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &[D; N]) -> D {
        (**self).chart_quality(chart, q)
    }

    fn nearest_in_main(&self, q: [f64; N], near: &[f64; N], kinds: &[CoordinateKind; N]) -> [f64; N] {
        (**self).nearest_in_main(q, near, kinds)
    }
}

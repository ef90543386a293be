//! An atlas of charts (paper §6): "we can make computations on the whole Q by starting from a specific
//! compatible chart and changing to another one whenever it is necessary".
//!
//! A system declares its other charts through [`System::charts`](crate::System::charts), with the maps φ to the main chart
//! and ψ = φ⁻¹ from it ([`System::chart_to_main`](crate::System::chart_to_main), [`System::main_to_chart`](crate::System::main_to_chart)) and a measure of where each chart
//! is good ([`System::chart_quality`](crate::System::chart_quality)). The Lagrangian is written once, in the main chart; in chart c
//! it is L ∘ Tφ_c ([`InChart`]): L(φ(q'), Dφ(q') v'), with Dφ(q') v' from a dual number over the
//! scalar, so that dual numbers, the tracer and compiled code all apply. Each chart is a
//! retraction-compatible chart of its own, so a step in it is the paper's scheme in that chart:
//! symplectic, and equivariant where the group translates the chart's group coordinates.
//!
//! Before each step, the run chooses the chart for it at the step's predicted midpoint
//! ([`SWITCH_BELOW`]) and, if it is another, moves there: q' = ψ_b(φ_a(q)) and the momenta by the
//! cotangent lift p' = Dτ(q')ᵀ p of the transition τ = ψ_a ∘ φ_b ([`transition`]), a symplectic map.
//! Where the group translates the group coordinates of both charts (φ equivariant), Dτ maps the group
//! direction to itself exactly, so the momentum map J = p_g is carried over exactly.

pub use crate::chart::nearest_turns;
use num_dual::Dual;

use crate::dim::Dim;
use crate::mechanics::lagrangian::{Lagrangian, SystemIn};
use crate::{Coordinate, Scalar};

/// A step is taken in the main chart where the main chart's measure ([`System::chart_quality`](crate::System::chart_quality)) at
/// the step's midpoint is at least this (1/√2: 45° from the pole of spherical coordinates, where the
/// polar caps' measure is as large); elsewhere in the best chart with the main chart's group
/// coordinates if its measure is at least this, else in the best chart. The choice depends on the
/// midpoint alone, so a reversed step makes it alike and switches leave the run reversible: with
/// hysteresis (leaving at one measure, returning at another) a periodic motion would switch at
/// points that are not mirror images, and its energy would drift by the difference of the charts'
/// modified energies at each switch.
pub const SWITCH_BELOW: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A system seen in chart `chart` of its atlas (0: the main chart): the chart's coordinates, and the
/// Lagrangian L ∘ Tφ of the chart.
///
/// ```
/// use ddirac::{atlas::InChart, System, systems::SphericalPendulum};
/// use ddirac::mechanics::lagrangian::Lagrangian;
/// let pendulum = SphericalPendulum::default();
/// let (main, cap) = (InChart::new(&pendulum, 0), InChart::new(&pendulum, 1));
/// // The same state in the main chart (θ, φ) and in the lower cap's (x, y).
/// let (q, v) = ([0.3, 2.5], [0.2, -0.7]); // φ = 2.5: the lower hemisphere
/// let q_cap = pendulum.main_to_chart(1, &q);
/// let v_cap = ddirac::atlas::push_forward(&pendulum, &q, &v, 1);
/// assert!((main.lagrangian(&q, &v) - cap.lagrangian(&q_cap, &v_cap)).abs() < 1e-14);
/// ```
#[derive(Debug, Clone)]
pub struct InChart<S, Dm: Dim> {
    system: S,
    chart: usize,
    coordinates: Dm::Array<Coordinate>,
}

impl<S: SystemIn<Dm>, Dm: Dim> InChart<S, Dm> {
    /// `system` in chart `chart` (0 for the main chart). Panics for a chart the system does not have.
    pub fn new(system: S, chart: usize) -> Self {
        let coordinates = if chart == 0 { system.coordinates() } else { system.charts().swap_remove(chart - 1).1 };
        Self { system, chart, coordinates }
    }

    /// The chart's index (0: the main chart).
    pub fn chart(&self) -> usize {
        self.chart
    }

    /// The system in its main chart.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: SystemIn<Dm>, Dm: Dim> Lagrangian<Dm> for InChart<S, Dm> {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &Dm::Array<D>, v: &Dm::Array<D>) -> D {
        if self.chart == 0 {
            return self.system.lagrangian(q, v);
        }
        if let Some(written) = self.system.chart_lagrangian(self.chart, q, v) {
            return written;
        }
        // (φ(q), Dφ(q) v) from one evaluation of φ on dual numbers q + ε v.
        let dim = Dm::of(q);
        let lifted: Dm::Array<Dual<D>> = dim.array(|i| Dual::new(q[i], v[i]));
        let image = self.system.chart_to_main(self.chart, &lifted);
        self.system.lagrangian(&dim.array(|i| image[i].re), &dim.array(|i| image[i].eps))
    }
}

impl<S: SystemIn<Dm>, Dm: Dim> SystemIn<Dm> for InChart<S, Dm> {
    #[inline(always)]
    fn dim(&self) -> Dm {
        self.system.dim()
    }

    fn coordinates(&self) -> Dm::Array<Coordinate> {
        self.coordinates.clone()
    }

    fn exact_solution(&self, q0: &Dm::Array<f64>, p0: &Dm::Array<f64>, t: f64) -> Option<Dm::Array<Option<f64>>> {
        (self.chart == 0).then(|| self.system.exact_solution(q0, p0, t)).flatten()
    }

    fn chart_quality(&self, _chart: usize, q: &Dm::Array<f64>) -> f64 {
        self.system.chart_quality(self.chart, q)
    }
}

/// |a − b|∞ / (1 + |a|∞), infinite where an entry of either is not finite: how far a round trip
/// through a chart's maps lands from the point `a` it started from.
///
/// ```
/// let apart = ddirac::atlas::round_trip_distance(&[1.0, -3.0], &[1.0, -3.002]);
/// assert!((apart - 0.002 / 4.0).abs() < 1e-15);
/// assert_eq!(ddirac::atlas::round_trip_distance(&[1.0], &[f64::NAN]), f64::INFINITY);
/// ```
pub fn round_trip_distance(a: &[f64], b: &[f64]) -> f64 {
    let scale = 1.0 + a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (a, b)| if (a - b).is_finite() { m.max((a - b).abs()) } else { f64::INFINITY })
        / scale
}

/// A point of chart `chart` in the main chart (the identity for chart 0).
fn to_main<S: SystemIn<Dm>, Dm: Dim, D: Scalar>(system: &S, chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
    if chart == 0 {
        q.clone()
    } else {
        system.chart_to_main(chart, q)
    }
}

/// A point of the main chart in chart `chart` (the identity for chart 0).
fn from_main<S: SystemIn<Dm>, Dm: Dim, D: Scalar>(system: &S, chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
    if chart == 0 {
        q.clone()
    } else {
        system.main_to_chart(chart, q)
    }
}

/// The coordinates in chart `to` of the point with coordinates `q` in chart `from`, on any scalar.
pub(crate) fn map<S: SystemIn<Dm>, Dm: Dim, D: Scalar>(
    system: &S,
    from: usize,
    to: usize,
    q: &Dm::Array<D>,
) -> Dm::Array<D> {
    if from == to {
        return q.clone();
    }
    from_main(system, to, &to_main(system, from, q))
}

/// The coordinates in chart `to` of the point with coordinates `q` in chart `from`.
pub fn point<S: SystemIn<Dm>, Dm: Dim>(system: &S, from: usize, to: usize, q: &Dm::Array<f64>) -> Dm::Array<f64> {
    if from == to {
        return q.clone();
    }
    from_main(system, to, &to_main(system, from, q))
}

/// The velocity `v` at the main-chart point `q` in the coordinates of chart `chart`: Dψ(q) v.
pub fn push_forward<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
    chart: usize,
) -> Dm::Array<f64> {
    let dim = Dm::of(q);
    let lifted: Dm::Array<Dual<f64>> = dim.array(|i| Dual::new(q[i], v[i]));
    let image = from_main(system, chart, &lifted);
    dim.array(|i| image[i].eps)
}

/// The switch from chart `from` to chart `to` of the state (q, p) of chart `from`: the point in
/// chart `to`, and the momenta by the cotangent lift p' = Dτ(q')ᵀ p of the transition
/// τ = ψ_from ∘ φ_to (chart `to` → chart `from`), whose Jacobian is taken by dual numbers at q'.
/// Returns `None` when the result is not finite (the point is outside chart `to`).
pub fn transition<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    from: usize,
    to: usize,
    q: &Dm::Array<f64>,
    p: &Dm::Array<f64>,
) -> Option<(Dm::Array<f64>, Dm::Array<f64>)> {
    let dim = Dm::of(q);
    let q_to = point(system, from, to, q);
    let p_to = dim.array(|j| {
        let seeded: Dm::Array<Dual<f64>> = dim.array(|i| Dual::new(q_to[i], f64::from(u8::from(i == j))));
        let column = from_main(system, from, &to_main(system, to, &seeded));
        // Σ_i p_i ∂τ_i/∂q'_j, with exact zeros where τ_i does not depend on q'_j.
        column.as_ref().iter().zip(p.as_ref()).map(|(c, p)| c.eps * p).sum()
    });
    q_to.as_ref().iter().chain(p_to.as_ref()).all(|x| x.is_finite()).then_some((q_to, p_to))
}

/// The coordinates of each chart of `system`: the main chart (index 0) and the others.
pub fn all_charts<S: SystemIn<Dm>, Dm: Dim>(system: &S) -> Vec<Dm::Array<Coordinate>> {
    std::iter::once(system.coordinates()).chain(system.charts().into_iter().map(|(_, c)| c)).collect()
}

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
//! The charts' discrete Lagrangians are glued into one on Q × Q ([`crate::blend`]; orders 6 and 8
//! switch at a step instead, [`glues`]). Before each step
//! the run chooses the chart to solve it in — the one chart with weight at the step's ends, else the
//! best at its predicted midpoint ([`SWITCH_BELOW`]) — and, if it is another, moves there:
//! q' = ψ_b(φ_a(q)) and the momenta by the cotangent lift p' = Dτ(q')ᵀ p of the transition
//! τ = ψ_a ∘ φ_b ([`transition`]), a symplectic map.
//! Where the group translates the group coordinates of both charts (φ equivariant), Dτ maps the group
//! direction to itself exactly, so the momentum map J = p_g is carried over exactly.

pub use crate::chart::nearest_turns;
use num_dual::Dual;

use crate::blend::{partition, rise, sole};
use crate::chart::nearest_turns as turns;
use crate::dim::{Dim, Entry};
use crate::mechanics::discrete_lagrangian::by_rule;
use crate::mechanics::discrete_lagrangian::Rule;
use crate::mechanics::lagrangian::{Lagrangian, SystemIn};
use crate::{Coordinate, CoordinateKind, Scalar};

/// A step whose ends are where charts overlap ([`crate::blend`]) is solved in the main chart where the
/// main chart's measure ([`System::chart_quality`](crate::System::chart_quality)) at the step's
/// predicted midpoint is at least this (1/√2: 45° from the pole of spherical coordinates, where the
/// polar caps' measure is as large); elsewhere in the best chart with the main chart's group
/// coordinates if its measure is at least this, else in the best chart. The glued discrete
/// Lagrangian is the same function in each, so the choice is one of coordinates (of the conditioning
/// of the step's equations), not of the method.
pub const SWITCH_BELOW: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Whether a run with `method` glues its charts' discrete Lagrangians where they overlap
/// ([`crate::blend`]): for the rule alone and compositions of order 4. Compositions of order 6 and 8
/// switch charts at a step instead (each step with the scheme of the chart preferred at its
/// midpoint, [`SWITCH_BELOW`]): glued, their error holds the weights' high derivatives and loses their
/// order at the steps they are taken with (the over-the-top spherical pendulum's error at order 8 was
/// not monotone in h), while a switch is a step of the order of either chart's (an error O(h^{p+1})
/// where the two differ); the constant of the error then depends on where the steps fall.
pub fn glues(method: &crate::Method) -> bool {
    method.composition.order() < 6
}

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
    /// The atlas glued ([`crate::blend`]): the discrete Lagrangian is then the glued one.
    glue: Option<std::sync::Arc<Glue<S, Dm>>>,
}

impl<S: SystemIn<Dm>, Dm: Dim> InChart<S, Dm> {
    /// `system` in chart `chart` (0 for the main chart). Panics for a chart the system does not have.
    pub fn new(system: S, chart: usize) -> Self {
        let coordinates = if chart == 0 { system.coordinates() } else { system.charts().swap_remove(chart - 1).1 };
        Self { system, chart, coordinates, glue: None }
    }

    /// `system` in chart `chart` with the discrete Lagrangian of its atlas glued ([`crate::blend`]):
    /// the same function of two points of Q in every chart.
    pub(crate) fn glued(system: S, chart: usize) -> Self
    where
        S: Clone,
    {
        let glue = Some(std::sync::Arc::new(Glue::new(&system)));
        Self { glue, ..Self::new(system, chart) }
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

    #[inline(always)]
    fn discrete<D, B>(
        &self,
        rule: Rule,
        step: f64,
        base: &Dm::Array<B>,
        d0: &Dm::Array<D>,
        d1: &Dm::Array<D>,
    ) -> Option<D>
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        self.glue.as_ref().map(|glue| glue.discrete(self.chart, rule, step, base, d0, d1))
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

    fn chart_quality<D: Scalar>(&self, _chart: usize, q: &Dm::Array<D>) -> D {
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

/// How far (relative) a point may come back from a chart's maps there and back and still count as in
/// the chart.
pub(crate) const DOMAIN_TOLERANCE: f64 = 1e-6;

/// The measure of chart `chart` at the main-chart point `main` if the point is in the chart: its maps
/// take it there and back (a chart's ψ may be defined beyond its domain, as the projection of a
/// hemisphere is on the other one) and the measure is finite.
pub(crate) fn measure_at<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    kinds: &Dm::Array<CoordinateKind>,
    chart: usize,
    main: &Dm::Array<f64>,
) -> Option<f64> {
    if chart == 0 {
        return Some(system.chart_quality(0, main)).filter(|q| q.is_finite());
    }
    let there = point(system, 0, chart, main);
    let back = system.nearest_in_main(point(system, chart, 0, &there), main, kinds);
    let apart = round_trip_distance(main.as_ref(), back.as_ref());
    let measure = system.chart_quality(chart, &there);
    (apart <= DOMAIN_TOLERANCE && measure.is_finite()).then_some(measure)
}

/// The chart that alone has weight at the main-chart point `main`, if one does: the weights
/// w_c ∝ σ_c Π_{j<c} (1 − σ_j) of [`crate::blend`] leave one chart with weight exactly where one chart
/// in the domain has σ > 0 up to the first whose σ is one. Allocates nothing (it is asked at every
/// step's ends): [`sole`] of the charts' σ.
pub(crate) fn sole_chart<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    kinds: &Dm::Array<CoordinateKind>,
    charts: usize,
    main: &Dm::Array<f64>,
) -> Option<usize> {
    sole((0..charts).filter_map(|c| measure_at(system, kinds, c, main).map(|m| (c, rise(m)))))
}

/// The atlas glued: the Lagrangian of each chart, and the kinds of each chart's coordinates.
#[derive(Debug, Clone)]
pub(crate) struct Glue<S, Dm: Dim> {
    charts: Vec<InChart<S, Dm>>,
    kinds: Vec<Dm::Array<CoordinateKind>>,
}

impl<S: SystemIn<Dm> + Clone, Dm: Dim> Glue<S, Dm> {
    /// The charts of `system`'s atlas.
    pub fn new(system: &S) -> Self {
        let kinds = all_charts(system)
            .iter()
            .map(|coordinates| {
                let dim = Dm::of(coordinates);
                dim.array(|i| coordinates[i].kind)
            })
            .collect::<Vec<_>>();
        let charts = (0..kinds.len()).map(|c| InChart::new(system.clone(), c)).collect();
        Self { charts, kinds }
    }
}

impl<S: SystemIn<Dm>, Dm: Dim> Glue<S, Dm> {
    fn system(&self) -> &S {
        self.charts[0].system()
    }

    /// The weights at the point `x` of chart `chart` with the point in each chart that has weight:
    /// all to `chart` where no chart's measure reaches [`BLEND_FROM`].
    fn weights<D: Scalar>(&self, chart: usize, x: &Dm::Array<D>) -> Vec<(usize, D, Dm::Array<D>)> {
        let system = self.system();
        let dim = Dm::of(x);
        let main = point(system, chart, 0, &dim.array(|i| x[i].re()));
        let mut points = Vec::new();
        let rises = (0..self.charts.len()).filter_map(|c| {
            measure_at(system, &self.kinds[0], c, &main)?;
            let there = map(system, chart, c, x);
            let sigma = rise(system.chart_quality(c, &there));
            points.push((c, there));
            Some((c, sigma))
        });
        let weights = partition(rises);
        if weights.is_empty() {
            return vec![(chart, D::one(), x.clone())];
        }
        weights
            .into_iter()
            .map(|(c, w)| {
                let at = points.iter().position(|(p, _)| *p == c).expect("a point for each weighted chart");
                (c, w, points.swap_remove(at).1)
            })
            .collect()
    }

    /// The glued L_d at the points base + d0, base + d1 of chart `chart`.
    pub fn discrete<D, B>(
        &self,
        chart: usize,
        rule: Rule,
        step: f64,
        base: &Dm::Array<B>,
        d0: &Dm::Array<D>,
        d1: &Dm::Array<D>,
    ) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        let dim = Dm::of(d0);
        let x0 = dim.array(|i| d0[i] + base[i]);
        let x1 = dim.array(|i| d1[i] + base[i]);
        let (at0, at1) = (self.weights(chart, &x0), self.weights(chart, &x1));
        let mut used: Vec<usize> = at0.iter().chain(&at1).map(|(c, _, _)| *c).collect();
        used.sort_unstable();
        used.dedup();
        let zero = dim.array(|_| 0.0);
        let mut total = D::zero();
        for c in used {
            let find = |at: &[(usize, D, Dm::Array<D>)], x: &Dm::Array<D>| match at.iter().find(|(p, _, _)| *p == c) {
                Some((_, w, there)) => (*w, there.clone()),
                None => (D::zero(), map(self.system(), chart, c, x)),
            };
            let ((w0, y0), (w1, mut y1)) = (find(&at0, &x0), find(&at1, &x1));
            // The second point on the branch of the chart's angles nearest the first: the shift is a
            // constant, a number of whole turns.
            let (re0, re1) = (dim.array(|i| y0[i].re()), dim.array(|i| y1[i].re()));
            let near = if c == 0 {
                self.system().nearest_in_main(re1.clone(), &re0, &self.kinds[0])
            } else {
                turns(re1.clone(), &re0, &self.kinds[c])
            };
            for i in 0..dim.n() {
                y1[i] += near[i] - re1[i];
            }
            let lagrangian = &self.charts[c];
            let term = by_rule::<Dm, D, f64>(rule, step, &zero, &y0, &y1, |q, v| lagrangian.lagrangian(q, v));
            total += (w0 + w1) * 0.5 * term;
        }
        total
    }
}

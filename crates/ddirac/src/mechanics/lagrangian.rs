//! The Lagrangian L(q, v) as the engine evaluates it, and the system it belongs to, in a dimension
//! ([`crate::dim::Dim`]) fixed when the engine is compiled or chosen at run time.
//!
//! Every [`System`] is a Lagrangian and a [`SystemIn`] its fixed dimension ([`Fixed<N>`]); a system
//! whose number of coordinates is chosen at run time (a text spec's, [`crate::expression::ExpressionLagrangian`])
//! is one in [`Dynamic`]. The engine from the schemes to the stepper is written over a dimension and
//! runs either.

use crate::dim::{Dim, Dynamic, Entry, Fixed};
use crate::mechanics::rule::Rule;
use crate::{Chart, Coordinate, CoordinateKind, Scalar, System};

/// L(q, v) on arrays of a dimension, generic over the scalar.
pub trait Lagrangian<Dm: Dim> {
    /// L(q, v).
    fn lagrangian<D: Scalar>(&self, q: &Dm::Array<D>, v: &Dm::Array<D>) -> D;

    /// The discrete Lagrangian of `rule` and step `step` at q0 = base + d0, q1 = base + d1 where it is
    /// not the rule applied to [`Lagrangian::lagrangian`] (an atlas's charts glued: [`crate::blend`]);
    /// `None`, the default, where it is.
    #[inline(always)]
    fn discrete<D, B>(
        &self,
        _rule: Rule,
        _step: f64,
        _base: &Dm::Array<B>,
        _d0: &Dm::Array<D>,
        _d1: &Dm::Array<D>,
    ) -> Option<D>
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        None
    }
}

impl<S: System<N>, const N: usize> Lagrangian<Fixed<N>> for S {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        System::lagrangian(self, q, v)
    }
}

/// A system as the stepper runs it, in a dimension: [`System`]'s coordinates, reference solution and
/// atlas (paper §6) over the arrays of `Dm`. Every `System<N>` is one in `Fixed<N>`; see [`System`]
/// for what each method means.
pub trait SystemIn<Dm: Dim>: Lagrangian<Dm> {
    /// The dimension: the number of coordinates.
    fn dim(&self) -> Dm;

    /// The coordinates of the main chart.
    fn coordinates(&self) -> Dm::Array<Coordinate>;

    /// An exact reference solution, where known.
    fn exact_solution(&self, _q0: &Dm::Array<f64>, _p0: &Dm::Array<f64>, _t: f64) -> Option<Dm::Array<Option<f64>>> {
        None
    }

    /// The other charts of the atlas: each one's name and coordinates.
    fn charts(&self) -> Vec<(String, Dm::Array<Coordinate>)> {
        Vec::new()
    }

    /// φ: a point of chart `chart` in the main chart.
    fn chart_to_main<D: Scalar>(&self, _chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
        q.clone()
    }

    /// ψ = φ⁻¹: a point of the main chart in chart `chart`.
    fn main_to_chart<D: Scalar>(&self, _chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
        q.clone()
    }

    /// The Lagrangian in chart `chart`, where written down.
    fn chart_lagrangian<D: Scalar>(&self, _chart: usize, _q: &Dm::Array<D>, _v: &Dm::Array<D>) -> Option<D> {
        None
    }

    /// How good chart `chart` is at its point `q`.
    fn chart_quality<D: Scalar>(&self, _chart: usize, _q: &Dm::Array<D>) -> D {
        D::one()
    }

    /// A main-chart point `q` as the representative nearest `near`.
    fn nearest_in_main(
        &self,
        q: Dm::Array<f64>,
        near: &Dm::Array<f64>,
        kinds: &Dm::Array<CoordinateKind>,
    ) -> Dm::Array<f64> {
        crate::chart::nearest_turns(q, near, kinds)
    }
}

impl<S: System<N>, const N: usize> SystemIn<Fixed<N>> for S {
    #[inline(always)]
    fn dim(&self) -> Fixed<N> {
        Fixed
    }

    fn coordinates(&self) -> [Coordinate; N] {
        System::coordinates(self)
    }

    fn exact_solution(&self, q0: &[f64; N], p0: &[f64; N], t: f64) -> Option<[Option<f64>; N]> {
        System::exact_solution(self, q0, p0, t)
    }

    fn charts(&self) -> Vec<(String, [Coordinate; N])> {
        System::charts(self).into_iter().map(|Chart { name, coordinates }| (name, coordinates)).collect()
    }

    #[inline(always)]
    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        System::chart_to_main(self, chart, q)
    }

    #[inline(always)]
    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        System::main_to_chart(self, chart, q)
    }

    #[inline(always)]
    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &[D; N], v: &[D; N]) -> Option<D> {
        System::chart_lagrangian(self, chart, q, v)
    }

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &[D; N]) -> D {
        System::chart_quality(self, chart, q)
    }

    fn nearest_in_main(&self, q: [f64; N], near: &[f64; N], kinds: &[CoordinateKind; N]) -> [f64; N] {
        System::nearest_in_main(self, q, near, kinds)
    }
}

/// A system of a fixed dimension run in a dimension chosen at run time ([`Dynamic`]): the same
/// Lagrangian, coordinates, reference solution and atlas on `Vec`s. A run of it gives the numbers of
/// the system's own run bit for bit (the same operations in the same order), which is how the
/// dynamic path is tested against the fixed one.
///
/// ```
/// use ddirac::mechanics::lagrangian::AsDynamic;
/// use ddirac::{solve, Method, OutputOptions, systems::ChargedParticle};
/// let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(50));
/// let method = Method { reduced: true, ..Method::default() };
/// let fixed = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
/// let dynamic = solve(&AsDynamic(system), &problem, &method, &OutputOptions::default()).unwrap();
/// assert_eq!(fixed.q, dynamic.q);
/// ```
#[derive(Debug, Clone)]
pub struct AsDynamic<S, const N: usize>(pub S);

impl<S, const N: usize> AsDynamic<S, N> {
    fn array<T: Copy>(x: &[T]) -> [T; N] {
        x.try_into().expect("a dynamic array of the system's size")
    }
}

impl<S: System<N>, const N: usize> Lagrangian<Dynamic> for AsDynamic<S, N> {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &Vec<D>, v: &Vec<D>) -> D {
        self.0.lagrangian(&Self::array(q), &Self::array(v))
    }
}

impl<S: System<N>, const N: usize> SystemIn<Dynamic> for AsDynamic<S, N> {
    fn dim(&self) -> Dynamic {
        Dynamic(N)
    }

    fn coordinates(&self) -> Vec<Coordinate> {
        self.0.coordinates().to_vec()
    }

    fn exact_solution(&self, q0: &Vec<f64>, p0: &Vec<f64>, t: f64) -> Option<Vec<Option<f64>>> {
        self.0.exact_solution(&Self::array(q0), &Self::array(p0), t).map(|e| e.to_vec())
    }

    fn charts(&self) -> Vec<(String, Vec<Coordinate>)> {
        self.0.charts().into_iter().map(|c| (c.name, c.coordinates.to_vec())).collect()
    }

    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &Vec<D>) -> Vec<D> {
        self.0.chart_to_main(chart, &Self::array(q)).to_vec()
    }

    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &Vec<D>) -> Vec<D> {
        self.0.main_to_chart(chart, &Self::array(q)).to_vec()
    }

    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &Vec<D>, v: &Vec<D>) -> Option<D> {
        self.0.chart_lagrangian(chart, &Self::array(q), &Self::array(v))
    }

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &Vec<D>) -> D {
        self.0.chart_quality(chart, &Self::array(q))
    }

    fn nearest_in_main(&self, q: Vec<f64>, near: &Vec<f64>, kinds: &Vec<CoordinateKind>) -> Vec<f64> {
        self.0.nearest_in_main(Self::array(&q), &Self::array(near), &Self::array(kinds)).to_vec()
    }
}

/// A system by reference: what `&S` is for a [`System`], for a system in any dimension (a blanket
/// implementation for `&S` would overlap with that of every `System`).
#[derive(Debug)]
pub(crate) struct Borrowed<'a, S>(pub &'a S);

impl<S> Clone for Borrowed<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S> Copy for Borrowed<'_, S> {}

impl<S: Lagrangian<Dm>, Dm: Dim> Lagrangian<Dm> for Borrowed<'_, S> {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &Dm::Array<D>, v: &Dm::Array<D>) -> D {
        self.0.lagrangian(q, v)
    }
}

impl<S: SystemIn<Dm>, Dm: Dim> SystemIn<Dm> for Borrowed<'_, S> {
    #[inline(always)]
    fn dim(&self) -> Dm {
        self.0.dim()
    }

    fn coordinates(&self) -> Dm::Array<Coordinate> {
        self.0.coordinates()
    }

    fn exact_solution(&self, q0: &Dm::Array<f64>, p0: &Dm::Array<f64>, t: f64) -> Option<Dm::Array<Option<f64>>> {
        self.0.exact_solution(q0, p0, t)
    }

    fn charts(&self) -> Vec<(String, Dm::Array<Coordinate>)> {
        self.0.charts()
    }

    #[inline(always)]
    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
        self.0.chart_to_main(chart, q)
    }

    #[inline(always)]
    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &Dm::Array<D>) -> Dm::Array<D> {
        self.0.main_to_chart(chart, q)
    }

    #[inline(always)]
    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &Dm::Array<D>, v: &Dm::Array<D>) -> Option<D> {
        self.0.chart_lagrangian(chart, q, v)
    }

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &Dm::Array<D>) -> D {
        self.0.chart_quality(chart, q)
    }

    fn nearest_in_main(
        &self,
        q: Dm::Array<f64>,
        near: &Dm::Array<f64>,
        kinds: &Dm::Array<CoordinateKind>,
    ) -> Dm::Array<f64> {
        self.0.nearest_in_main(q, near, kinds)
    }
}

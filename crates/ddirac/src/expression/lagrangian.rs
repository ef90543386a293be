//! The Lagrangian of a text system for any number of coordinates: what the engine evaluates in a
//! dimension chosen at run time ([`crate::dim::Dynamic`]), where [`super::ExpressionSystem`] is the
//! same Lagrangian in a dimension fixed when the engine is compiled (one of [`crate::SIZES`]).
//!
//! Both evaluate the spec's compiled program the same way (the parameters folded in, or kept as
//! runtime inputs of a trace), so they give the same numbers.

use super::atlas::TextAtlas;
use super::compiled_spec::{compile, exact_at, own_lagrangian, Compiled, OpenLagrangian};
use super::{CompiledExpression, ExpressionError, ExpressionSpec};
use crate::dim::Dynamic;
use crate::mechanics::lagrangian::{Lagrangian, SystemIn};
use crate::{Coordinate, Scalar};

/// A text spec's Lagrangian L(q, v), of as many coordinates as the spec declares.
///
/// ```
/// use ddirac::expression::{ExpressionLagrangian, ExpressionSpec};
/// use ddirac::mechanics::lagrangian::Lagrangian;
/// use ddirac::Coordinate;
/// let n = 150;
/// let spec = ExpressionSpec {
///     coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
///     lagrangian: (0..n).map(|i| format!("0.5*x{i}_dot^2 - 0.5*x{i}^2")).collect::<Vec<_>>().join(" + "),
///     ..ExpressionSpec::default()
/// };
/// let l = ExpressionLagrangian::new(&spec).unwrap();
/// assert_eq!(l.coordinates().len(), 150);
/// assert_eq!(l.lagrangian(&vec![1.0; n], &vec![2.0; n]), 150.0 * (2.0 - 0.5));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpressionLagrangian {
    coordinates: Vec<Coordinate>,
    lagrangian: CompiledExpression,
    open: OpenLagrangian,
    exact: Vec<Option<CompiledExpression>>,
    atlas: Option<TextAtlas>,
}

impl ExpressionLagrangian {
    /// Checks and compiles the spec.
    pub fn new(spec: &ExpressionSpec) -> Result<Self, ExpressionError> {
        Ok(Self::from_compiled(compile(spec)?))
    }

    pub(super) fn from_compiled(compiled: Compiled) -> Self {
        let Compiled { coordinates, lagrangian, open, exact, atlas } = compiled;
        Self { coordinates, lagrangian, open, exact, atlas }
    }

    /// The spec's coordinates, in the order of q and v.
    pub fn coordinates(&self) -> &[Coordinate] {
        &self.coordinates
    }
}

impl Lagrangian<Dynamic> for ExpressionLagrangian {
    fn lagrangian<D: Scalar>(&self, q: &Vec<D>, v: &Vec<D>) -> D {
        own_lagrangian(&self.lagrangian, &self.open, self.coordinates.len(), q, v)
    }
}

/// The spec's coordinates, exact solution and atlas, as [`super::ExpressionSystem`] has them.
impl SystemIn<Dynamic> for ExpressionLagrangian {
    fn dim(&self) -> Dynamic {
        Dynamic(self.coordinates.len())
    }

    fn coordinates(&self) -> Vec<Coordinate> {
        self.coordinates.clone()
    }

    /// The given exact solutions at `t`; `q0` and `p0` are not used.
    fn exact_solution(&self, _q0: &Vec<f64>, _p0: &Vec<f64>, t: f64) -> Option<Vec<Option<f64>>> {
        if self.exact.iter().all(Option::is_none) {
            return None;
        }
        Some((0..self.coordinates.len()).map(|i| exact_at(&self.exact, i, t)).collect())
    }

    fn charts(&self) -> Vec<(String, Vec<Coordinate>)> {
        let charts = self.atlas.iter().flat_map(|atlas| &atlas.charts);
        charts.map(|c| (c.name.clone(), c.coordinates.clone())).collect()
    }

    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &Vec<D>) -> Vec<D> {
        match &self.atlas {
            Some(atlas) => (0..q.len()).map(|i| atlas.map(chart, true, q, i)).collect(),
            None => q.clone(),
        }
    }

    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &Vec<D>) -> Vec<D> {
        match &self.atlas {
            Some(atlas) => (0..q.len()).map(|i| atlas.map(chart, false, q, i)).collect(),
            None => q.clone(),
        }
    }

    fn chart_quality<D: crate::Scalar>(&self, chart: usize, q: &Vec<D>) -> D {
        self.atlas.as_ref().map_or(D::one(), |atlas| atlas.quality(chart, q))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::{Dim, Fixed};
    use crate::expression::ExpressionSystem;
    use crate::mechanics::dirac::LagrangeDirac;
    use crate::scheme::testing::{assert_alike, run};
    use crate::{Differentiation, DiscreteLagrangian, Method, Rule};

    /// `n` masses on a line joined by springs, the first to a wall, with ω_i² = 1 + i/n of their own.
    fn springs(n: usize) -> ExpressionSpec {
        let kinetic = (0..n).map(|i| format!("0.5*x{i}_dot^2"));
        let own = (0..n).map(|i| format!("0.5*{}*x{i}^2", 1.0 + i as f64 / n as f64));
        let joined = (1..n).map(|i| format!("0.5*k*(x{i} - x{})^2", i - 1));
        ExpressionSpec {
            coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
            lagrangian: kinetic.collect::<Vec<_>>().join(" + ")
                + " - ("
                + &own.chain(joined).collect::<Vec<_>>().join(" + ")
                + ")",
            parameters: vec![("k".into(), 0.7)],
            ..ExpressionSpec::default()
        }
    }

    #[test]
    fn a_text_system_steps_alike_in_a_fixed_and_a_dynamic_dimension() {
        const N: usize = 24;
        let spec = springs(N);
        let fixed_system = ExpressionSystem::<N>::new(&spec).unwrap();
        let dynamic_system = ExpressionLagrangian::new(&spec).unwrap();
        let q: [f64; N] = std::array::from_fn(|i| 0.3 * (i as f64).sin());
        let p: [f64; N] = std::array::from_fn(|i| 0.1 * (i as f64).cos());
        for choice in [Differentiation::Dual, Differentiation::Compiled] {
            let ld = DiscreteLagrangian::new(fixed_system.clone(), Rule::Midpoint, 0.01);
            let fixed = LagrangeDirac { ld, dim: Fixed::<N> };
            let ld = DiscreteLagrangian::new(dynamic_system.clone(), Rule::Midpoint, 0.01);
            let dynamic = LagrangeDirac { ld, dim: Dynamic(N) };
            let method = Method { rule: Rule::Midpoint, differentiation: choice, ..Method::default() };
            assert_alike(&fixed_system, &fixed, &dynamic, &method, q, p, 20);
        }
    }

    #[test]
    fn a_text_system_of_150_coordinates_steps_in_a_dynamic_dimension() {
        // 150 uncoupled oscillators released at rest from x = 1: the midpoint rule turns each
        // (x, p/ω) by 2 atan(ωh/2) per step, exactly, so x_k = cos(2k atan(ωh/2)).
        let n = 150;
        let omega = |i: usize| 1.0 + i as f64 / n as f64;
        let spec = ExpressionSpec {
            coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
            lagrangian: (0..n)
                .map(|i| format!("0.5*(x{i}_dot^2 - {}*x{i}^2)", omega(i).powi(2)))
                .collect::<Vec<_>>()
                .join(" + "),
            ..ExpressionSpec::default()
        };
        let (h, steps) = (0.01, 25);
        let scheme = LagrangeDirac {
            ld: DiscreteLagrangian::new(ExpressionLagrangian::new(&spec).unwrap(), Rule::Midpoint, h),
            dim: Dynamic(n),
        };
        for choice in [Differentiation::Dual, Differentiation::Compiled] {
            let rows = run(&scheme, choice, Dynamic(n).array(|_| 1.0), Dynamic(n).array(|_| 0.0), steps);
            for (k, (q, _)) in rows.iter().enumerate() {
                for (i, x) in q.iter().enumerate() {
                    let exact = (2.0 * (k + 1) as f64 * (omega(i) * h / 2.0).atan()).cos();
                    assert!((x - exact).abs() < 1e-12, "{choice:?}, step {}: x{i} = {x} against {exact}", k + 1);
                }
            }
        }
    }
}

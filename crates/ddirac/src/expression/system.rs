//! A [`System`] whose Lagrangian is given as text.
//!
//! The Lagrangian L(q, q̇) is an expression in the coordinates `q_i` (by name), their velocities
//! `<name>_dot`, the parameters and the definitions (named expressions, which may use all of these and
//! each other). A Lagrangian is autonomous: `t` is reserved and not available in it. Exact solutions,
//! if given, are expressions in `t` and the parameters only: the initial data q0, p0 of the problem
//! are *not* available in them, so an exact solution holds for one problem's initial data and must be
//! written for it. The constant `pi` is predefined unless a coordinate, parameter or definition takes
//! the name.

use super::compiled_spec::{compile, exact_at, own_lagrangian, Compiled, OpenLagrangian};
use super::{CompiledExpression, ExpressionError, ExpressionSpec};
use crate::{Chart, Coordinate, System};

/// A system with `N` coordinates whose Lagrangian is compiled from an [`ExpressionSpec`].
///
/// It is a [`System<N>`] for exactly the `N` it was built with: [`ExpressionSystem::new`] checks
/// that the spec has `N` coordinates, so it can be wrapped as `Erased::<_, N>` only for that `N`.
/// [`ExpressionSpec::into_dyn`] chooses `N` from the coordinate count.
///
/// ```
/// use ddirac::expression::{ExpressionError, ExpressionSpec, ExpressionSystem};
/// use ddirac::{Coordinate, System};
/// let spec = ExpressionSpec {
///     coordinates: vec![Coordinate::group("x")],
///     lagrangian: "0.5*m*x_dot^2".into(),
///     parameters: vec![("m".into(), 2.0)],
///     exact_solution: vec![("x".into(), "3*t".into())],
///     ..ExpressionSpec::default()
/// };
/// let system = ExpressionSystem::<1>::new(&spec).unwrap();
/// assert_eq!(system.lagrangian(&[0.0], &[3.0]), 9.0);
/// assert_eq!(system.exact_solution(&[0.0], &[6.0], 2.0), Some([Some(6.0)]));
/// assert!(matches!(ExpressionSystem::<2>::new(&spec), Err(ExpressionError::Dimension { .. })));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpressionSystem<const N: usize> {
    coordinates: [Coordinate; N],
    /// The spec's coordinates, the first of the `N`; the others are padding ([`crate::padding`]).
    own: usize,
    /// The mass of the padding coordinates.
    padding_mass: f64,
    lagrangian: CompiledExpression,
    open: OpenLagrangian,
    exact: Vec<Option<CompiledExpression>>,
    atlas: Option<super::atlas::TextAtlas>,
}

impl<const N: usize> ExpressionSystem<N> {
    /// Checks and compiles `spec`, which must have `N` coordinates.
    pub fn new(spec: &ExpressionSpec) -> Result<Self, ExpressionError> {
        if spec.coordinates.len() != N {
            return Err(ExpressionError::Dimension { expected: N, found: spec.coordinates.len() });
        }
        Self::from_compiled(compile(spec)?)
    }

    fn from_compiled(compiled: Compiled) -> Result<Self, ExpressionError> {
        let found = compiled.coordinates.len();
        if found != N {
            return Err(ExpressionError::Dimension { expected: N, found });
        }
        Ok(Self::padded(compiled))
    }

    /// The compiled spec (at most `N` coordinates) followed by padding coordinates up to `N`
    /// ([`crate::padding`]).
    pub(super) fn padded(compiled: Compiled) -> Self {
        let Compiled { coordinates, lagrangian, open, exact, atlas } = compiled;
        let own = coordinates.len();
        let coordinates = crate::padding::coordinates(&coordinates);
        let mut system = Self { coordinates, own, padding_mass: 0.0, lagrangian, open, exact, atlas };
        if own < N {
            system.padding_mass = crate::padding::mass(&system);
        }
        system
    }

    /// The compiled Lagrangian with the parameters folded in; its variables are q_0 … q_{N−1}, then
    /// their velocities.
    pub fn lagrangian_program(&self) -> &CompiledExpression {
        &self.lagrangian
    }
}

impl<const N: usize> System<N> for ExpressionSystem<N> {
    fn coordinates(&self) -> [Coordinate; N] {
        self.coordinates.clone()
    }

    /// With the parameters folded in, or, in a trace that keeps them as runtime inputs, read from
    /// those.
    fn lagrangian<D: crate::Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        let n = self.own;
        let own = own_lagrangian(&self.lagrangian, &self.open, n, q, v);
        if n < N {
            own + crate::padding::lagrangian(v, n, self.padding_mass)
        } else {
            own
        }
    }

    /// The given exact solutions at `t`; `q0` and `p0` are not used (see the module documentation).
    fn exact_solution(&self, _q0: &[f64; N], _p0: &[f64; N], t: f64) -> Option<[Option<f64>; N]> {
        if self.exact.iter().all(Option::is_none) {
            return None;
        }
        Some(std::array::from_fn(|i| exact_at(&self.exact, i, t)))
    }

    fn charts(&self) -> Vec<Chart<N>> {
        let charts = self.atlas.iter().flat_map(|atlas| &atlas.charts);
        charts
            .map(|c| Chart { name: c.name.clone(), coordinates: crate::padding::coordinates(&c.coordinates) })
            .collect()
    }

    fn chart_to_main<D: crate::Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        match &self.atlas {
            Some(atlas) => std::array::from_fn(|i| atlas.map(chart, true, q, i)),
            None => *q,
        }
    }

    fn main_to_chart<D: crate::Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        match &self.atlas {
            Some(atlas) => std::array::from_fn(|i| atlas.map(chart, false, q, i)),
            None => *q,
        }
    }

    fn chart_quality<D: crate::Scalar>(&self, chart: usize, q: &[D; N]) -> D {
        self.atlas.as_ref().map_or(D::one(), |atlas| atlas.quality(chart, &q[..self.own]))
    }
}

//! A [`System`] whose Lagrangian is given as text.
//!
//! The Lagrangian L(q, q̇) is an expression in the coordinates `q_i` (by name), their velocities
//! `<name>_dot`, the parameters and the definitions (named expressions, which may use all of these and
//! each other). A Lagrangian is autonomous: `t` is reserved and not available in it. Exact solutions,
//! if given, are expressions in `t` and the parameters only: the initial data q0, p0 of the problem
//! are *not* available in them, so an exact solution holds for one problem's initial data and must be
//! written for it. The constant `pi` is predefined unless a coordinate, parameter or definition takes
//! the name.

use super::compile::closest;
use super::{CompiledExpression, ExpressionError, ExpressionLagrangian, Origin, Scope, CONSTANTS, FUNCTIONS};
use crate::sizes::RuntimeSized;
use crate::{Chart, Coordinate, DynSystem, Erased, ErasedDynamic, System};

/// The text of a system: coordinates, Lagrangian, definitions, parameters and exact solutions, as a
/// spec file gives them.
///
/// ```
/// use ddirac::expression::ExpressionSpec;
/// use ddirac::Coordinate;
/// // A pendulum of length l: L = ½ m l² φ̇² + m g l cos φ.
/// let spec = ExpressionSpec {
///     coordinates: vec![Coordinate::shape("phi").angle()],
///     lagrangian: "0.5*m*l^2*phi_dot^2 + m*g*l*cos(phi)".into(),
///     parameters: vec![("m".into(), 1.0), ("l".into(), 2.0), ("g".into(), 9.8)],
///     ..ExpressionSpec::default()
/// };
/// let system = spec.into_dyn().unwrap();
/// assert_eq!(system.coordinates()[0].name, "phi");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExpressionSpec {
    /// The coordinates, in order; each `name` also declares the velocity `name_dot`.
    pub coordinates: Vec<Coordinate>,
    /// The Lagrangian.
    pub lagrangian: String,
    /// Definitions, name → source.
    pub definitions: Vec<(String, String)>,
    /// Parameters, name → value.
    pub parameters: Vec<(String, f64)>,
    /// Exact solutions, coordinate name → expression in `t` and the parameters.
    pub exact_solution: Vec<(String, String)>,
    /// With an atlas: where the main chart is good, an expression in the coordinates and the
    /// parameters (about 1 where regular, falling to 0 at its singular set).
    pub quality: Option<String>,
    /// The other charts of the atlas (paper §6; [`crate::atlas`]).
    pub charts: Vec<super::ChartSpec>,
}

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

/// The Lagrangian with its parameters as variables after q and q̇, for traces that keep them as
/// runtime inputs ([`crate::RuntimeInput::Parameter`]), so that one compiled program serves every
/// value of them; and the parameters' values. The folded Lagrangian is the same graph with the
/// parameters substituted as constants.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct OpenLagrangian {
    program: CompiledExpression,
    parameters: Vec<f64>,
}

/// A checked and compiled spec, before its dimension is fixed.
pub(super) struct Compiled {
    pub(super) coordinates: Vec<Coordinate>,
    pub(super) lagrangian: CompiledExpression,
    pub(super) open: OpenLagrangian,
    pub(super) exact: Vec<Option<CompiledExpression>>,
    pub(super) atlas: Option<super::atlas::TextAtlas>,
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
    fn padded(compiled: Compiled) -> Self {
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

    fn chart_quality(&self, chart: usize, q: &[f64; N]) -> f64 {
        self.atlas.as_ref().map_or(1.0, |atlas| atlas.quality(chart, &q[..self.own]))
    }
}

impl ExpressionSpec {
    /// Checks and compiles the spec into a type-erased system with as many coordinates as it declares.
    /// Up to the largest of [`crate::SIZES`] (16) it runs in an engine whose arrays are sized when it
    /// is compiled, on the stack; above, in a dimension chosen at run time ([`crate::dim::Dynamic`],
    /// [`ExpressionLagrangian`]).
    ///
    /// ```
    /// use ddirac::expression::{ExpressionError, ExpressionSpec};
    /// use ddirac::Coordinate;
    /// let chain = |n: usize| ExpressionSpec {
    ///     coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
    ///     lagrangian: (0..n).map(|i| format!("0.5*x{i}_dot^2")).collect::<Vec<_>>().join(" + "),
    ///     ..ExpressionSpec::default()
    /// };
    /// assert_eq!(chain(24).into_dyn().unwrap().coordinates().len(), 24);
    /// assert_eq!(chain(17).into_dyn().unwrap().coordinates().len(), 17);
    /// assert_eq!(chain(150).into_dyn().unwrap().coordinates().len(), 150);
    /// ```
    pub fn into_dyn(self) -> Result<Box<dyn DynSystem>, ExpressionError> {
        match crate::sizes::engine_size(self.coordinates.len()) {
            Some(size) => self.into_dyn_in(size),
            None => Ok(Box::new(ErasedDynamic(ExpressionLagrangian::from_compiled(compile(&self)?)))),
        }
    }

    /// [`ExpressionSpec::into_dyn`] in the engine of `size` coordinates, one of [`crate::SIZES`] and
    /// at least the spec's count; the coordinates beyond the spec's are padding
    /// ([`crate::padding`]). For comparing a padded run with an unpadded one, and for measuring what
    /// a larger engine costs.
    ///
    /// ```
    /// use ddirac::expression::{ExpressionError, ExpressionSpec};
    /// use ddirac::Coordinate;
    /// let spec = ExpressionSpec {
    ///     coordinates: vec![Coordinate::shape("x")],
    ///     lagrangian: "0.5*x_dot^2 - 0.5*x^2".into(),
    ///     ..ExpressionSpec::default()
    /// };
    /// assert_eq!(spec.clone().into_dyn_in(4).unwrap().coordinates().len(), 1);
    /// assert!(matches!(spec.into_dyn_in(17), Err(ExpressionError::EngineSize { size: 17, found: 1 })));
    /// ```
    pub fn into_dyn_in(self, size: usize) -> Result<Box<dyn DynSystem>, ExpressionError> {
        let compiled = compile(&self)?;
        let own = compiled.coordinates.clone();
        if own.len() > size {
            return Err(ExpressionError::EngineSize { size, found: own.len() });
        }
        macro_rules! dispatch {
            ($($n:literal)*) => {
                match size {
                    $($n => Box::new(Erased::<_, $n>(RuntimeSized::Text(ExpressionSystem::<$n>::padded(compiled))))
                        as Box<dyn DynSystem>,)*
                    _ => return Err(ExpressionError::EngineSize { size, found: own.len() }),
                }
            };
        }
        let inner = crate::sizes::with_sizes!(dispatch);
        Ok(if own.len() == size { inner } else { Box::new(crate::padding::Padded { inner, own, size }) })
    }
}

/// The exact solution of coordinate `i` at `t`, if the spec gives one.
pub(super) fn exact_at(exact: &[Option<CompiledExpression>], i: usize, t: f64) -> Option<f64> {
    exact.get(i)?.as_ref().map(|program| program.eval(&[t]))
}

/// L(q, v) of the spec's own `n` coordinates (the first n entries of `q` and `v`): with the
/// parameters folded in, or, in a trace that keeps them as runtime inputs, read from those.
#[inline(always)]
pub(super) fn own_lagrangian<D: crate::Scalar>(
    lagrangian: &CompiledExpression,
    open: &OpenLagrangian,
    n: usize,
    q: &[D],
    v: &[D],
) -> D {
    let parameters = &open.parameters;
    let runtime = |k: usize| D::runtime_input(crate::RuntimeInput::Parameter(k), parameters[k]);
    if !parameters.is_empty() && runtime(0).is_some() {
        let values: Vec<D> = (0..parameters.len()).map(|k| runtime(k).unwrap_or(D::from(parameters[k]))).collect();
        open.program.eval_with(|i| match i {
            _ if i < n => q[i],
            _ if i < 2 * n => v[i - n],
            _ => values[i - 2 * n],
        })
    } else {
        lagrangian.eval_with(|i| if i < n { q[i] } else { v[i - n] })
    }
}

fn velocity(name: &str) -> String {
    format!("{name}_dot")
}

pub(super) fn compile(spec: &ExpressionSpec) -> Result<Compiled, ExpressionError> {
    check_names(spec)?;
    let names = || spec.coordinates.iter().map(|c| c.name.clone());
    let mut lagrangian = Scope::new();
    let mut exact = Scope::new().variable("t");
    for name in names().chain(names().map(|n| velocity(&n))) {
        lagrangian = lagrangian.variable(&name);
        exact = exact.unavailable(&name, "an exact solution depends on `t` and the parameters only");
    }
    lagrangian = lagrangian.unavailable("t", "a Lagrangian does not depend on time (`t` is for exact solutions)");
    for &(name, value) in CONSTANTS {
        lagrangian = lagrangian.constant(name, value);
        exact = exact.constant(name, value);
    }
    for (name, value) in &spec.parameters {
        lagrangian = lagrangian.variable(name);
        exact = exact.constant(name, *value);
    }
    for (name, source) in &spec.definitions {
        lagrangian = lagrangian.definition(name, source);
        exact = exact.unavailable(name, "definitions are not available in exact solutions");
    }
    // One lowering with the parameters as inputs after q and q̇; the folded Lagrangian substitutes
    // their values.
    let (graph, root) = lagrangian.lower(Origin::Lagrangian, &spec.lagrangian)?;
    let parameters: Vec<f64> = spec.parameters.iter().map(|(_, v)| *v).collect();
    let mut values: Vec<Option<f64>> = vec![None; 2 * spec.coordinates.len()];
    values.extend(parameters.iter().copied().map(Some));
    let (folded, folded_root) = graph.substitute(&[root], &values);
    let lagrangian = CompiledExpression::new(folded.program(&folded_root));
    let open = OpenLagrangian { program: CompiledExpression::new(graph.program(&[root])), parameters };

    let mut solutions: Vec<Option<CompiledExpression>> = vec![None; spec.coordinates.len()];
    for (name, source) in &spec.exact_solution {
        let origin = Origin::ExactSolution(name.clone());
        let Some(i) = spec.coordinates.iter().position(|c| &c.name == name) else {
            let suggestion = closest(name, spec.coordinates.iter().map(|c| c.name.as_str()));
            return Err(ExpressionError::UnknownCoordinate { origin, name: name.clone(), suggestion });
        };
        if solutions[i].is_some() {
            let what = format!("an exact solution for `{name}`");
            return Err(ExpressionError::DuplicateName {
                origin,
                name: name.clone(),
                first: what.clone(),
                second: what,
            });
        }
        solutions[i] = Some(exact.compile(origin, source)?);
    }
    let atlas = super::atlas::compile(spec)?;
    Ok(Compiled { coordinates: spec.coordinates.clone(), lagrangian, open, exact: solutions, atlas })
}

/// Checks that every declared name is an identifier, not a function or a constant, and declared once.
fn check_names(spec: &ExpressionSpec) -> Result<(), ExpressionError> {
    if spec.coordinates.is_empty() {
        return Err(ExpressionError::NoCoordinates);
    }
    let mut declared: Vec<(String, String)> = vec![("t".into(), "the time `t` (reserved)".into())];
    let mut declare = |name: &str, what: String, origin: Origin| {
        let invalid = |reason: &str| ExpressionError::InvalidName {
            origin: origin.clone(),
            name: name.to_owned(),
            reason: reason.to_owned(),
        };
        let mut chars = name.chars();
        let identifier = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !identifier {
            return Err(invalid("a name is a letter or `_` followed by letters, digits and `_`"));
        }
        if FUNCTIONS.contains(&name) {
            return Err(invalid("it is the name of a function"));
        }
        if let Some(reason) = super::functions::constant(name) {
            return Err(invalid(&reason));
        }
        if let Some((_, first)) = declared.iter().find(|(n, _)| n == name) {
            let (name, first) = (name.to_owned(), first.clone());
            return Err(ExpressionError::DuplicateName { origin, name, first, second: what });
        }
        declared.push((name.to_owned(), what));
        Ok(())
    };
    for c in &spec.coordinates {
        declare(&c.name, format!("coordinate `{}`", c.name), Origin::Coordinate(c.name.clone()))?;
    }
    for c in &spec.coordinates {
        let what = format!("the velocity of coordinate `{}`", c.name);
        declare(&velocity(&c.name), what, Origin::Coordinate(c.name.clone()))?;
    }
    for (name, value) in &spec.parameters {
        let origin = Origin::Parameter(name.clone());
        declare(name, format!("parameter `{name}`"), origin.clone())?;
        if !value.is_finite() {
            return Err(ExpressionError::NonFinite { origin, value: *value });
        }
    }
    for (name, _) in &spec.definitions {
        declare(name, format!("definition `{name}`"), Origin::Definition(name.clone()))?;
    }
    Ok(())
}

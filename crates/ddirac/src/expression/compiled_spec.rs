//! A spec checked and compiled, before its dimension is fixed: the Lagrangian's program (with the
//! parameters folded in, and open as runtime inputs), the exact solutions and the atlas.

use super::atlas::TextAtlas;
use super::compile::closest;
use super::{CompiledExpression, ExpressionError, ExpressionSpec, Origin, Scope, CONSTANTS, FUNCTIONS};
use crate::Coordinate;

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
    pub(super) atlas: Option<TextAtlas>,
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

/// The names of a rigid body's attitude in its Lagrangian: the entries `R11` … `R33` of R (body to
/// space) and the body angular velocity `Omega1` … `Omega3`, in the order of the variables.
pub const ATTITUDE_NAMES: [&str; 12] =
    ["R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33", "Omega1", "Omega2", "Omega3"];

/// A rigid body's Lagrangian ℓ(R, Ω, s, ṡ) of the spec's Lagrangian, definitions and parameters: its
/// variables are [`ATTITUDE_NAMES`], then the spec's coordinates (the shape s), then their velocities
/// `<name>_dot`; the parameters are folded in.
pub(crate) fn compile_rigid(spec: &ExpressionSpec) -> Result<CompiledExpression, ExpressionError> {
    let attitude: Vec<(String, String)> = ATTITUDE_NAMES
        .iter()
        .map(|n| {
            let what = if n.starts_with('R') { "an entry of the attitude R" } else { "the body angular velocity Ω" };
            ((*n).to_owned(), format!("`{n}`, {what}"))
        })
        .collect();
    check_names_with(spec, attitude)?;
    let names = || spec.coordinates.iter().map(|c| c.name.clone());
    let mut scope = Scope::new();
    for name in ATTITUDE_NAMES.iter().map(|n| (*n).to_owned()).chain(names()).chain(names().map(|n| velocity(&n))) {
        scope = scope.variable(&name);
    }
    scope = scope.unavailable("t", "a Lagrangian does not depend on time");
    for &(name, value) in CONSTANTS {
        scope = scope.constant(name, value);
    }
    for (name, value) in &spec.parameters {
        scope = scope.constant(name, *value);
    }
    for (name, source) in &spec.definitions {
        scope = scope.definition(name, source);
    }
    scope.compile(Origin::Lagrangian, &spec.lagrangian)
}

/// Checks that every declared name is an identifier, not a function or a constant, and declared once.
fn check_names(spec: &ExpressionSpec) -> Result<(), ExpressionError> {
    if spec.coordinates.is_empty() {
        return Err(ExpressionError::NoCoordinates);
    }
    check_names_with(spec, vec![])
}

/// [`check_names`] with the names `reserved` (name, what it is) declared before the spec's.
fn check_names_with(spec: &ExpressionSpec, reserved: Vec<(String, String)>) -> Result<(), ExpressionError> {
    let mut declared: Vec<(String, String)> = vec![("t".into(), "the time `t` (reserved)".into())];
    declared.extend(reserved);
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

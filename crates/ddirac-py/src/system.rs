//! Systems: the built-in ones with parameter overrides, and systems whose Lagrangian is text (the
//! `[system]` table of a spec).

use std::sync::Arc;

use ddirac::expression::ExpressionSpec;
use ddirac::{Coordinate, CoordinateKind, DynSystem, Role};
use pyo3::prelude::*;

use crate::error::raise;

/// A system of the engine, whatever its type and number of coordinates.
#[pyclass(module = "ddirac._ddirac", frozen)]
pub struct SystemHandle {
    pub(crate) inner: Arc<dyn DynSystem>,
    /// The name `summary.json` gives it.
    #[pyo3(get)]
    pub name: String,
    /// The parameters it was built with, by name.
    #[pyo3(get)]
    pub parameters: Vec<(String, f64)>,
}

#[pymethods]
impl SystemHandle {
    /// The coordinates as (name, role, kind) with role `shape` or `group` and kind `real` or `angle`.
    #[getter]
    fn coordinates(&self) -> Vec<(String, &'static str, &'static str)> {
        self.inner
            .coordinates()
            .into_iter()
            .map(|c| {
                let role = if c.role == Role::Group { "group" } else { "shape" };
                let kind = if c.kind == CoordinateKind::Angle { "angle" } else { "real" };
                (c.name, role, kind)
            })
            .collect()
    }
}

/// The built-in system `name` with some of its parameters overridden.
#[pyfunction]
pub fn builtin_system(name: &str, parameters: Vec<(String, f64)>) -> PyResult<SystemHandle> {
    let Some(builtin) = ddirac::systems::find(name) else {
        let known: Vec<&str> = ddirac::systems::BUILT_IN.iter().map(|b| b.name).collect();
        return Err(raise(format!("no built-in system `{name}`; the built-in systems are: {}", known.join(", "))));
    };
    let defaults = (builtin.defaults)();
    if let Some((unknown, _)) = parameters.iter().find(|(p, _)| !defaults.iter().any(|(d, _)| d == p)) {
        let known: Vec<&str> = defaults.iter().map(|(d, _)| *d).collect();
        return Err(raise(format!("`{name}` has no parameter `{unknown}`; its parameters are: {}", known.join(", "))));
    }
    let inner = (builtin.build)(&parameters).map_err(crate::error::engine)?;
    let mut all: Vec<(String, f64)> = defaults.iter().map(|(d, v)| ((*d).to_owned(), *v)).collect();
    for (p, v) in &parameters {
        if let Some(slot) = all.iter_mut().find(|(d, _)| d == p) {
            slot.1 = *v;
        }
    }
    Ok(SystemHandle { inner: Arc::from(inner), name: name.to_owned(), parameters: all })
}

/// The names of the built-in systems with their one-line descriptions.
#[pyfunction]
pub fn builtin_names() -> Vec<(&'static str, &'static str)> {
    ddirac::systems::BUILT_IN.iter().map(|b| (b.name, b.description)).collect()
}

/// A system from a Lagrangian in text: the coordinates are `shape` then `group` (or `order`), the
/// `angles` among them on S¹; definitions, parameters and exact solutions by name, in order.
#[pyfunction]
#[pyo3(signature = (lagrangian, shape, group, angles, definitions, parameters, exact, order=None, name=None))]
#[allow(clippy::too_many_arguments)]
pub fn text_system(
    lagrangian: String,
    shape: Vec<String>,
    group: Vec<String>,
    angles: Vec<String>,
    definitions: Vec<(String, String)>,
    parameters: Vec<(String, f64)>,
    exact: Vec<(String, String)>,
    order: Option<Vec<String>>,
    name: Option<String>,
) -> PyResult<SystemHandle> {
    let declared: Vec<(String, Role)> =
        shape.iter().map(|x| (x.clone(), Role::Shape)).chain(group.iter().map(|g| (g.clone(), Role::Group))).collect();
    if let Some(both) = shape.iter().find(|x| group.contains(x)) {
        return Err(raise(format!("coordinate `{both}` is listed in both `shape` and `group`")));
    }
    let names: Vec<&str> = declared.iter().map(|(n, _)| n.as_str()).collect();
    if let Some(a) = angles.iter().find(|a| !names.contains(&a.as_str())) {
        return Err(raise(format!("`{a}` in `angles` is not a coordinate; the coordinates are: {}", names.join(", "))));
    }
    let ordered: Vec<(String, Role)> = match order {
        None => declared.clone(),
        Some(order) => {
            let is_permutation = order.len() == declared.len()
                && declared.iter().all(|(n, _)| order.iter().filter(|o| *o == n).count() == 1);
            if !is_permutation {
                return Err(raise(format!(
                    "`order` must list every coordinate once: {} (it is {})",
                    names.join(", "),
                    order.join(", ")
                )));
            }
            order.iter().map(|o| declared.iter().find(|(n, _)| n == o).cloned().expect("a permutation")).collect()
        }
    };
    let coordinates: Vec<Coordinate> = ordered
        .into_iter()
        .map(|(n, role)| {
            let c = match role {
                Role::Shape => Coordinate::shape(&n),
                Role::Group => Coordinate::group(&n),
            };
            if angles.contains(&n) {
                c.angle()
            } else {
                c
            }
        })
        .collect();
    let mut sources = vec![("lagrangian".to_owned(), lagrangian.clone())];
    sources.extend(definitions.iter().map(|(n, v)| (format!("definition:{n}"), v.clone())));
    sources.extend(exact.iter().map(|(n, v)| (format!("exact:{n}"), v.clone())));
    let coordinate_names: Vec<String> = coordinates.iter().map(|c| c.name.clone()).collect();
    let parameter_names: Vec<String> = parameters.iter().map(|(n, _)| n.clone()).collect();
    let definition_names: Vec<String> = definitions.iter().map(|(n, _)| n.clone()).collect();
    let declared = crate::error::Declared {
        coordinates: &coordinate_names,
        parameters: &parameter_names,
        definitions: &definition_names,
        rigid: false,
    };
    let spec = ExpressionSpec {
        coordinates,
        lagrangian,
        definitions,
        parameters: parameters.clone(),
        exact_solution: exact,
        ..ExpressionSpec::default()
    };
    let inner = spec.into_dyn().map_err(|e| crate::error::expression(e, &sources, &declared))?;
    Ok(SystemHandle { inner: Arc::from(inner), name: name.unwrap_or_else(|| "custom".to_owned()), parameters })
}

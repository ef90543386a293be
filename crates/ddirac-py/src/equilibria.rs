//! `ddirac.relative_equilibria`: the relative equilibrium of the reduced discrete map of a run's
//! method and step on the momentum level of its initial data ([`ddirac::relative_equilibrium`]), as
//! `ddirac equilibria` finds it, returned as a dict of arrays; `ddirac.relative_equilibrium_family`:
//! its continuation along the momentum of a group coordinate, as `ddirac equilibria --family` does.

use ddirac::relative_equilibrium::{family, find, RelativeEquilibrium, SearchOptions};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::engine;
use crate::simulate::RunArgs;
use crate::system::SystemHandle;

/// The relative equilibrium nearest to the initial shape and shape momenta of `run_args`, on the level
/// of its initial group momenta, for the method and step of `run_args`.
#[pyfunction]
pub fn relative_equilibrium<'py>(
    py: Python<'py>,
    system: &SystemHandle,
    run_args: RunArgs,
) -> PyResult<Bound<'py, PyDict>> {
    let (problem, method) = run_args.problem_and_method(&*system.inner)?;
    let inner = system.inner.clone();
    let found =
        py.detach(move || find(inner.as_ref(), &problem, &method, &SearchOptions::default())).map_err(engine)?;
    as_dict(py, &found)
}

/// The family of relative equilibria through the one nearest to the initial shape of `run_args`,
/// continued along the momentum of the group coordinate `along` over `values`
/// ([`ddirac::relative_equilibrium::family`]): `{"members": [dict, ...], "ended": None or (value,
/// message), "stability_changes": [(a, b), ...], "folds": [(momentum, shape, shape_momentum,
/// next_member), ...]}`.
#[pyfunction]
pub fn relative_equilibrium_family<'py>(
    py: Python<'py>,
    system: &SystemHandle,
    run_args: RunArgs,
    along: String,
    values: Vec<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (problem, method) = run_args.problem_and_method(&*system.inner)?;
    let inner = system.inner.clone();
    let found = py
        .detach(move || family(inner.as_ref(), &problem, &method, &along, &values, &SearchOptions::default()))
        .map_err(engine)?;
    let members = found.members.iter().map(|m| as_dict(py, m)).collect::<PyResult<Vec<_>>>()?;
    let d = PyDict::new(py);
    d.set_item("members", members)?;
    d.set_item("ended", found.ended.as_ref().map(|(value, error)| (*value, error.to_string())))?;
    d.set_item("stability_changes", found.stability_changes())?;
    let folds: Vec<_> =
        found.folds.iter().map(|f| (f.momentum, f.shape.clone(), f.shape_momentum.clone(), f.next_member)).collect();
    d.set_item("folds", folds)?;
    Ok(d)
}

/// A relative equilibrium as a dict of arrays.
fn as_dict<'py>(py: Python<'py>, found: &RelativeEquilibrium) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("shape_names", found.shape_names.clone())?;
    d.set_item("group_names", found.group_names.clone())?;
    d.set_item("shape", PyArray1::from_vec(py, found.shape.clone()))?;
    d.set_item("shape_momentum", PyArray1::from_vec(py, found.shape_momentum.clone()))?;
    d.set_item("momentum", PyArray1::from_vec(py, found.momentum.clone()))?;
    d.set_item("group_velocity", PyArray1::from_vec(py, found.group_velocity.clone()))?;
    let k = found.multipliers.len();
    let flat: Vec<f64> = found.multipliers.iter().flat_map(|&(re, im)| [re, im]).collect();
    d.set_item("multipliers", PyArray1::from_vec(py, flat).reshape([k, 2])?)?;
    d.set_item("step", found.step)?;
    d.set_item("stable", found.stable)?;
    d.set_item("modulus_tolerance", found.modulus_tolerance)?;
    d.set_item("determinant", found.determinant)?;
    d.set_item("residual", found.residual)?;
    d.set_item("iterations", found.iterations)?;
    d.set_item("ambiguous", found.ambiguous.clone())?;
    Ok(d)
}

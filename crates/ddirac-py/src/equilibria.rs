//! `ddirac.relative_equilibria`: the relative equilibrium of the reduced discrete map of a run's
//! method and step on the momentum level of its initial data ([`ddirac::relative_equilibrium`]), as
//! `ddirac equilibria` finds it, returned as a dict of arrays.

use ddirac::relative_equilibrium::{find, SearchOptions};
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

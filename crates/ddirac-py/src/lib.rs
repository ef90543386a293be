//! `ddirac._ddirac`: the extension module under the Python package `ddirac` (`python/ddirac`).
//!
//! It offers the engine in plain types (lists, tuples, floats, strings) and returns NumPy arrays; the
//! Python package shapes the public API on top (`ddirac.System`, `ddirac.simulate`, `ddirac.Error`).
//! Integration runs with the GIL released.

mod check;
mod ensemble;
mod equilibria;
mod error;
mod overhead;
mod rigid;
mod simulate;
mod spec;
mod system;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _ddirac(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<error::Error>())?;
    m.add("SpecError", py.get_type::<error::SpecError>())?;
    m.add("ExpressionError", py.get_type::<error::ExpressionError>())?;
    m.add("InvarianceError", py.get_type::<error::InvarianceError>())?;
    m.add("ConvergenceError", py.get_type::<error::ConvergenceError>())?;
    m.add_class::<system::SystemHandle>()?;
    m.add_class::<rigid::RigidHandle>()?;
    m.add_function(wrap_pyfunction!(rigid::rigid_body, m)?)?;
    m.add_function(wrap_pyfunction!(rigid::rigid_text_system, m)?)?;
    m.add_function(wrap_pyfunction!(rigid::simulate_rigid, m)?)?;
    m.add_function(wrap_pyfunction!(system::builtin_system, m)?)?;
    m.add_function(wrap_pyfunction!(system::text_system, m)?)?;
    m.add_function(wrap_pyfunction!(system::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(check::check, m)?)?;
    m.add_function(wrap_pyfunction!(equilibria::relative_equilibrium, m)?)?;
    m.add_function(wrap_pyfunction!(equilibria::relative_equilibrium_family, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::method_keys, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::time_grid, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::convergence_stability, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::orders_agree, m)?)?;
    m.add("STABLE", ddirac_cli::convergence::STABLE)?;
    m.add_function(wrap_pyfunction!(ensemble::ensemble, m)?)?;
    m.add_function(wrap_pyfunction!(ensemble::ensemble_members, m)?)?;
    m.add_function(wrap_pyfunction!(overhead::rust_seconds, m)?)?;
    m.add_class::<spec::LoadedSpec>()?;
    m.add_function(wrap_pyfunction!(spec::load_spec, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

//! Spec files from Python: `ddirac.load(path, overrides)` reads and validates a spec as `ddirac run`
//! does (the overrides are its `--set` assignments), and runs it into arrays or into an output
//! directory.

use std::path::PathBuf;
use std::sync::Arc;

use ddirac::{InitialMomentum, Method, OutputOptions, Problem};
use ddirac_cli::diagnostics::CliError;
use ddirac_cli::keys::method::{MethodKey, MethodKeys};
use ddirac_cli::run::{self, Loaded, RunOptions};
use miette::{GraphicalReportHandler, GraphicalTheme};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::SpecError;
use crate::simulate::interruptible;
use crate::system::SystemHandle;

/// A command-line error as `ddirac.Error`, with the diagnostic `ddirac run` prints (the spec line
/// underlined), without colours.
pub(crate) fn cli_error(error: CliError) -> PyErr {
    let error = match error {
        CliError::Integration(engine) => return crate::error::engine(engine),
        // No spec text to quote: the message alone, unwrapped, so that it can be searched for.
        CliError::Members { .. } | CliError::Merge(_) | CliError::Set { .. } => {
            return SpecError::new_err(error.to_string())
        }
        other => other,
    };
    let report: miette::Report = error.into();
    let mut text = String::new();
    let handler = GraphicalReportHandler::new_themed(GraphicalTheme::unicode_nocolor()).with_width(100);
    match handler.render_report(&mut text, report.as_ref()) {
        Ok(()) => SpecError::new_err(text.trim_end().to_owned()),
        Err(_) => SpecError::new_err(report.to_string()),
    }
}

/// A validated spec.
#[pyclass(module = "ddirac._ddirac", frozen)]
pub struct LoadedSpec {
    path: PathBuf,
    set: Vec<String>,
    system: Arc<dyn ddirac::DynSystem>,
    #[pyo3(get)]
    name: String,
    #[pyo3(get)]
    parameters: Vec<(String, f64)>,
    problem: Problem,
    method: Method,
    output: OutputOptions,
    /// Where `ddirac run` would write it.
    #[pyo3(get)]
    directory: PathBuf,
    /// What the overrides did that the user may not expect (the step h that overriding another key
    /// of `[time]` gives), as `ddirac run` prints them as `note: …`.
    #[pyo3(get)]
    notes: Vec<String>,
}

/// Reads the spec at `path` with the `--set` assignments `set`, as `ddirac run` does.
#[pyfunction]
pub fn load_spec(path: PathBuf, set: Vec<String>) -> PyResult<LoadedSpec> {
    let Loaded { plan, notes, .. } = run::load(&path, &set).map_err(cli_error)?;
    let directory = run::output_dir(None, &plan, &path);
    Ok(LoadedSpec {
        path,
        set,
        system: Arc::from(plan.system),
        name: plan.name,
        parameters: plan.parameters,
        problem: plan.problem,
        method: plan.method,
        output: plan.output,
        directory,
        notes,
    })
}

#[pymethods]
impl LoadedSpec {
    /// The spec's system.
    #[getter]
    fn system(&self) -> SystemHandle {
        SystemHandle { inner: self.system.clone(), name: self.name.clone(), parameters: self.parameters.clone() }
    }

    /// The time grid and initial data: (step, steps, q0, p0 or None, v0 or None).
    #[allow(clippy::type_complexity)]
    #[getter]
    fn problem(&self) -> (f64, usize, Vec<f64>, Option<Vec<f64>>, Option<Vec<f64>>) {
        let (p, v) = match &self.problem.initial {
            InitialMomentum::Momentum(p) => (Some(p.clone()), None),
            InitialMomentum::Velocity(v) => (None, Some(v.clone())),
        };
        (self.problem.step, self.problem.steps, self.problem.q0.clone(), p, v)
    }

    /// The method's keys as the spec's `[method]` table names them ([`MethodKeys::of`]).
    #[getter]
    fn method<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let k = MethodKeys::of(&self.method);
        let d = PyDict::new(py);
        for key in MethodKey::ALL {
            match key {
                MethodKey::Rule => d.set_item(key.name(), &k.rule)?,
                MethodKey::Variant => d.set_item(key.name(), &k.variant)?,
                MethodKey::Reduced => d.set_item(key.name(), k.reduced)?,
                MethodKey::Connection => d.set_item(key.name(), &k.connection)?,
                MethodKey::Tolerance => d.set_item(key.name(), k.tolerance)?,
                MethodKey::MaxIterations => d.set_item(key.name(), k.max_iterations)?,
                MethodKey::Jacobian => d.set_item(key.name(), &k.jacobian)?,
                MethodKey::Derivatives => d.set_item(key.name(), &k.derivatives)?,
                MethodKey::CheckInvariance => d.set_item(key.name(), k.check_invariance)?,
                MethodKey::OnEnergyJump => d.set_item(key.name(), &k.on_energy_jump)?,
                MethodKey::EnergyJumpThreshold => d.set_item(key.name(), k.energy_jump_threshold)?,
                MethodKey::Order => d.set_item(key.name(), k.order)?,
                MethodKey::Composition => d.set_item(key.name(), &k.composition)?,
                MethodKey::Atlas => d.set_item(key.name(), k.atlas)?,
                MethodKey::Sensitivities => d.set_item(key.name(), k.sensitivities)?,
                MethodKey::ConnectionRow(_) | MethodKey::ConnectionEntry(..) => {}
            }
        }
        Ok(d)
    }

    /// Integrates the spec into arrays (the dict `ddirac.simulate` returns), writing no file.
    #[pyo3(signature = (progress=None))]
    fn run_arrays<'py>(&self, py: Python<'py>, progress: Option<Py<PyAny>>) -> PyResult<Bound<'py, PyDict>> {
        let system = self.system();
        crate::simulate::run(py, &system, self.problem.clone(), self.method.clone(), self.output, progress)
    }

    /// Runs the spec as `ddirac run --quiet` does into `out` (default: the spec's directory) and
    /// returns the directory.
    #[pyo3(signature = (out=None))]
    fn run_files(&self, py: Python<'_>, out: Option<PathBuf>) -> PyResult<PathBuf> {
        let out = out.unwrap_or_else(|| self.directory.clone());
        let options = RunOptions {
            spec: self.path.clone(),
            out: Some(out.clone()),
            set: self.set.clone(),
            quiet: true,
            format: vec![],
        };
        interruptible(py, move || run::run(&options))?.map_err(cli_error)?;
        Ok(out)
    }
}

//! One run: problem and method from plain arguments, the rows gathered into arrays while the GIL is
//! released, and the summary as the dict `summary.json` holds.

use ddirac::{DynSystem, Method, OutputOptions, Problem, Summary};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::conversion::FromPyObjectOwned;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::error::{engine, raise};
use crate::system::SystemHandle;
use ddirac_cli::keys::{
    self, initial::Values, method::MethodKey, method::MethodKeys, time::TimeKeys, KeyError, Spelling,
};
use ddirac_cli::report::{summary_json_of, RunRecord};

/// The method keys of a run as the Python package passes them: a dict with the keys of a spec's
/// `[method]` table that were given ([`MethodKey::ALL`]), read into [`MethodKeys`].
pub(crate) struct MethodArgs(pub(crate) MethodKeys);

impl<'a, 'py> FromPyObject<'a, 'py> for MethodArgs {
    type Error = PyErr;

    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let dict = ob.cast::<PyDict>()?;
        if let Some(key) = dict.keys().iter().find_map(|k| {
            let name = k.extract::<String>().unwrap_or_default();
            (!MethodKey::ALL.iter().any(|m| m.name() == name)).then_some(name)
        }) {
            return Err(raise(format!("unknown method key {key:?}")));
        }
        fn get<'py, T: FromPyObjectOwned<'py>>(dict: &Bound<'py, PyDict>, key: MethodKey) -> PyResult<Option<T>> {
            match dict.get_item(key.name())? {
                Some(value) if !value.is_none() => value
                    .extract::<T>()
                    .map(Some)
                    .map_err(|e| raise(format!("{}: {}", key.spelled(Spelling::Argument), e.into()))),
                _ => Ok(None),
            }
        }
        Ok(MethodArgs(MethodKeys {
            rule: get(&dict, MethodKey::Rule)?,
            variant: get(&dict, MethodKey::Variant)?,
            reduced: get(&dict, MethodKey::Reduced)?,
            connection: get(&dict, MethodKey::Connection)?,
            tolerance: get(&dict, MethodKey::Tolerance)?,
            max_iterations: get(&dict, MethodKey::MaxIterations)?,
            jacobian: get(&dict, MethodKey::Jacobian)?,
            derivatives: get(&dict, MethodKey::Derivatives)?,
            check_invariance: get(&dict, MethodKey::CheckInvariance)?,
            on_energy_jump: get(&dict, MethodKey::OnEnergyJump)?,
            energy_jump_threshold: get(&dict, MethodKey::EnergyJumpThreshold)?,
            order: get(&dict, MethodKey::Order)?,
            composition: get(&dict, MethodKey::Composition)?,
            atlas: get(&dict, MethodKey::Atlas)?,
            sensitivities: get(&dict, MethodKey::Sensitivities)?,
        }))
    }
}

/// A vector of the initial data as Python passes it: a list in the coordinate order, or a list of
/// (name, value) pairs.
#[derive(FromPyObject)]
pub(crate) enum VectorArg {
    InOrder(Vec<f64>),
    ByName(Vec<(String, f64)>),
}

impl VectorArg {
    pub(crate) fn values(self) -> Values {
        match self {
            VectorArg::InOrder(list) => Values::InOrder(list),
            VectorArg::ByName(entries) => Values::ByName(entries),
        }
    }
}

/// What a run is made of, as the Python package passes it (a dict): initial data (`q0` with exactly one
/// of `p0` and `v0`), time grid (two or three of `step`, `steps`, `duration`) and the `method` keys,
/// checked by the rules of [`ddirac_cli::keys`] that a spec file's keys follow.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct RunArgs {
    q0: VectorArg,
    p0: Option<VectorArg>,
    v0: Option<VectorArg>,
    step: Option<f64>,
    steps: Option<i64>,
    duration: Option<f64>,
    method: MethodArgs,
}

impl RunArgs {
    /// The problem and the method for `system`, or an error naming what is wrong.
    pub(crate) fn problem_and_method(self, system: &dyn DynSystem) -> PyResult<(Problem, Method)> {
        let coordinates = system.coordinates();
        let names: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
        let (q0, momentum) = keys::initial::initial(
            &self.q0.values(),
            self.p0.map(VectorArg::values).as_ref(),
            self.v0.map(VectorArg::values).as_ref(),
            &names,
            Spelling::Argument,
        )
        .map_err(text)?;
        let grid = TimeKeys { step: self.step, steps: self.steps, duration: self.duration };
        let (step, steps) = keys::time::grid(&grid, Spelling::Argument).map_err(text)?;
        let method = keys::method::method(&self.method.0, &coordinates, Spelling::Argument).map_err(text)?;
        Ok((Problem::new(step, steps, q0, momentum), method))
    }
}

/// A refused key as the exception Python raises.
fn text<K>(error: KeyError<K>) -> PyErr {
    raise(error.text())
}

/// The step h and the number of steps N of a time grid given by two of `step`, `steps` and `duration`
/// (all three when they agree), as a spec's `[time]` table gives it.
#[pyfunction]
pub fn time_grid(step: Option<f64>, steps: Option<i64>, duration: Option<f64>) -> PyResult<(f64, usize)> {
    keys::time::grid(&TimeKeys { step, steps, duration }, Spelling::Argument).map_err(text)
}

/// The finest stretch of a convergence table's rows whose consecutive observed orders agree within
/// `STABLE` (10 %), as (first row, last row, mean order): the rule of `ddirac convergence`.
#[pyfunction]
pub fn convergence_stability(orders: Vec<Option<f64>>) -> Option<(usize, usize, f64)> {
    ddirac_cli::convergence::stability_of(&orders).map(|s| (s.rows.0, s.rows.1, s.order))
}

/// Whether two orders agree within `STABLE` of the larger (both positive): the rule of `ddirac
/// convergence`.
#[pyfunction]
pub fn orders_agree(a: f64, b: f64) -> bool {
    ddirac_cli::convergence::agree(a, b)
}

/// The names of the method keys, in the order of a spec's `[method]` table.
#[pyfunction]
pub fn method_keys() -> Vec<&'static str> {
    MethodKey::ALL.iter().map(|k| k.name()).collect()
}

/// Integrates and gathers the rows column by column: the whole work of a run from Python but the
/// arrays' hand-over.
pub(crate) fn collect(
    system: &dyn ddirac::DynSystem,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    watch: &mut dyn FnMut(usize) -> Result<(), ddirac::OutputError>,
) -> Result<(Columns, ddirac::Summary), ddirac::Error> {
    let mut columns = Columns::default();
    let observer = &mut |row: &ddirac::Row<'_>| -> Result<(), ddirac::OutputError> {
        columns.t.push(row.t);
        columns.q.extend_from_slice(row.q);
        columns.p.extend_from_slice(row.p);
        columns.energy.push(row.energy);
        columns.discrete_energy.push(row.discrete_energy.unwrap_or(f64::NAN));
        columns.momentum_map.extend_from_slice(row.momentum_map);
        columns.chart.push(row.chart as i64);
        Ok(())
    };
    let summary = system.integrate_watched(problem, method, output, observer, watch)?;
    Ok((columns, summary))
}

/// The watch's message when a Python signal handler or the progress callback raised: the run stopped
/// for it.
#[derive(Debug)]
struct SignalRaised;

impl std::fmt::Display for SignalRaised {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a Python signal handler raised")
    }
}

impl std::error::Error for SignalRaised {}

/// How often a run reports its progress to the callback of [`simulate`].
pub(crate) const PROGRESS_EVERY: Duration = Duration::from_millis(100);

/// Runs `work` on the calling thread with the GIL released, handing it a watch for the engine's
/// step loop ([`ddirac::integrate_watched`]) that runs Python's signal handlers every
/// [`SIGNAL_POLL`] and calls `progress(k)` every [`PROGRESS_EVERY`]: a handler that raises (Ctrl-C's
/// `KeyboardInterrupt`), or the callback raising, stops the run before its next step and the exception
/// is raised. Python runs signal handlers in the main thread only; a run started from another thread
/// is not interrupted. A panic of the engine becomes `ddirac.Error`.
pub(crate) fn watched<T: Send>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&mut dyn FnMut(usize) -> Result<(), ddirac::OutputError>) -> Result<T, ddirac::Error> + Send,
) -> PyResult<T> {
    let mut raised: Option<PyErr> = None;
    let result = py.detach(|| {
        let (mut signals, mut reported) = (Instant::now(), Instant::now());
        let mut watch = |k: usize| -> Result<(), ddirac::OutputError> {
            let report = progress.is_some() && reported.elapsed() >= PROGRESS_EVERY;
            if !report && signals.elapsed() < SIGNAL_POLL {
                return Ok(());
            }
            signals = Instant::now();
            let checked = Python::attach(|py| {
                py.check_signals()?;
                if let (true, Some(callback)) = (report, &progress) {
                    reported = Instant::now();
                    callback.call1(py, (k,))?;
                }
                Ok::<(), PyErr>(())
            });
            checked.map_err(|e| {
                raised = Some(e);
                Box::new(SignalRaised) as ddirac::OutputError
            })
        };
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(&mut watch)))
    });
    match (raised, result) {
        (Some(e), _) => Err(e),
        (None, Ok(result)) => result.map_err(engine),
        (None, Err(panic)) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("a panic");
            Err(raise(format!("internal error of the engine ({what}); please report it with the run's arguments")))
        }
    }
}

/// The rows of a run, gathered column by column.
#[derive(Default)]
pub(crate) struct Columns {
    t: Vec<f64>,
    q: Vec<f64>,
    p: Vec<f64>,
    energy: Vec<f64>,
    discrete_energy: Vec<f64>,
    momentum_map: Vec<f64>,
    /// The chart of the atlas each row's step was in (0: the main chart).
    chart: Vec<i64>,
}

/// Integrates `system` for the run `run_args` ([`RunArgs`]), keeping every `every`-th row;
/// returns a dict of NumPy arrays (`t`, `q`, `p` of shape (rows, n), `energy`, `discrete_energy` with
/// NaN on the last row, `momentum_map` of shape (rows, n_g), `chart` the chart of the atlas each row's
/// step was in, `switching` whether the run may switch charts (as `trajectory.csv` then has a `chart`
/// column)) and the `summary` dict.
#[pyfunction]
#[pyo3(signature = (system, run_args, every, wrap_angles, progress=None))]
pub fn simulate<'py>(
    py: Python<'py>,
    system: &SystemHandle,
    run_args: RunArgs,
    every: usize,
    wrap_angles: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (problem, method) = run_args.problem_and_method(&*system.inner)?;
    if every == 0 {
        return Err(raise("`every` must be at least 1"));
    }
    run(py, system, problem, method, OutputOptions { every, wrap_angles }, progress)
}

/// Integrates `problem` for `system` with `method`, keeping the rows `output` asks for, into the dict
/// [`simulate`] returns; `progress(k)` is called with the step index every [`PROGRESS_EVERY`].
pub(crate) fn run<'py>(
    py: Python<'py>,
    system: &SystemHandle,
    problem: Problem,
    method: Method,
    output: OutputOptions,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let inner = system.inner.clone();
    let n = inner.coordinates().len();
    let (problem_for_summary, method_for_summary) = (problem.clone(), method.clone());
    let (columns, summary) = watched(py, progress, |watch| collect(inner.as_ref(), &problem, &method, &output, watch))?;
    let rows = columns.t.len();
    let n_g = columns.momentum_map.len().checked_div(rows).unwrap_or(0);
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, columns.t))?;
    out.set_item("q", PyArray1::from_vec(py, columns.q).reshape([rows, n])?)?;
    out.set_item("p", PyArray1::from_vec(py, columns.p).reshape([rows, n])?)?;
    out.set_item("energy", PyArray1::from_vec(py, columns.energy))?;
    out.set_item("discrete_energy", PyArray1::from_vec(py, columns.discrete_energy))?;
    out.set_item("momentum_map", PyArray1::from_vec(py, columns.momentum_map).reshape([rows, n_g])?)?;
    out.set_item("chart", PyArray1::from_vec(py, columns.chart))?;
    // As the command line decides whether `trajectory.csv` has a `chart` column.
    out.set_item("switching", method_for_summary.atlas && !system.inner.charts().is_empty())?;
    let (run_problem, run_method) = (&problem_for_summary, &method_for_summary);
    out.set_item("summary", summary_dict(py, system, &summary, run_problem, run_method, &output)?)?;
    Ok(out)
}

/// How often the calling thread looks for Python signals (Ctrl-C) while a run integrates.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `work` (a run of the command line's machinery, which has no watch) on a pooled thread with the
/// GIL released, while the calling thread looks for Python signals every [`SIGNAL_POLL`]: a signal
/// handler that raises (Ctrl-C's `KeyboardInterrupt`) asks the run to stop before its next step
/// ([`ddirac::interrupt`]), and its exception is raised once the worker has stopped. Python runs
/// signal handlers in the main thread only; a run started from another thread is not interrupted.
pub(crate) fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    interruptible_with(py, work, &mut |_| Ok(()))
}

/// [`interruptible`], calling `tick` (a progress report) after each look for signals and once at
/// the end; if `tick` raises, the run is stopped as by a signal.
pub(crate) fn interruptible_with<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send + 'static,
    tick: &mut (dyn FnMut(Python<'_>) -> PyResult<()> + Send),
) -> PyResult<T> {
    py.detach(|| {
        let (done, finished) = mpsc::channel();
        // A pooled thread: spawning one per run cost tens of microseconds of a short run's call.
        rayon::spawn(move || {
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            let _ = done.send(result);
        });
        let mut raised = None;
        let result = loop {
            match finished.recv_timeout(SIGNAL_POLL) {
                Ok(result) => break result.map_err(|_| raise("the run's thread panicked")),
                Err(RecvTimeoutError::Disconnected) => break Err(raise("the run's thread stopped without a result")),
                Err(RecvTimeoutError::Timeout) if raised.is_none() => {
                    if let Err(e) = Python::attach(|py| py.check_signals().and_then(|()| tick(py))) {
                        ddirac::interrupt::request();
                        raised = Some(e);
                    }
                }
                Err(RecvTimeoutError::Timeout) => {}
            }
        };
        if let Some(e) = raised {
            ddirac::interrupt::clear();
            return Err(e);
        }
        let _ = Python::attach(tick);
        result
    })
}

/// The summary as the dict of `summary.json` (the command line's definition, [`summary_json_of`]),
/// without what only a run of a file has (`spec`, `total_wall_seconds`).
fn summary_dict<'py>(
    py: Python<'py>,
    system: &SystemHandle,
    s: &Summary,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let record = RunRecord {
        system: &system.name,
        parameters: &system.parameters,
        coordinates: system.inner.coordinates(),
        problem,
        method,
        output,
        spec: None,
        total_seconds: None,
    };
    let text = serde_json::to_string(&summary_json_of(record, s))
        .map_err(|e| raise(format!("the summary cannot be written as JSON: {e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.cast_into::<PyDict>()?)
}

/// Warnings as `summary.json` lists them: `{kind, step, t, message, count}` each.
pub(crate) fn warnings<'py>(py: Python<'py>, warnings: &[ddirac::Warning]) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for w in warnings {
        let entry = PyDict::new(py);
        entry.set_item("kind", w.kind.name())?;
        entry.set_item("step", w.step)?;
        entry.set_item("t", w.t)?;
        entry.set_item("message", &w.message)?;
        entry.set_item("count", w.count)?;
        list.append(entry)?;
    }
    Ok(list)
}

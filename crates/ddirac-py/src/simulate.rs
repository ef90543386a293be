//! One run: problem and method from plain arguments, the rows gathered into arrays while the GIL is
//! released, and the summary as the dict `summary.json` holds.

use ddirac::{
    Connection, Differentiation, EnergyJump, InitialMomentum, JumpAction, Method, NewtonOptions, OutputOptions,
    Problem, Rule, Summary, Variant,
};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::error::{engine, raise};
use crate::system::SystemHandle;
use ddirac_cli::report::{summary_json_of, RunRecord};

/// The method keys of a run, as a spec's `[method]` table names them (a dict from Python).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct MethodKeys {
    rule: String,
    variant: String,
    reduced: bool,
    connection: Option<Vec<Vec<f64>>>,
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    reuse_jacobian: Option<bool>,
    derivatives: String,
    check_invariance: bool,
    on_energy_jump: String,
    energy_jump_threshold: Option<f64>,
    order: Option<i64>,
    composition: Option<String>,
    atlas: bool,
}

impl MethodKeys {
    /// The method, or an error naming the key that is wrong.
    pub(crate) fn method(self) -> PyResult<Method> {
        let one_of = |key: &str, value: &str, names: &[&str]| {
            raise(format!("`{key}` = {value:?} is not one of: {}", names.join(", ")))
        };
        let rule = Rule::from_name(&self.rule).ok_or_else(|| one_of("rule", &self.rule, &Rule::ALL.map(Rule::name)))?;
        let variant = match self.variant.as_str() {
            "plus" => Variant::Plus,
            "minus" => Variant::Minus,
            other => return Err(one_of("variant", other, &["plus", "minus"])),
        };
        let differentiation = Differentiation::from_name(&self.derivatives).ok_or_else(|| {
            one_of("derivatives", &self.derivatives, &Differentiation::ALL.map(Differentiation::name))
        })?;
        let action = JumpAction::from_name(&self.on_energy_jump)
            .ok_or_else(|| one_of("on_energy_jump", &self.on_energy_jump, &JumpAction::ALL.map(JumpAction::name)))?;
        let defaults = NewtonOptions::default();
        let newton = NewtonOptions {
            tolerance: self.tolerance.unwrap_or(defaults.tolerance),
            max_iterations: self.max_iterations.unwrap_or(defaults.max_iterations),
            reuse_jacobian: self.reuse_jacobian.unwrap_or(defaults.reuse_jacobian),
        };
        if !(newton.tolerance.is_finite() && newton.tolerance > 0.0) {
            return Err(raise(format!("`tolerance` = {} must be a positive number", newton.tolerance)));
        }
        let connection = self.connection.map(|rows| Connection::new(&rows)).transpose().map_err(raise)?;
        let threshold = self.energy_jump_threshold.unwrap_or(EnergyJump::default().threshold);
        let energy_jump = EnergyJump { threshold, action };
        let (reduced, check_invariance) = (self.reduced, self.check_invariance);
        let order = match self.order.map(u8::try_from) {
            Some(Ok(order)) => Some(order),
            Some(Err(_)) => {
                return Err(raise(format!("`order` = {} is not one of: 2, 4, 6, 8", self.order.unwrap_or(0))))
            }
            None => None,
        };
        let composition = ddirac::Composition::select(order, self.composition.as_deref()).map_err(raise)?;
        Ok(Method {
            rule,
            variant,
            reduced,
            connection,
            newton,
            check_invariance,
            differentiation,
            energy_jump,
            composition,
            atlas: self.atlas,
        })
    }
}

/// What a run is made of, as the Python package passes it (a dict): initial data (`q0` with exactly one
/// of `p0` and `v0`), time grid (`step`, `steps`) and the `method` keys.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct RunArgs {
    q0: Vec<f64>,
    p0: Option<Vec<f64>>,
    v0: Option<Vec<f64>>,
    step: f64,
    steps: usize,
    method: MethodKeys,
}

impl RunArgs {
    /// The problem and the method, or an error naming what is wrong.
    pub(crate) fn problem_and_method(self) -> PyResult<(Problem, Method)> {
        let method = self.method.method()?;
        let initial = match (self.p0, self.v0) {
            (Some(p), None) => InitialMomentum::Momentum(p),
            (None, Some(v)) => InitialMomentum::Velocity(v),
            _ => return Err(raise("give exactly one of `p0` (momenta) and `v0` (velocities)")),
        };
        Ok((Problem::new(self.step, self.steps, self.q0, initial), method))
    }
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
    let (problem, method) = run_args.problem_and_method()?;
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

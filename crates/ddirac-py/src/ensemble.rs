//! Ensembles from Python: the members of a spec (columns of values keyed as `--set` names them, or
//! the spec's `[ensemble]` table) run on the command line's machinery ([`ddirac_cli::ensemble`])
//! with the GIL released, and come back as NumPy arrays with a leading member axis. A chunk of the
//! members (`offset`) is what a Dask task runs.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use ddirac_cli::ensemble::{Ensemble, Layout, MemberRows, MembersFrom, Results, DIAGNOSTICS};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::error::raise;
use crate::simulate::interruptible_with;
use crate::spec::cli_error;

fn load(
    path: PathBuf,
    text: Option<String>,
    set: &[String],
    columns: Option<Vec<(String, Vec<f64>)>>,
) -> PyResult<Ensemble> {
    let text = match text {
        Some(text) => text,
        None => std::fs::read_to_string(&path)
            .map_err(|e| raise(format!("cannot read the spec file `{}`: {e}", path.display())))?,
    };
    let from = columns.map_or(MembersFrom::Spec, MembersFrom::Columns);
    Ensemble::from_text(&path, text, set, from).map_err(cli_error)
}

/// The members the spec's `[ensemble]` table generates: (keys, values as a members × keys array).
#[pyfunction]
#[pyo3(signature = (path, text, set))]
pub fn ensemble_members<'py>(
    py: Python<'py>,
    path: PathBuf,
    text: Option<String>,
    set: Vec<String>,
) -> PyResult<(Vec<String>, Bound<'py, PyAny>)> {
    let ensemble = load(path, text, &set, None)?;
    let keys: Vec<String> = ensemble.members.keys.iter().map(|k| k.name()).collect();
    let (m, k) = (ensemble.members.len(), keys.len());
    let values = PyArray1::from_vec(py, ensemble.members.values).reshape([m, k])?.into_any();
    Ok((keys, values))
}

/// Runs the members given by `columns` (or the spec's `[ensemble]` table), numbered from `offset`,
/// on `threads` threads (default: all cores), and returns their results as a dict of arrays.
#[pyfunction]
#[pyo3(signature = (path, text, set, columns, offset=0, threads=None, trajectories=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn ensemble<'py>(
    py: Python<'py>,
    path: PathBuf,
    text: Option<String>,
    set: Vec<String>,
    columns: Option<Vec<(String, Vec<f64>)>>,
    offset: usize,
    threads: Option<usize>,
    trajectories: Option<bool>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut ensemble = load(path, text, &set, columns)?;
    if let Some(t) = trajectories {
        ensemble.trajectories = t;
    }
    let ensemble = Arc::new(ensemble);
    let count = ensemble.members.len();
    let rows = ensemble.rows();
    let layout = ensemble.layout();
    let kept = Arc::new(Mutex::new(ensemble.trajectories.then(|| Kept::new(count, rows, &layout))));
    let done = Arc::new(AtomicUsize::new(0));
    let (work_ensemble, work_kept, work_done) = (ensemble.clone(), kept.clone(), done.clone());
    let work = move || {
        let keep = |offset: usize, r: &MemberRows| -> Result<(), ddirac::OutputError> {
            if let Some(k) = work_kept.lock().expect("no panic while keeping rows").as_mut() {
                k.put(offset, r);
            }
            Ok(())
        };
        let report = |d: usize| work_done.store(d, Ordering::Relaxed);
        work_ensemble.run(0..count, threads, &keep, &report)
    };
    let mut results = interruptible_with(py, work, &mut |py| match &progress {
        Some(callback) => callback.call1(py, (done.load(Ordering::Relaxed),)).map(drop),
        None => Ok(()),
    })?
    .map_err(cli_error)?;
    for failure in &mut results.failures {
        failure.member += offset;
    }
    let kept = kept.lock().expect("no panic while keeping rows").take();
    arrays(py, &ensemble, results, kept, offset)
}

/// The rows of every member, kept in memory: the parts of the state ([`Layout::parts`]), then the
/// energy, each members × rows × width.
struct Kept {
    rows: usize,
    widths: Vec<usize>,
    arrays: Vec<Vec<f64>>,
}

impl Kept {
    fn new(members: usize, rows: usize, layout: &Layout) -> Self {
        let mut widths: Vec<usize> = layout.parts().iter().map(|p| p.width()).collect();
        widths.push(1);
        let arrays = widths.iter().map(|w| vec![f64::NAN; members * rows * w]).collect();
        Self { rows, widths, arrays }
    }

    fn put(&mut self, offset: usize, r: &MemberRows) {
        let values = r.state.iter().chain(std::iter::once(&r.energy));
        for ((array, width), values) in self.arrays.iter_mut().zip(&self.widths).zip(values) {
            let block = offset * self.rows * width;
            array[block..block + values.len()].copy_from_slice(values);
        }
    }
}

/// The results as a dict of arrays and plain values.
fn arrays<'py>(
    py: Python<'py>,
    ensemble: &Ensemble,
    results: Results,
    kept: Option<Kept>,
    offset: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let m = results.len();
    let layout = ensemble.layout();
    let d = PyDict::new(py);
    d.set_item("offset", offset)?;
    d.set_item("coordinates", ensemble.coordinates())?;
    d.set_item("attitude", layout.attitude)?;
    let keys: Vec<String> = ensemble.members.keys.iter().map(|k| k.name()).collect();
    d.set_item("members", PyArray1::from_vec(py, ensemble.members.values.clone()).reshape([m, keys.len()])?)?;
    d.set_item("keys", keys)?;
    let mut at = 0;
    for part in layout.parts() {
        let width = part.width();
        let values: Vec<f64> = (0..m).flat_map(|k| results.part(k, at..at + width).to_vec()).collect();
        let shape: Vec<usize> = std::iter::once(m).chain(part.shape.iter().copied()).collect();
        d.set_item(format!("final_{}", part.name), PyArray1::from_vec(py, values).reshape(shape)?)?;
        at += width;
    }
    d.set_item("finished", PyArray1::from_vec(py, results.finished))?;
    d.set_item("steps", PyArray1::from_vec(py, results.steps))?;
    let diagnostics = PyDict::new(py);
    for ((name, _), column) in DIAGNOSTICS.iter().zip(results.diagnostics) {
        diagnostics.set_item(*name, PyArray1::from_vec(py, column))?;
    }
    d.set_item("diagnostics", diagnostics)?;
    let failures = PyList::empty(py);
    for f in &results.failures {
        let item = PyDict::new(py);
        item.set_item("member", f.member)?;
        item.set_item("step", f.step)?;
        item.set_item("t", f.t)?;
        item.set_item("error", &f.error)?;
        failures.append(item)?;
    }
    d.set_item("failures", failures)?;
    d.set_item("derivatives", results.derivatives.into_iter().collect::<Vec<_>>())?;
    d.set_item("warnings", results.warnings.into_iter().collect::<Vec<_>>())?;
    d.set_item("member_seconds", results.member_seconds)?;
    d.set_item("steppers", (results.preparations.prepared, results.preparations.renewed))?;
    if let Some(k) = kept {
        d.set_item("t", PyArray1::from_vec(py, ensemble.times()))?;
        let mut names: Vec<(String, Vec<usize>)> =
            layout.parts().into_iter().map(|p| (p.name.to_owned(), p.shape)).collect();
        names.push(("energy".into(), vec![]));
        for ((name, shape), values) in names.into_iter().zip(k.arrays) {
            let shape: Vec<usize> = [m, k.rows].into_iter().chain(shape).collect();
            d.set_item(name, PyArray1::from_vec(py, values).reshape(shape)?)?;
        }
    }
    Ok(d)
}

//! `ddirac.check`: the hypotheses of a run tested without integrating, as data, and the verdict a run
//! would give (paper §4: invariance; §6: periodicity of angles; the Legendre map and the primary
//! constraint of a degenerate Lagrangian; with an atlas, each chart's maps, Legendre map, group
//! coordinates and angles).

use ddirac::{CheckReport, Finding};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::error::engine;
use crate::simulate::RunArgs;
use crate::system::SystemHandle;

fn findings<'py>(py: Python<'py>, findings: &[Finding], tolerance: f64) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for f in findings {
        let d = PyDict::new(py);
        d.set_item("coordinate", &f.coordinate)?;
        d.set_item("deviation", f.deviation)?;
        d.set_item("samples", f.samples)?;
        d.set_item("decided", f.decided())?;
        d.set_item("holds", f.holds(tolerance))?;
        list.append(d)?;
    }
    Ok(list)
}

/// Tests the hypotheses of the run `run_args` of `system` near the
/// initial data; returns the findings and the verdict (`runs`, and the `error` a run would fail with
/// or the `warnings` it would run with, as a run's summary lists them).
#[pyfunction]
pub fn check<'py>(py: Python<'py>, system: &SystemHandle, run_args: RunArgs) -> PyResult<Bound<'py, PyDict>> {
    let (problem, method) = run_args.problem_and_method(&*system.inner)?;
    let inner = system.inner.clone();
    let checked = method.clone();
    let report: CheckReport = py.detach(move || inner.check(&problem, &checked)).map_err(engine)?;
    let d = PyDict::new(py);
    d.set_item("invariance", findings(py, &report.invariance, report.invariance_tolerance)?)?;
    d.set_item("invariance_tolerance", report.invariance_tolerance)?;
    d.set_item("invariant", report.invariant())?;
    d.set_item("periodicity", findings(py, &report.periodicity, report.periodicity_tolerance)?)?;
    d.set_item("periodicity_tolerance", report.periodicity_tolerance)?;
    d.set_item("periodic", report.periodic())?;
    d.set_item("connection_axioms", report.connection_axioms)?;
    d.set_item("legendre_rank", report.legendre_rank)?;
    d.set_item("coordinates", report.coordinates)?;
    d.set_item("regular", report.regular())?;
    d.set_item("constraint_mismatch", report.constraint_mismatch)?;
    d.set_item("momentum_consistent", report.momentum_consistent())?;
    let charts = PyList::empty(py);
    for c in &report.charts {
        let chart = PyDict::new(py);
        chart.set_item("name", &c.name)?;
        chart.set_item("points", c.points)?;
        chart.set_item("round_trip", c.round_trip)?;
        chart.set_item("inverse", c.inverse())?;
        chart.set_item("worst", c.worst.clone())?;
        chart.set_item("singular_where_good", c.singular_where_good.as_ref().map(|(at, _)| at.clone()))?;
        chart.set_item("invariance", findings(py, &c.invariance, report.invariance_tolerance)?)?;
        chart.set_item("periodicity", findings(py, &c.periodicity, report.periodicity_tolerance)?)?;
        charts.append(chart)?;
    }
    d.set_item("charts", charts)?;
    let verdict = PyDict::new(py);
    match report.verdict(&method) {
        Ok(warnings) => {
            verdict.set_item("runs", true)?;
            verdict.set_item("error", py.None())?;
            verdict.set_item("warnings", crate::simulate::warnings(py, &warnings)?)?;
        }
        Err(e) => {
            verdict.set_item("runs", false)?;
            verdict.set_item("error", e.to_string())?;
            verdict.set_item("warnings", Vec::<String>::new())?;
        }
    }
    d.set_item("verdict", verdict)?;
    Ok(d)
}

//! What calling the engine from Python costs: the same run timed inside Rust, for
//! `scripts/python_overhead.py` to set beside `ddirac.simulate` in one process.

use std::time::Instant;

use ddirac::OutputOptions;
use pyo3::prelude::*;

use crate::error::engine;
use crate::simulate::{collect, RunArgs};
use crate::system::SystemHandle;

/// Seconds the Rust library takes for the run `ddirac.simulate` would make with these arguments
/// (`every` = 1): set-up, integration and the rows gathered into vectors, without Python objects.
#[pyfunction]
pub fn rust_seconds(py: Python<'_>, system: &SystemHandle, run_args: RunArgs) -> PyResult<f64> {
    let (problem, method) = run_args.problem_and_method(&*system.inner)?;
    let inner = system.inner.clone();
    py.detach(move || {
        let start = Instant::now();
        let run = collect(inner.as_ref(), &problem, &method, &OutputOptions::default(), &mut |_| Ok(()));
        let seconds = start.elapsed().as_secs_f64();
        run.map(|run| {
            std::hint::black_box(run);
            seconds
        })
    })
    .map_err(engine)
}

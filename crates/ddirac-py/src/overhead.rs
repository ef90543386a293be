//! What calling the engine from Python costs: the same run timed inside Rust, for
//! `scripts/python_overhead.py` to set beside `ddirac.simulate` in one process.

use std::time::Instant;

use ddirac::OutputOptions;
use pyo3::prelude::*;

use crate::error::engine;
use crate::simulate::{collect, problem, MethodKeys};
use crate::system::SystemHandle;

/// Seconds the Rust library takes for the run `ddirac.simulate` would make with these arguments
/// (`every` = 1): set-up, integration and the rows gathered into vectors, without Python objects.
#[pyfunction]
#[pyo3(signature = (system, q0, p0, v0, step, steps, method))]
#[allow(clippy::too_many_arguments)]
pub fn rust_seconds(
    py: Python<'_>,
    system: &SystemHandle,
    q0: Vec<f64>,
    p0: Option<Vec<f64>>,
    v0: Option<Vec<f64>>,
    step: f64,
    steps: usize,
    method: MethodKeys,
) -> PyResult<f64> {
    let method = method.method()?;
    let problem = problem(q0, p0, v0, step, steps)?;
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

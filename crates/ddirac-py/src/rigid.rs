//! Rigid bodies from Python: the built-in `rigid_body` with parameter overrides, and its runs from
//! (R0, Π0 or Ω0) on a time grid with the method keys of a spec, the rows gathered into arrays while
//! the GIL is released (`R` of shape (rows, 3, 3), `Pi` and `momentum_map` of shape (rows, 3)).

use ddirac::rigid::{RigidInitial, RigidProblem, RigidStepper};
use ddirac::systems::{Parameters, RigidBody};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{engine, raise};
use crate::simulate::{watched, MethodArgs};
use ddirac_cli::keys::{self, time::TimeKeys, Spelling};
use ddirac_cli::rigid::plan::RigidModel;
use ddirac_cli::rigid::{report, RigidPlan};

/// The built-in rigid body with its parameters set.
#[pyclass(module = "ddirac._ddirac", frozen)]
pub struct RigidHandle {
    body: RigidBody,
    /// The name `summary.json` gives it.
    #[pyo3(get)]
    pub name: &'static str,
    /// Its parameters, by name, in its order.
    #[pyo3(get)]
    pub parameters: Vec<(String, f64)>,
    /// The symmetry it declares: `SO(3)` (every rotation), `vertical` or `none`.
    #[pyo3(get)]
    pub symmetry: &'static str,
}

/// The rigid body with some of its parameters overridden.
#[pyfunction]
pub fn rigid_body(parameters: Vec<(String, f64)>) -> PyResult<RigidHandle> {
    let mut body = RigidBody::default_parameters();
    for (name, value) in &parameters {
        body.set_parameter(name, *value).map_err(engine)?;
    }
    let all = body.parameters().into_iter().map(|(n, v)| (n.to_owned(), v)).collect();
    let symmetry = ddirac::rigid::RigidSystem::symmetry(&body).name();
    Ok(RigidHandle { body, name: ddirac_cli::rigid::NAME, parameters: all, symmetry })
}

/// What a rigid body's run is made of, as the Python package passes it (a dict).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct RigidArgs {
    r0: Vec<Vec<f64>>,
    pi0: Option<Vec<f64>>,
    omega0: Option<Vec<f64>>,
    step: Option<f64>,
    steps: Option<i64>,
    duration: Option<f64>,
    method: MethodArgs,
}

/// Three numbers, or an error naming the argument.
fn three(values: &[f64], what: &str) -> PyResult<[f64; 3]> {
    <[f64; 3]>::try_from(values).map_err(|_| raise(format!("`{what}` has {} entries; it takes 3", values.len())))
}

impl RigidArgs {
    fn plan(self, handle: &RigidHandle, every: usize) -> PyResult<RigidPlan> {
        if self.r0.len() != 3 {
            return Err(raise(format!("`R0` has {} rows; a rotation has 3 rows of 3", self.r0.len())));
        }
        let mut r0 = [[0.0; 3]; 3];
        for (i, row) in self.r0.iter().enumerate() {
            r0[i] = three(row, &format!("row {} of R0", i + 1))?;
        }
        let initial = match (self.pi0, self.omega0) {
            (Some(pi), None) => RigidInitial::Momentum { pi: three(&pi, "Pi0")?, p: vec![] },
            (None, Some(omega)) => RigidInitial::Velocity { omega: three(&omega, "Omega0")?, v: vec![] },
            (Some(_), Some(_)) => return Err(raise("give one of `Pi0` and `Omega0`, not both (Π = I Ω)")),
            (None, None) => {
                return Err(raise(
                    "give the body angular momentum `Pi0` or the body angular velocity `Omega0` (3 numbers)",
                ))
            }
        };
        let grid = TimeKeys { step: self.step, steps: self.steps, duration: self.duration };
        let (step, steps) = keys::time::grid(&grid, Spelling::Argument).map_err(|e| raise(e.text()))?;
        if self.method.0.connection.is_some() {
            return Err(raise("a rigid body takes no `connection`: it is reduced by SO(3) itself (`reduced=True`)"));
        }
        if self.method.0.atlas.is_some() {
            return Err(raise("a rigid body takes no `atlas`: its attitude is advanced on SO(3), in no chart"));
        }
        let method = keys::method::method(&self.method.0, &[], Spelling::Argument).map_err(|e| raise(e.text()))?;
        let problem = RigidProblem::new(step, steps, r0, initial);
        // The attitude and the data are checked before the GIL is released.
        problem.validate(0).map_err(engine)?;
        Ok(RigidPlan {
            name: ddirac_cli::rigid::NAME.to_owned(),
            body: RigidModel::Body(handle.body),
            parameters: handle.parameters.clone(),
            problem,
            method,
            every,
            directory: None,
        })
    }
}

/// Integrates the rigid body `handle` for `run_args`, keeping every `every`-th row (and the last);
/// returns a dict of NumPy arrays (`t`, `R` (rows, 3, 3), `Pi` (rows, 3), `energy`, `momentum_map`
/// (rows, 3): the spatial angular momentum R Π) and the `summary` dict (`summary.json`'s).
#[pyfunction]
#[pyo3(signature = (handle, run_args, every, progress=None))]
pub fn simulate_rigid<'py>(
    py: Python<'py>,
    handle: &RigidHandle,
    run_args: RigidArgs,
    every: usize,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if every == 0 {
        return Err(raise("`every` must be at least 1"));
    }
    let plan = run_args.plan(handle, every)?;
    let (mut t, mut r, mut pi, mut energy, mut j): (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) =
        (vec![], vec![], vec![], vec![], vec![]);
    let summary = watched(py, progress, |watch| {
        let mut stepper = RigidStepper::new(&plan.body, plan.problem.clone(), &plan.method)?;
        let mut keep = |stepper: &RigidStepper<'_, RigidModel>| {
            let row = stepper.row();
            t.push(row.t);
            r.extend(row.r.iter().flatten());
            pi.extend(row.pi);
            energy.push(row.energy);
            j.extend(row.momentum_map);
        };
        keep(&stepper);
        while !stepper.is_finished() {
            let k = stepper.k();
            watch(k).map_err(ddirac::Error::Output)?;
            stepper.step()?;
            if stepper.k() % every == 0 || stepper.is_finished() {
                keep(&stepper);
            }
        }
        Ok(stepper.summary())
    })?;
    let rows = t.len();
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, t))?;
    out.set_item("R", PyArray1::from_vec(py, r).reshape([rows, 3, 3])?)?;
    out.set_item("Pi", PyArray1::from_vec(py, pi).reshape([rows, 3])?)?;
    out.set_item("energy", PyArray1::from_vec(py, energy))?;
    out.set_item("momentum_map", PyArray1::from_vec(py, j).reshape([rows, 3])?)?;
    let text = serde_json::to_string(&report::summary_json(&plan, &summary, None, None))
        .map_err(|e| raise(format!("the summary cannot be written as JSON: {e}")))?;
    out.set_item("summary", py.import("json")?.call_method1("loads", (text,))?)?;
    Ok(out)
}

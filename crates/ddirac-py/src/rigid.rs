//! Rigid bodies from Python: the built-in `rigid_body` with parameter overrides, and its runs from
//! (R0, Π0 or Ω0) on a time grid with the method keys of a spec, the rows gathered into arrays while
//! the GIL is released (`R` of shape (rows, 3, 3), `Pi` and `momentum_map` of shape (rows, 3)).

use ddirac::expression::ExpressionSpec;
use ddirac::rigid::{RigidExpressionSystem, RigidInitial, RigidProblem, RigidStepper, RigidSystem, Symmetry};
use ddirac::systems::{Parameters, RigidBody};
use ddirac::Coordinate;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{engine, raise};
use crate::simulate::{watched, MethodArgs};
use ddirac_cli::keys::{self, time::TimeKeys, Spelling};
use ddirac_cli::rigid::plan::RigidModel;
use ddirac_cli::rigid::{report, RigidPlan};

/// A rigid system: the built-in body with its parameters set, or one whose Lagrangian is text.
#[pyclass(module = "ddirac._ddirac", frozen)]
pub struct RigidHandle {
    body: RigidModel,
    /// The name `summary.json` gives it.
    #[pyo3(get)]
    pub name: String,
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
    let symmetry = RigidSystem::symmetry(&body).name();
    Ok(RigidHandle {
        body: RigidModel::Body(body),
        name: ddirac_cli::rigid::NAME.to_owned(),
        parameters: all,
        symmetry,
    })
}

#[pymethods]
impl RigidHandle {
    /// The shape coordinates as (name, kind) with kind `real` or `angle`.
    #[getter]
    fn shape(&self) -> Vec<(String, &'static str)> {
        RigidSystem::shape(&self.body)
            .into_iter()
            .map(|c| {
                let kind = if c.kind == ddirac::CoordinateKind::Angle { "angle" } else { "real" };
                (c.name, kind)
            })
            .collect()
    }
}

/// A rigid system whose Lagrangian is text, in `Omega1` … `Omega3`, `R11` … `R33`, the `shape`
/// coordinates (the `angles` among them on S¹) and their velocities, with the `symmetry` it declares
/// (`SO(3)`, `vertical` or `none`).
#[pyfunction]
#[pyo3(signature = (lagrangian, shape, angles, definitions, parameters, symmetry, name=None))]
pub fn rigid_text_system(
    lagrangian: String,
    shape: Vec<String>,
    angles: Vec<String>,
    definitions: Vec<(String, String)>,
    parameters: Vec<(String, f64)>,
    symmetry: &str,
    name: Option<String>,
) -> PyResult<RigidHandle> {
    let symmetry = match symmetry {
        "SO(3)" => Symmetry::Rotations,
        "vertical" => Symmetry::Vertical,
        "none" => Symmetry::None,
        other => {
            return Err(raise(format!(
                "unknown symmetry {other:?}: `symmetry` is \"SO(3)\" (every rotation of space), \"vertical\" \
                 (rotations about e3) or \"none\""
            )))
        }
    };
    if let Some(a) = angles.iter().find(|a| !shape.contains(a)) {
        return Err(raise(format!("`{a}` in `angles` is not a shape coordinate; they are: {}", shape.join(", "))));
    }
    let coordinates: Vec<Coordinate> = shape
        .iter()
        .map(|n| if angles.contains(n) { Coordinate::shape(n).angle() } else { Coordinate::shape(n) })
        .collect();
    let mut sources = vec![("lagrangian".to_owned(), lagrangian.clone())];
    sources.extend(definitions.iter().map(|(n, v)| (format!("definition:{n}"), v.clone())));
    let parameter_names: Vec<String> = parameters.iter().map(|(n, _)| n.clone()).collect();
    let definition_names: Vec<String> = definitions.iter().map(|(n, _)| n.clone()).collect();
    let declared = crate::error::Declared {
        coordinates: &shape,
        parameters: &parameter_names,
        definitions: &definition_names,
        rigid: true,
    };
    let spec = ExpressionSpec {
        coordinates,
        lagrangian,
        definitions,
        parameters: parameters.clone(),
        ..ExpressionSpec::default()
    };
    let system =
        RigidExpressionSystem::new(&spec, symmetry).map_err(|e| crate::error::expression(e, &sources, &declared))?;
    Ok(RigidHandle {
        body: RigidModel::Text(Box::new(system)),
        name: name.unwrap_or_else(|| "custom".to_owned()),
        parameters,
        symmetry: symmetry.name(),
    })
}

/// What a rigid body's run is made of, as the Python package passes it (a dict).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct RigidArgs {
    r0: Vec<Vec<f64>>,
    pi0: Option<Vec<f64>>,
    omega0: Option<Vec<f64>>,
    q0: Option<crate::simulate::VectorArg>,
    p0: Option<crate::simulate::VectorArg>,
    v0: Option<crate::simulate::VectorArg>,
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
        let shape = RigidSystem::shape(&handle.body);
        let (s0, shape_momentum) = if shape.is_empty() {
            if self.q0.is_some() || self.p0.is_some() || self.v0.is_some() {
                return Err(raise(
                    "this rigid body has no shape coordinates: give `R0` and one of `Pi0`, `Omega0`, not `q0`, `p0`, `v0`",
                ));
            }
            (vec![], None)
        } else {
            let names: Vec<&str> = shape.iter().map(|c| c.name.as_str()).collect();
            let Some(q0) = self.q0 else {
                return Err(raise(format!(
                    "`q0` is missing: the shape coordinates ({}) at the start",
                    names.join(", ")
                )));
            };
            let (q0, momentum) = keys::initial::initial(
                &q0.values(),
                self.p0.map(crate::simulate::VectorArg::values).as_ref(),
                self.v0.map(crate::simulate::VectorArg::values).as_ref(),
                &names,
                Spelling::Argument,
            )
            .map_err(|e| raise(e.text()))?;
            (q0, Some(momentum))
        };
        let (p, v) = match shape_momentum {
            Some(ddirac::InitialMomentum::Momentum(p)) => (Some(p), None),
            Some(ddirac::InitialMomentum::Velocity(v)) => (None, Some(v)),
            None => (None, None),
        };
        let initial = match (self.pi0, self.omega0) {
            (Some(_), None) if v.is_some() => {
                return Err(raise("`Pi0` goes with the shape's momenta `p0`, `Omega0` with its velocities `v0`"))
            }
            (None, Some(_)) if p.is_some() => {
                return Err(raise("`Omega0` goes with the shape's velocities `v0`, `Pi0` with its momenta `p0`"))
            }
            (Some(pi), None) => RigidInitial::Momentum { pi: three(&pi, "Pi0")?, p: p.unwrap_or_default() },
            (None, Some(omega)) => RigidInitial::Velocity { omega: three(&omega, "Omega0")?, v: v.unwrap_or_default() },
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
        if self.method.0.sensitivities == Some(true) {
            return Err(raise("a rigid body has no tangent map yet: `sensitivities` is for systems in coordinates"));
        }
        let method = keys::method::method(&self.method.0, &[], Spelling::Argument).map_err(|e| raise(e.text()))?;
        let problem = RigidProblem { s0, ..RigidProblem::new(step, steps, r0, initial) };
        // The attitude and the data are checked before the GIL is released.
        problem.validate(shape.len()).map_err(engine)?;
        Ok(RigidPlan {
            name: handle.name.clone(),
            body: handle.body.clone(),
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
    let (mut t, mut r, mut pi): (Vec<f64>, Vec<f64>, Vec<f64>) = (vec![], vec![], vec![]);
    let (mut energy, mut j): (Vec<f64>, Vec<f64>) = (vec![], vec![]);
    let (mut q, mut p): (Vec<f64>, Vec<f64>) = (vec![], vec![]);
    let n = RigidSystem::shape(&plan.body).len();
    let summary = watched(py, progress, |watch| {
        let mut stepper = RigidStepper::new(&plan.body, plan.problem.clone(), &plan.method)?;
        let mut keep = |stepper: &RigidStepper<'_, RigidModel>| {
            let row = stepper.row();
            t.push(row.t);
            r.extend(row.r.iter().flatten());
            pi.extend(row.pi);
            energy.push(row.energy);
            j.extend(row.momentum_map);
            q.extend(&row.s);
            p.extend(&row.p);
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
    out.set_item("q", PyArray1::from_vec(py, q).reshape([rows, n])?)?;
    out.set_item("p", PyArray1::from_vec(py, p).reshape([rows, n])?)?;
    let text = serde_json::to_string(&report::summary_json(&plan, &summary, None, None))
        .map_err(|e| raise(format!("the summary cannot be written as JSON: {e}")))?;
    out.set_item("summary", py.import("json")?.call_method1("loads", (text,))?)?;
    Ok(out)
}

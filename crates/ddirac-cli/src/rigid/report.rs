//! What a rigid body's run writes: the columns of its trajectory (`t`, `R11` … `R33`, `Pi1` …
//! `Pi3`, the shape and its momenta, `energy`, `momentum_x` … `momentum_z`), its `summary.json`
//! (`final.R` as three rows, `final.Pi`) and the short text printed on stdout.

use std::path::Path;

use ddirac::rigid::{RigidInitial, RigidRow, RigidSummary};
use ddirac::Method;
use serde::Serialize;

use super::plan::RigidPlan;
use crate::report::{self, NewtonJson, StatsJson, WarningJson};

/// The columns of the trajectory of a body with the shape coordinates `shape`.
pub fn columns(shape: &[String]) -> Vec<String> {
    let attitude = (1..=3).flat_map(|i| (1..=3).map(move |j| format!("R{i}{j}")));
    std::iter::once("t".to_owned())
        .chain(attitude)
        .chain((1..=3).map(|i| format!("Pi{i}")))
        .chain(shape.iter().cloned())
        .chain(shape.iter().map(|s| format!("p_{s}")))
        .chain(["energy".to_owned()])
        .chain(["x", "y", "z"].map(|a| format!("momentum_{a}")))
        .collect()
}

/// The values of a row, in the order of [`columns`]; the energy is empty (NaN in `.npy`) where the
/// Legendre transform cannot be inverted.
pub fn values(row: &RigidRow) -> impl Iterator<Item = Option<f64>> + '_ {
    std::iter::once(row.t)
        .chain(row.r.iter().flatten().copied())
        .chain(row.pi)
        .chain(row.s.iter().chain(&row.p).copied())
        .map(Some)
        .chain([(!row.energy.is_nan()).then_some(row.energy)])
        .chain(row.momentum_map.map(Some))
}

/// The content of a rigid body's `summary.json`, in the order it is written.
#[derive(Serialize)]
pub struct RigidSummaryJson<'a> {
    ddirac_version: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    spec: Option<String>,
    system: &'a str,
    /// `SO(3)`: the configuration holds an attitude R (what marks a rigid system's summary).
    attitude: &'static str,
    parameters: report::Parameters<'a>,
    #[serde(skip_serializing_if = "<[String]>::is_empty")]
    shape: Vec<String>,
    symmetry: &'static str,
    method: MethodJson,
    steps: usize,
    step: f64,
    duration: f64,
    initial: InitialJson,
    output: OutputJson,
    #[serde(rename = "final")]
    final_state: FinalJson,
    energy: StatsJson,
    momentum_map: MomentumMapJson<'a>,
    casimir: CasimirJson,
    orthogonality: f64,
    newton: NewtonJson,
    wall_seconds: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    total_wall_seconds: Option<f64>,
    warnings: Vec<WarningJson>,
}

#[derive(Serialize)]
struct MethodJson {
    rule: &'static str,
    reduced: bool,
    tolerance: f64,
    max_iterations: usize,
    jacobian: &'static str,
    check_invariance: bool,
    derivatives: &'static str,
    on_energy_jump: &'static str,
    energy_jump_threshold: f64,
    order: u8,
    composition: &'static str,
    stages: usize,
}

impl MethodJson {
    fn new(method: &Method, closed_form: bool) -> Self {
        Self {
            rule: method.rule.name(),
            reduced: method.reduced,
            tolerance: method.newton.tolerance,
            max_iterations: method.newton.max_iterations,
            jacobian: if method.newton.reuse_jacobian { "reuse" } else { "fresh" },
            check_invariance: method.check_invariance,
            // A body that declares its principal axes is stepped with derivatives in closed form;
            // any other takes them from dual numbers.
            derivatives: if closed_form { "closed form" } else { "dual" },
            on_energy_jump: method.energy_jump.action.name(),
            energy_jump_threshold: method.energy_jump.threshold,
            order: method.composition.order(),
            composition: method.composition.name(),
            stages: method.composition.coefficients().len(),
        }
    }
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct InitialJson {
    R: [[f64; 3]; 3],
    #[serde(skip_serializing_if = "Vec::is_empty")]
    q: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    Pi: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    Omega: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    p: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    v: Option<Vec<f64>>,
}

#[derive(Serialize)]
struct OutputJson {
    every: usize,
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct FinalJson {
    R: [[f64; 3]; 3],
    Pi: [f64; 3],
    #[serde(skip_serializing_if = "Vec::is_empty")]
    q: Vec<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    p: Vec<f64>,
}

#[derive(Serialize)]
struct MomentumMapJson<'a> {
    /// R0 Π0, in space.
    initial: &'a [f64],
    /// The components the symmetry conserves: `x`, `y`, `z` (every rotation) or `z` (the vertical).
    conserved: Vec<&'static str>,
    max_drift: f64,
    scale: f64,
    max_relative_drift: Option<f64>,
}

#[derive(Serialize)]
struct CasimirJson {
    initial: f64,
    max_relative_drift: f64,
    /// Whether the symmetry conserves |Π| (every rotation): else the drift is the motion's.
    conserved: bool,
}

/// The content of `summary.json` of a rigid body's run of the spec file `spec`.
pub fn summary_json<'a>(
    plan: &'a RigidPlan,
    summary: &'a RigidSummary,
    spec: Option<&Path>,
    total_seconds: Option<f64>,
) -> RigidSummaryJson<'a> {
    let shaped = |x: &Vec<f64>| (!x.is_empty()).then(|| x.clone());
    let (pi, omega, p, v) = match &plan.problem.initial {
        RigidInitial::Momentum { pi, p } => (Some(*pi), None, shaped(p), None),
        RigidInitial::Velocity { omega, v } => (None, Some(*omega), None, shaped(v)),
    };
    let j = &summary.momentum_map;
    RigidSummaryJson {
        ddirac_version: env!("CARGO_PKG_VERSION"),
        spec: spec.map(|s| s.display().to_string()),
        system: &plan.name,
        attitude: "SO(3)",
        shape: super::shape_names(plan),
        parameters: report::Parameters(&plan.parameters),
        symmetry: summary.symmetry.name(),
        method: MethodJson::new(&plan.method, ddirac::rigid::RigidSystem::principal_axes(&plan.body).is_some()),
        steps: summary.steps,
        step: summary.step,
        duration: summary.step * summary.steps as f64,
        initial: InitialJson { R: plan.problem.r0, q: plan.problem.s0.clone(), Pi: pi, Omega: omega, p, v },
        output: OutputJson { every: plan.every },
        final_state: FinalJson {
            R: summary.final_r,
            Pi: summary.final_pi,
            q: summary.final_s.clone(),
            p: summary.final_p.clone(),
        },
        energy: StatsJson::new(&summary.energy, true),
        momentum_map: MomentumMapJson {
            initial: &j.initial,
            conserved: summary.symmetry.conserved_components().iter().map(|&i| ["x", "y", "z"][i]).collect(),
            max_drift: j.max_drift,
            scale: j.scale,
            max_relative_drift: j.max_relative_drift,
        },
        casimir: CasimirJson {
            initial: summary.casimir.initial,
            max_relative_drift: summary.casimir.max_relative_drift,
            conserved: summary.symmetry == ddirac::rigid::Symmetry::Rotations,
        },
        orthogonality: summary.orthogonality,
        newton: NewtonJson::new(&summary.newton),
        wall_seconds: summary.wall_seconds,
        total_wall_seconds: total_seconds,
        warnings: summary.warnings.iter().map(WarningJson::new).collect(),
    }
}

/// The short human summary printed after a successful run.
pub fn human(plan: &RigidPlan, summary: &RigidSummary, dir: &Path, total_seconds: f64) -> String {
    let m = &plan.method;
    let e = &summary.energy;
    let spread = (e.max - e.min) / e.initial.abs().max(f64::MIN_POSITIVE);
    let j = &summary.momentum_map;
    let conserved = match summary.symmetry.conserved_components() {
        [] => "none (no symmetry)".to_owned(),
        [2] => "the vertical component".to_owned(),
        _ => "all components".to_owned(),
    };
    let r = summary.final_r;
    [
        format!(
            "{}: {} steps of h = {} (T = {}), rule {}, {}{}",
            plan.name,
            summary.steps,
            summary.step,
            summary.step * summary.steps as f64,
            m.rule.name(),
            if m.reduced { "reduced by SO(3)" } else { "unreduced" },
            report::composition(m.composition)
        ),
        format!("  final R          {:?}, {:?}, {:?}", r[0], r[1], r[2]),
        format!("  final Pi         {:?}", summary.final_pi),
        if e.initial.is_nan() {
            "  energy           not reported (see the warnings)".to_owned()
        } else {
            format!("  energy           [{:.10e}, {:.10e}] (relative spread {spread:.3e})", e.min, e.max)
        },
        format!(
            "  angular momentum R Pi, {conserved} conserved: drift {:.3e}{}",
            j.max_drift,
            j.max_relative_drift.map_or(String::new(), |r| format!(" (relative {r:.3e})"))
        ),
        match summary.symmetry {
            ddirac::rigid::Symmetry::Rotations => format!(
                "  |Pi|             {:.10e}, relative drift {:.3e}; |R^T R - I| at most {:.3e}",
                summary.casimir.initial, summary.casimir.max_relative_drift, summary.orthogonality
            ),
            _ => format!(
                "  |R^T R - I|      at most {:.3e} (|Pi| is not conserved without the symmetry of every rotation)",
                summary.orthogonality
            ),
        },
        format!(
            "  newton           {} iterations in total, at most {} per step, {} Jacobians, largest residual {:.3e}",
            summary.newton.total_iterations,
            summary.newton.max_iterations,
            summary.newton.total_jacobians,
            summary.newton.max_residual
        ),
        report::warnings(&summary.warnings),
        format!("  output           {}", dir.display()),
        format!("  wall time        {:.3} s ({:.3} s integrating)", total_seconds, summary.wall_seconds),
    ]
    .join("\n")
}

//! What a finished run reports: `summary.json` and the short text printed on stdout.

use std::path::Path;

use ddirac::{Coordinate, InitialMomentum, Method, OutputOptions, Problem, Stats, Summary};
use serde::Serialize;

use crate::spec::Plan;

/// The content of `summary.json`, in the order it is written.
#[derive(Serialize)]
pub struct SummaryJson<'a> {
    ddirac_version: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    spec: Option<String>,
    system: &'a str,
    parameters: Parameters<'a>,
    coordinates: &'a [String],
    angles: Vec<String>,
    method: MethodJson,
    steps: usize,
    step: f64,
    duration: f64,
    initial: InitialJson<'a>,
    output: OutputJson,
    #[serde(rename = "final")]
    final_state: FinalJson<'a>,
    energy: StatsJson,
    discrete_energy: StatsJson,
    momentum_map: MomentumMapJson<'a>,
    derivatives: String,
    newton: NewtonJson,
    wall_seconds: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    total_wall_seconds: Option<f64>,
    reference_error: Option<f64>,
    chart_switches: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    sensitivity: Option<SensitivityJson<'a>>,
    warnings: Vec<WarningJson>,
}

/// With `method.sensitivities`: the tangent map d(q_N, p_N)/d(q_0, p_0) (`state`, 2n rows of 2n,
/// q then p in the coordinates' order).
#[derive(Serialize)]
struct SensitivityJson<'a> {
    state: &'a [Vec<f64>],
}

/// One warning: `{kind, step, t, message, count}` (`step` and `t` are `null` for a finding before
/// the first step).
#[derive(Serialize)]
pub struct WarningJson {
    kind: &'static str,
    step: Option<usize>,
    t: Option<f64>,
    message: String,
    count: usize,
}

impl WarningJson {
    pub(crate) fn new(w: &ddirac::Warning) -> Self {
        Self { kind: w.kind.name(), step: w.step, t: w.t, message: w.message.clone(), count: w.count }
    }
}

/// Prints each warning of a run once on stderr.
pub fn print_warnings(warnings: &[ddirac::Warning]) {
    for w in warnings {
        eprintln!("warning [{}]: {w}", w.kind.name());
    }
}

/// Parameters as a JSON object `{name: value}`, in the system's order.
pub(crate) struct Parameters<'a>(pub(crate) &'a [(String, f64)]);

impl Serialize for Parameters<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_map(self.0.iter().map(|(name, value)| (name, value)))
    }
}

#[derive(Serialize)]
struct MethodJson {
    rule: &'static str,
    variant: &'static str,
    reduced: bool,
    connection: Vec<Vec<f64>>,
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
    atlas: bool,
    sensitivities: bool,
}

#[derive(Serialize)]
struct InitialJson<'a> {
    q: &'a [f64],
    #[serde(skip_serializing_if = "Option::is_none")]
    p: Option<&'a [f64]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    v: Option<&'a [f64]>,
}

#[derive(Serialize)]
struct OutputJson {
    every: usize,
    wrap_angles: bool,
}

#[derive(Serialize)]
struct FinalJson<'a> {
    q: &'a [f64],
    p: &'a [f64],
}

#[derive(Serialize)]
pub(crate) struct StatsJson {
    #[serde(skip_serializing_if = "Option::is_none")]
    initial: Option<f64>,
    min: f64,
    max: f64,
    mean: f64,
}

impl StatsJson {
    pub(crate) fn new(s: &Stats, with_initial: bool) -> Self {
        Self { initial: with_initial.then_some(s.initial), min: s.min, max: s.max, mean: s.mean }
    }
}

#[derive(Serialize)]
struct MomentumMapJson<'a> {
    initial: &'a [f64],
    max_drift: f64,
    scale: f64,
    max_relative_drift: Option<f64>,
}

#[derive(Serialize)]
pub(crate) struct NewtonJson {
    total_iterations: usize,
    total_jacobians: usize,
    max_iterations: usize,
    max_residual: f64,
    subdivided_steps: usize,
    max_subdivision: usize,
}

impl NewtonJson {
    pub(crate) fn new(n: &ddirac::diagnostics::NewtonSummary) -> Self {
        Self {
            total_iterations: n.total_iterations,
            total_jacobians: n.total_jacobians,
            max_iterations: n.max_iterations,
            max_residual: n.max_residual,
            subdivided_steps: n.subdivided_steps,
            max_subdivision: n.max_subdivision,
        }
    }
}

/// What a run was, besides the library's [`Summary`] of it: what `summary.json` records of the
/// system, the problem, the method and the output, and of the run's file and whole time when it
/// ran from a spec file.
pub struct RunRecord<'a> {
    /// The system's name (a built-in's, or the spec's `system.name`).
    pub system: &'a str,
    /// Its parameters, in its order.
    pub parameters: &'a [(String, f64)],
    /// Its coordinates (which are angles; the shape of the connection).
    pub coordinates: Vec<Coordinate>,
    /// The problem run.
    pub problem: &'a Problem,
    /// The method it ran with.
    pub method: &'a Method,
    /// The rows kept.
    pub output: &'a OutputOptions,
    /// The spec file's path, for a run of a file.
    pub spec: Option<String>,
    /// The whole command's time, for a run of a file.
    pub total_seconds: Option<f64>,
}

/// The content of `summary.json` of a run from a spec file.
pub fn summary_json<'a>(plan: &'a Plan, summary: &'a Summary, spec: &Path, total_seconds: f64) -> SummaryJson<'a> {
    let record = RunRecord {
        system: &plan.name,
        parameters: &plan.parameters,
        coordinates: plan.system.coordinates(),
        problem: &plan.problem,
        method: &plan.method,
        output: &plan.output,
        spec: Some(spec.display().to_string()),
        total_seconds: Some(total_seconds),
    };
    summary_json_of(record, summary)
}

/// The content of `summary.json` of any run: what the command line writes and the Python module
/// returns as a run's `summary`, from one definition.
pub fn summary_json_of<'a>(record: RunRecord<'a>, summary: &'a Summary) -> SummaryJson<'a> {
    let (method, problem) = (record.method, record.problem);
    let (p, v) = match &problem.initial {
        InitialMomentum::Momentum(p) => (Some(p.as_slice()), None),
        InitialMomentum::Velocity(v) => (None, Some(v.as_slice())),
    };
    SummaryJson {
        ddirac_version: env!("CARGO_PKG_VERSION"),
        spec: record.spec,
        system: record.system,
        parameters: Parameters(record.parameters),
        coordinates: &summary.coordinates,
        angles: record
            .coordinates
            .iter()
            .filter(|c| c.kind == ddirac::CoordinateKind::Angle)
            .map(|c| c.name.clone())
            .collect(),
        method: MethodJson {
            rule: method.rule.name(),
            variant: method.variant.name(),
            reduced: method.reduced,
            connection: connection(method, &record.coordinates),
            tolerance: method.newton.tolerance,
            max_iterations: method.newton.max_iterations,
            jacobian: if method.newton.reuse_jacobian { "reuse" } else { "fresh" },
            check_invariance: method.check_invariance,
            derivatives: method.differentiation.name(),
            on_energy_jump: method.energy_jump.action.name(),
            order: method.composition.order(),
            composition: method.composition.name(),
            stages: method.composition.coefficients().len(),
            atlas: method.atlas,
            sensitivities: method.sensitivities,
            energy_jump_threshold: method.energy_jump.threshold,
        },
        steps: summary.steps,
        step: summary.step,
        duration: summary.step * summary.steps as f64,
        initial: InitialJson { q: &problem.q0, p, v },
        output: OutputJson { every: record.output.every, wrap_angles: record.output.wrap_angles },
        final_state: FinalJson { q: &summary.final_q, p: &summary.final_p },
        energy: StatsJson::new(&summary.energy, true),
        discrete_energy: StatsJson::new(&summary.discrete_energy, false),
        momentum_map: MomentumMapJson {
            initial: &summary.momentum_map.initial,
            max_drift: summary.momentum_map.max_drift,
            scale: summary.momentum_map.scale,
            max_relative_drift: summary.momentum_map.max_relative_drift,
        },
        derivatives: summary.derivatives.to_string(),
        newton: NewtonJson::new(&summary.newton),
        wall_seconds: summary.wall_seconds,
        total_wall_seconds: record.total_seconds,
        reference_error: summary.reference_error,
        chart_switches: summary.chart_switches,
        sensitivity: summary.sensitivity.as_deref().map(|state| SensitivityJson { state }),
        warnings: summary.warnings.iter().map(WarningJson::new).collect(),
    }
}

/// K as written to the summary: the method's rows, or zeros of the right shape.
fn connection(method: &Method, coordinates: &[Coordinate]) -> Vec<Vec<f64>> {
    method.connection.as_ref().map(ddirac::Connection::rows).unwrap_or_else(|| {
        let n_x = coordinates.iter().filter(|c| c.role == ddirac::Role::Shape).count();
        vec![vec![0.0; n_x]; coordinates.len() - n_x]
    })
}

/// The short human summary printed after a successful run.
pub fn human(plan: &Plan, summary: &Summary, dir: &Path, total_seconds: f64) -> String {
    let m = &plan.method;
    let list = |names: &[String], values: &[f64]| {
        names.iter().zip(values).map(|(n, v)| format!("{n} = {v:.10}")).collect::<Vec<_>>().join(", ")
    };
    let e = &summary.energy;
    let spread = (e.max - e.min) / e.initial.abs().max(f64::MIN_POSITIVE);
    let reference = summary.reference_error.map_or("none (no exact solution)".to_owned(), |r| format!("{r:.6e}"));
    [
        format!(
            "{}: {} steps of h = {} (T = {}), rule {}, variant {}, {}{}",
            plan.name,
            summary.steps,
            summary.step,
            summary.step * summary.steps as f64,
            m.rule.name(),
            m.variant.name(),
            if m.reduced { "reduced" } else { "unreduced" },
            composition(m.composition)
        ),
        format!("  final q          {}", list(&summary.coordinates, &summary.final_q)),
        format!("  energy           [{:.10e}, {:.10e}] (relative spread {spread:.3e})", e.min, e.max),
        momentum_map(&summary.momentum_map),
        format!(
            "  newton           {} iterations in total, at most {} per step, {} Jacobians, largest residual {:.3e}",
            summary.newton.total_iterations,
            summary.newton.max_iterations,
            summary.newton.total_jacobians,
            summary.newton.max_residual
        ) + &subdivided(&summary.newton),
        format!("  derivatives      {}", summary.derivatives),
        format!("  reference error  {reference}"),
        charts(plan, summary),
        warnings(&summary.warnings),
        format!("  output           {}", dir.display()),
        format!("  wall time        {:.3} s ({:.3} s integrating)", total_seconds, summary.wall_seconds),
    ]
    .into_iter()
    .filter(|line| !line.is_empty())
    .collect::<Vec<_>>()
    .join("\n")
}

/// The atlas line: the charts and the switches between them, for a system with an atlas (empty
/// without one).
fn charts(plan: &Plan, summary: &Summary) -> String {
    let charts = plan.system.charts();
    match (charts.is_empty(), plan.method.atlas) {
        (true, _) => String::new(),
        (false, false) => format!("  charts           main chart only (atlas = false; {} more declared)", charts.len()),
        (false, true) => format!(
            "  charts           {} switches among {} charts (the main one and {}; see the `chart` column)",
            summary.chart_switches,
            charts.len() + 1,
            if charts.len() <= 2 { charts.join(", ") } else { format!("{} others", charts.len()) }
        ),
    }
}

/// The momentum-map line: the drift, and relative to what (the larger of ‖J_0‖∞ and the run's
/// largest momentum, so that J_0 = 0 has a scale too).
fn momentum_map(j: &ddirac::diagnostics::MomentumMapDrift) -> String {
    match j.max_relative_drift {
        Some(relative) => format!(
            "  momentum map     drift {:.3e} (relative {relative:.3e} to {:.3e}, the largest of |J_0| and the momenta)",
            j.max_drift, j.scale
        ),
        None => format!("  momentum map     drift {:.3e} (every momentum is 0)", j.max_drift),
    }
}

/// The warnings line: their number and kinds (each is printed in full on stderr).
pub(crate) fn warnings(warnings: &[ddirac::Warning]) -> String {
    if warnings.is_empty() {
        return "  warnings         none".into();
    }
    let kinds: Vec<&str> = warnings.iter().map(|w| w.kind.name()).collect();
    format!("  warnings         {} ({}; see stderr and summary.json)", warnings.len(), kinds.join(", "))
}

/// ", order p (set, s stages)" for a composed method, nothing for the basic one.
pub(crate) fn composition(c: ddirac::Composition) -> String {
    if c.is_basic() {
        String::new()
    } else {
        format!(", order {} ({}, {} sub-steps)", c.order(), c.name(), c.coefficients().len())
    }
}

/// "; k steps taken as up to m sub-steps" when failed steps were subdivided, nothing otherwise.
fn subdivided(newton: &ddirac::diagnostics::NewtonSummary) -> String {
    match newton.subdivided_steps {
        0 => String::new(),
        k => format!("; {k} failed steps taken as up to {} sub-steps", newton.max_subdivision),
    }
}

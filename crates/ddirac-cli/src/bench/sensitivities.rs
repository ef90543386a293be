//! `sensitivities`: the cost of a step that also propagates its tangent map
//! (`method.sensitivities`, [`ddirac::tangent_map`]) against the plain step, on the paper's double
//! spherical pendulum (§7.2, reduced (+), midpoint, h = 0.01, compiled derivatives), side by side.

use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Differentiation, Method, Problem, Rule, Variant};
use serde_json::Value;

use super::harness::{compare, Pair, Target};
use super::{built_in, engine, print, to_json, Settings};

/// The target of the issue that asked for tangent maps: a step with its tangent map at most twice
/// the plain step.
const TARGET: Target = Target::AtMost(2.0);

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 500 } else { 5000 };
    print::heading("sensitivities", "a step with its tangent map against the plain step");
    let system = built_in("double_spherical_pendulum")?;
    let problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let plain =
        Method { differentiation: Differentiation::Compiled, ..super::method(Rule::Midpoint, true, Variant::Plus) };
    let tangent = Method { sensitivities: true, ..plain.clone() };
    let what = "double spherical pendulum, reduced (+)";
    let contenders = vec![
        engine("plain step", what, system.as_ref(), &problem, plain)?,
        engine("with tangent map", what, system.as_ref(), &problem, tangent)?,
    ];
    let pairs = [Pair::new("with tangent map", "plain step").target(TARGET)];
    let title = format!("double spherical pendulum, reduced (+), compiled, h = 0.01, {steps} steps; time ratio");
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    to_json(&comparison)
}

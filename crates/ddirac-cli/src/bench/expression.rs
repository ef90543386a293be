//! `expression`: the double spherical pendulum (paper §7.2) with its Lagrangian written as text
//! (`ddirac::expression::ExpressionSystem`, the spec shared with the library's expression tests and
//! benchmark) against the same Lagrangian in Rust (`systems::DoubleSphericalPendulum`): whole runs,
//! reduced (+), midpoint rule, h = 0.01.

use ddirac::expression::ExpressionSystem;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Pair, Target};
use super::{engine, integrate_once, max_difference, method, print, to_json, Settings};

#[path = "../../../ddirac/tests/common/pendulum_text.rs"]
mod pendulum_text;

/// A text Lagrangian should cost at most this many Rust ones.
const TARGET: Target = Target::AtMost(1.5);

#[derive(Serialize)]
struct Report {
    comparison: Comparison,
    /// max_i |q_N,i| difference between the two runs.
    final_q_difference: f64,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 200 } else { 1000 };
    print::heading("expression", "a Lagrangian written as text against the same in Rust");
    let rust = DoubleSphericalPendulum::default();
    let text = ExpressionSystem::<4>::new(&pendulum_text::double_spherical_pendulum_spec())
        .map_err(|e| miette::miette!("the double spherical pendulum written as text does not compile: {e}"))?;
    let problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let reduced = method(Rule::Midpoint, true, Variant::Plus);
    let what = |name: &str| format!("double spherical pendulum ({name}), midpoint, reduced (+)");
    let finals = [
        integrate_once(&what("Rust"), &rust, &problem, &reduced)?.final_q,
        integrate_once(&what("text"), &text, &problem, &reduced)?.final_q,
    ];
    let contenders = vec![
        engine("Rust", &what("Rust"), &rust, &problem, reduced.clone())?,
        engine("text", &what("text"), &text, &problem, reduced)?,
    ];
    let title = format!("double spherical pendulum, midpoint, reduced (+), h = 0.01, {steps} steps");
    let comparison = compare(title, settings.schedule, contenders, &[Pair::new("text", "Rust").target(TARGET)])?;
    print::comparison(&comparison);
    let difference = max_difference(&finals[..1], &finals[1..]);
    println!("    text and Rust, max |q_N difference|: {difference:.2e}");
    to_json(&Report { comparison, final_q_difference: difference })
}

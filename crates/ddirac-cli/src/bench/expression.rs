//! `expression`: the double spherical pendulum (paper §7.2) with its Lagrangian written as text
//! (`ddirac::expression::ExpressionSpec::into_dyn`, the spec shared with the library's expression tests and
//! benchmark) against the same Lagrangian in Rust (`systems::DoubleSphericalPendulum`): whole runs,
//! reduced (+), midpoint rule, h = 0.01; and the chain of 50 pendula written as text against the
//! built-in `pendulum_chain` of 50 links (both in a dimension chosen at run time, type-erased as a
//! spec runs them), compiled derivatives, time per step after set-up (each batch restarts one
//! prepared stepper from its first state); and what padding costs: the text chain of 13, run in the
//! engine of 16 with padding coordinates (`ddirac::padding`), against the text chains of 13 and 16,
//! per step.

use ddirac::systems::{DoubleSphericalPendulum, PendulumChain};
use ddirac::{Differentiation, Method, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Pair, Target};
use super::{
    built_in, built_in_with, engine, integrate_once, max_difference, method, print, stepping, to_json, Settings,
};

#[path = "../../../ddirac/tests/common/chain_text.rs"]
mod chain_text;
#[path = "../../../ddirac/tests/common/pendulum_text.rs"]
mod pendulum_text;

/// A text Lagrangian should cost at most this many Rust ones.
const TARGET: Target = Target::AtMost(1.5);
/// A step of the text chain of 50 should cost at most this many of the built-in chain's (issue 12).
const CHAIN_TARGET: Target = Target::AtMost(1.2);
/// Links of the chain compared.
const LINKS: usize = 50;

#[derive(Serialize)]
struct Report {
    comparison: Comparison,
    /// max_i |q_N,i| difference between the two runs.
    final_q_difference: f64,
    /// The chain of 50 pendula, per step.
    chain: ChainReport,
    /// The padded chain of 13 against the chains of 13 and 16, per step.
    padding: Comparison,
}

#[derive(Serialize)]
struct ChainReport {
    comparison: Comparison,
    /// max_i |q_N,i| difference between the two steppers after one batch.
    final_q_difference: f64,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 200 } else { 1000 };
    print::heading("expression", "a Lagrangian written as text against the same in Rust");
    let rust = built_in("double_spherical_pendulum")?;
    let text = pendulum_text::double_spherical_pendulum_spec()
        .into_dyn()
        .map_err(|e| miette::miette!("the double spherical pendulum written as text does not compile: {e}"))?;
    let (rust, text) = (rust.as_ref(), text.as_ref());
    let problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let reduced = method(Rule::Midpoint, true, Variant::Plus);
    let what = |name: &str| format!("double spherical pendulum ({name}), midpoint, reduced (+)");
    let finals = [
        integrate_once(&what("Rust"), rust, &problem, &reduced)?.final_q,
        integrate_once(&what("text"), text, &problem, &reduced)?.final_q,
    ];
    let contenders = vec![
        engine("Rust", &what("Rust"), rust, &problem, reduced.clone())?,
        engine("text", &what("text"), text, &problem, reduced)?,
    ];
    let title = format!("double spherical pendulum, midpoint, reduced (+), h = 0.01, {steps} steps");
    let comparison = compare(title, settings.schedule, contenders, &[Pair::new("text", "Rust").target(TARGET)])?;
    print::comparison(&comparison);
    let difference = max_difference(&finals[..1], &finals[1..]);
    println!("    text and Rust, max |q_N difference|: {difference:.2e}");
    let chain = chain(settings)?;
    let padding = padding(settings)?;
    to_json(&Report { comparison, final_q_difference: difference, chain, padding })
}

/// The chain of 50 pendula as text against the built-in one, per step.
fn chain(settings: &Settings) -> Result<ChainReport, miette::Report> {
    let steps = if settings.quick { 20 } else { 200 };
    let text = chain_text::chain_spec(LINKS)
        .into_dyn()
        .map_err(|e| miette::miette!("the chain of {LINKS} written as text does not compile: {e}"))?;
    let built_in = built_in_with("pendulum_chain", &[("links", LINKS as f64)])?;
    let problem = PendulumChain::<LINKS>::problem(steps, 0.005);
    let compiled =
        Method { differentiation: Differentiation::Compiled, ..method(Rule::Midpoint, false, Variant::Plus) };
    let (text_contender, text_end) = stepping("text", text.as_ref(), &problem, &compiled)?;
    let (rust_contender, rust_end) = stepping("Rust", built_in.as_ref(), &problem, &compiled)?;
    let title = format!(
        "chain of {LINKS} pendula, midpoint, unreduced, compiled, h = 0.005, {steps} steps per batch after set-up"
    );
    let pairs = [Pair::new("text", "Rust").target(CHAIN_TARGET)];
    let comparison = compare(title, settings.schedule, vec![rust_contender, text_contender], &pairs)?;
    print::comparison(&comparison);
    let difference = max_difference(&[rust_end], &[text_end]);
    println!("    text and Rust, max |q_N difference|: {difference:.2e}");
    Ok(ChainReport { comparison, final_q_difference: difference })
}

/// The text chain of 13 links, padded to the engine of 16, against the text chains of 13 and 16,
/// per step (compiled derivatives): what running in a larger engine costs.
fn padding(settings: &Settings) -> Result<Comparison, miette::Report> {
    let steps = if settings.quick { 20 } else { 400 };
    let compiled =
        Method { differentiation: Differentiation::Compiled, ..method(Rule::Midpoint, false, Variant::Plus) };
    let chains = [(13, 13), (13, 16), (16, 16)].map(|(links, size)| {
        chain_text::chain_spec(links)
            .into_dyn_in(size)
            .map_err(|e| miette::miette!("the chain of {links} written as text does not compile: {e}"))
    });
    let [thirteen, padded, sixteen] = chains;
    let (thirteen, padded, sixteen) = (thirteen?, padded?, sixteen?);
    let problem = |links: usize| {
        let q0 = (1..=links).map(|i| 0.5 * (std::f64::consts::PI * i as f64 / (links + 1) as f64).sin()).collect();
        Problem::new(0.005, steps, q0, ddirac::InitialMomentum::Momentum(vec![0.0; links]))
    };
    let contenders = vec![
        stepping("13", thirteen.as_ref(), &problem(13), &compiled)?.0,
        stepping("13 in 16", padded.as_ref(), &problem(13), &compiled)?.0,
        stepping("16", sixteen.as_ref(), &problem(16), &compiled)?.0,
    ];
    let title = format!("text chains of 13, 13 (padded to 16) and 16 pendula, compiled, {steps} steps per batch");
    let pairs = [Pair::new("13 in 16", "13"), Pair::new("13 in 16", "16")];
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    Ok(comparison)
}

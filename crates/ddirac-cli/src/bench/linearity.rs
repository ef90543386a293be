//! `linearity`: time per step of the same integration run for 10³, 10⁴ and 10⁵ steps: the charged
//! particle of paper §7.1 (left rule, reduced (+), fixed h = 0.02, so that every step does the same
//! work). A cost linear in the number of steps gives per-step ratios ≈ 1; the fixed cost of a run
//! (setup, invariance check, summary) makes the shortest run slightly dearer per step.

use ddirac::systems::ChargedParticle;
use ddirac::{Differentiation, Method, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Pair};
use super::{engine, method, print, to_json, Settings};

#[derive(Serialize)]
struct Report {
    comparison: Comparison,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let counts: [usize; 3] = if settings.quick { [100, 1000, 10_000] } else { [1000, 10_000, 100_000] };
    print::heading("linearity", "time per step against the number of steps");
    let system = super::built_in("charged_particle")?;
    let problems: Vec<Problem> =
        counts.iter().map(|&steps| Problem { steps, ..ChargedParticle::paper_problem(1000) }).collect();
    let names: Vec<String> = counts.iter().map(|n| format!("{n} steps")).collect();
    // One derivative path for every count: the compiled closed-form step (under `auto` the run of
    // 10³ steps would use dual numbers).
    let reduced = Method { differentiation: Differentiation::Compiled, ..method(Rule::Left, true, Variant::Plus) };
    let mut contenders = vec![];
    for (name, problem) in names.iter().zip(&problems) {
        let what = format!("charged particle, left, reduced (+), h = 0.02, {name}");
        contenders.push(engine(name, &what, system.as_ref(), problem, reduced.clone())?);
    }
    let pairs: Vec<Pair<'_>> = names[1..].iter().map(|n| Pair::new(n, &names[0])).collect();
    let title =
        "charged particle (paper §7.1), left rule, reduced (+), compiled closed-form step, h = 0.02; ratios of \
                 time per step";
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    to_json(&Report { comparison })
}

//! `scaling`: time per step against the number of coordinates, for a planar chain of N pendula
//! (built-in `pendulum_chain` as a spec runs it: `systems::PendulumChain<N>` up to 16 links, above in a
//! dimension chosen at run time; released from rest in one arch; midpoint rule, unreduced, as the
//! chain has no symmetry; h = 0.01) with N = 2 … 50, all sizes timed side by side. Between two
//! sizes the ratio of times per step gives the exponent p of time ∝ N^p.

use std::hint::black_box;

use ddirac::systems::PendulumChain;
use ddirac::{Differentiation, Method, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Contender, Pair};
use super::{built_in_with, method, print, timed_run, to_json, Settings, LAST_ROW_ONLY};

/// Step size.
const STEP: f64 = 0.01;

/// The chain of `N` links as a contender named `N = …` doing `steps` steps.
fn chain<const N: usize>(steps: usize) -> Result<(usize, Contender<'static>), miette::Report> {
    let system = built_in_with("pendulum_chain", &[("links", N as f64)])?;
    let problem = PendulumChain::<N>::problem(steps, STEP);
    // Dual numbers at every size: under `auto` the choice between compiling and dual numbers depends
    // on the size (its cost estimate), which would mix two paths in one curve.
    let unreduced = Method { differentiation: Differentiation::Dual, ..method(Rule::Midpoint, false, Variant::Plus) };
    let what = format!("chain of {N} pendula, midpoint, unreduced, dual numbers, h = {STEP}, {steps} steps");
    let run =
        move || black_box(system.as_ref()).integrate(black_box(&problem), &unreduced, &LAST_ROW_ONLY, &mut |_| Ok(()));
    Ok((N, timed_run(&name(N), &what, steps, run)?))
}

fn name(links: usize) -> String {
    format!("N = {links}")
}

/// The exponent p of time per step ∝ N^p between two sizes.
#[derive(Serialize)]
struct Exponent {
    from: usize,
    to: usize,
    /// ln(median ratio) / ln(to / from).
    exponent: f64,
}

#[derive(Serialize)]
struct Report {
    links: Vec<usize>,
    comparison: Comparison,
    exponents: Vec<Exponent>,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 10 } else { 200 };
    print::heading("scaling", "time per step against the number of coordinates");
    let (links, contenders): (Vec<usize>, Vec<Contender<'static>>) =
        [chain::<2>(steps)?, chain::<5>(steps)?, chain::<10>(steps)?, chain::<20>(steps)?, chain::<50>(steps)?]
            .into_iter()
            .unzip();
    let names: Vec<String> = links.iter().map(|&n| name(n)).collect();
    let pairs: Vec<Pair<'_>> = names.windows(2).map(|w| Pair::new(&w[1], &w[0])).collect();
    let title =
        format!("chain of N pendula, midpoint, unreduced, dual numbers at every size, h = {STEP}, {steps} steps");
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    let exponents: Vec<Exponent> = links
        .windows(2)
        .zip(&comparison.ratios)
        .map(|(w, r)| Exponent {
            from: w[0],
            to: w[1],
            exponent: r.spread.median.ln() / (w[1] as f64 / w[0] as f64).ln(),
        })
        .collect();
    let text: Vec<String> =
        exponents.iter().map(|e| format!("{} ({} → {})", print::number(e.exponent), e.from, e.to)).collect();
    println!("    exponent p of time per step ∝ N^p: {}", text.join(", "));
    to_json(&Report { links, comparison, exponents })
}

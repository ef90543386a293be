//! `dimension`: what a dimension chosen at run time costs. The chain of N pendula (built-in
//! `pendulum_chain`, `systems::PendulumChain<N>` as a spec runs it, released from rest in one arch;
//! midpoint rule, unreduced, h = 0.005) in its fixed dimension against the same chain in a dynamic
//! one (`systems::DynamicPendulumChain`, as the built-in chain runs any other number of links), time
//! per step after set-up, with dual numbers and with compiled derivatives, for the N of
//! [`LINKS`] that are engine sizes ([`ddirac::systems::CHAIN_LINKS`]). Both give the same
//! numbers (the library's tests hold them equal bit for bit), so the ratio is the price of the
//! heap-held arrays and of dual numbers in blocks (`ddirac::dim::first_blocks`).

use ddirac::systems::{DynamicPendulumChain, CHAIN_LINKS};
use ddirac::{Differentiation, InitialMomentum, Method, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Pair};
use super::{built_in_with, max_difference, method, print, stepping, to_json, Settings};

/// The numbers of links compared, where the chain has a fixed dimension: up to the largest, 16 (above
/// it the dynamic dimension was measured faster or within 6 %, and the fixed sizes 20–50 left).
const LINKS: [usize; 4] = [4, 8, 12, 16];
/// The numbers of links compared with `--quick`.
const QUICK_LINKS: [usize; 2] = [8, 16];
/// Step size.
const STEP: f64 = 0.005;

#[derive(Serialize)]
struct Report {
    /// One comparison per number of links and derivative path.
    sizes: Vec<Sized>,
}

#[derive(Serialize)]
struct Sized {
    links: usize,
    derivatives: &'static str,
    comparison: Comparison,
    /// max_i |q_N,i| difference between the two steppers after one batch (0: the same numbers).
    final_q_difference: f64,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    print::heading("dimension", "the chain in a fixed dimension against a dynamic one");
    let mut sizes = Vec::new();
    let counts: &[usize] = if settings.quick { &QUICK_LINKS } else { &LINKS };
    for &links in counts.iter().filter(|n| CHAIN_LINKS.contains(n)) {
        for (derivatives, differentiation) in
            [("dual numbers", Differentiation::Dual), ("compiled", Differentiation::Compiled)]
        {
            sizes.push(compared(settings, links, derivatives, differentiation)?);
        }
    }
    to_json(&Report { sizes })
}

fn compared(
    settings: &Settings,
    links: usize,
    derivatives: &'static str,
    differentiation: Differentiation,
) -> Result<Sized, miette::Report> {
    // About the same time per batch at every size: 2 × 10⁴ steps of 16 links, fewer for more.
    let full = (20_000 * 16 * 16 / (links * links)).max(20);
    let steps = if settings.quick { 10 } else { full };
    let fixed = built_in_with("pendulum_chain", &[("links", links as f64)])?;
    let dynamic = DynamicPendulumChain::new(links).erased();
    let problem = chain_problem(links, steps);
    let method = Method { differentiation, ..method(Rule::Midpoint, false, Variant::Plus) };
    let (fixed_contender, fixed_end) = stepping("fixed", fixed.as_ref(), &problem, &method)?;
    let (dynamic_contender, dynamic_end) = stepping("dynamic", dynamic.as_ref(), &problem, &method)?;
    let title = format!(
        "chain of {links} pendula, midpoint, unreduced, {derivatives}, h = {STEP}, {steps} steps per batch after set-up"
    );
    let pairs = [Pair::new("dynamic", "fixed")];
    let comparison = compare(title, settings.schedule, vec![fixed_contender, dynamic_contender], &pairs)?;
    print::comparison(&comparison);
    let difference = max_difference(&[fixed_end], &[dynamic_end]);
    println!("    fixed and dynamic, max |q_N difference|: {difference:.2e}");
    Ok(Sized { links, derivatives, comparison, final_q_difference: difference })
}

/// `PendulumChain::<N>::problem` for a number of links known at run time.
fn chain_problem(links: usize, steps: usize) -> Problem {
    let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / (links + 1) as f64).sin();
    Problem::new(STEP, steps, (1..=links).map(arch).collect(), InitialMomentum::Momentum(vec![0.0; links]))
}

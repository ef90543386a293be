//! Text systems beyond 16 coordinates (issue 12): a chain of 24 and of 50 pendula written as text
//! runs through the type-erased layer (what specs and Python use) and equals the built-in
//! `pendulum_chain` of as many links — its Lagrangian and gradients at random points, and its
//! trajectories with dual numbers and with compiled derivatives. Counts between the engine's sizes are
//! in `issue_12_text_systems_of_any_size_up_to_100.rs`.

use crate::chain_text;
use crate::common;

use chain_text::chain_spec;
use common::{max_scaled_row_diff, sampler};
use ddirac::expression::ExpressionSystem;
use ddirac::systems::{find, PendulumChain};
use ddirac::{Differentiation, DynSystem, Method, OutputOptions, Problem, Rule, System};

/// Every row's (q, p) of a run of a type-erased system.
fn rows(system: &dyn DynSystem, problem: &Problem, method: &Method) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let summary = system
        .integrate(problem, method, &OutputOptions::default(), &mut |row| {
            rows.push(row.q.iter().chain(row.p.iter()).copied().collect());
            Ok(())
        })
        .unwrap_or_else(|e| panic!("the run failed: {e}"));
    assert_eq!(summary.steps, problem.steps);
    rows
}

fn midpoint(differentiation: Differentiation) -> Method {
    Method { rule: Rule::Midpoint, differentiation, atlas: false, ..Method::default() }
}

/// The text Lagrangian against the built-in one and its velocity gradient (the momenta) at random
/// states, through the typed systems.
fn same_lagrangian<const N: usize>() -> f64 {
    let text = ExpressionSystem::<N>::new(&chain_spec(N)).unwrap();
    let built_in = PendulumChain::<N>::default();
    let mut random = sampler(N as u64);
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        let q: [f64; N] = std::array::from_fn(|_| 2.0 * random());
        let v: [f64; N] = std::array::from_fn(|_| 3.0 * random());
        let (a, b) = (text.lagrangian(&q, &v), built_in.lagrangian(&q, &v));
        worst = worst.max((a - b).abs() / b.abs().max(1.0));
        let (pa, pb) = (
            ddirac::mechanics::legendre::momentum(&text, &q, &v),
            ddirac::mechanics::legendre::momentum(&built_in, &q, &v),
        );
        for i in 0..N {
            worst = worst.max((pa[i] - pb[i]).abs() / pb[i].abs().max(1.0));
        }
    }
    worst
}

/// The text chain of `links` against the built-in one over `steps` steps of h = 0.005, both
/// type-erased, with `differentiation`: the largest scaled row difference.
fn same_motion(links: usize, steps: usize, differentiation: Differentiation) -> f64 {
    let text = chain_spec(links).into_dyn().unwrap();
    assert_eq!(text.coordinates().len(), links);
    let built_in = (find("pendulum_chain").unwrap().build)(&[("links".into(), links as f64)]).unwrap();
    let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / (links + 1) as f64).sin();
    let problem = Problem::new(
        0.005,
        steps,
        (1..=links).map(arch).collect(),
        ddirac::InitialMomentum::Momentum(vec![0.0; links]),
    );
    let method = midpoint(differentiation);
    let (a, b) = (rows(text.as_ref(), &problem, &method), rows(built_in.as_ref(), &problem, &method));
    let moved = max_scaled_row_diff(&b[b.len() - 1..], &b[..1]);
    assert!(moved > 1e-2, "the chain should move: {moved:e}");
    max_scaled_row_diff(&a, &b)
}

#[test]
fn a_text_chain_of_24_has_the_built_in_lagrangian_and_motion() {
    let lagrangian = same_lagrangian::<24>();
    eprintln!("24 links: text and built-in Lagrangian and momenta differ by {lagrangian:.2e} (relative)");
    assert!(lagrangian <= 1e-13, "{lagrangian:e}");
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let difference = same_motion(24, 400, differentiation);
        eprintln!("24 links, {differentiation:?}: trajectories differ by {difference:.2e}");
        assert!(difference <= 1e-11, "{differentiation:?}: {difference:e}");
    }
}

#[test]
fn a_text_chain_of_50_has_the_built_in_lagrangian_and_motion() {
    let lagrangian = same_lagrangian::<50>();
    eprintln!("50 links: text and built-in Lagrangian and momenta differ by {lagrangian:.2e} (relative)");
    assert!(lagrangian <= 1e-13, "{lagrangian:e}");
    for (differentiation, steps) in [(Differentiation::Dual, 40), (Differentiation::Compiled, 400)] {
        let difference = same_motion(50, steps, differentiation);
        eprintln!("50 links, {differentiation:?}, {steps} steps: trajectories differ by {difference:.2e}");
        assert!(difference <= 1e-11, "{differentiation:?}: {difference:e}");
    }
}

//! The chain-of-pendula example (`examples/pendulum_chain.toml`, built-in `pendulum_chain` with the
//! number of links as a parameter): its energy against the potential of the initial arch, the same
//! motion as the library's `PendulumChain<8>`, and the refusals of unsupported sizes and of reduction.

use crate::common;

use common::{assert_fails, example, numbers, run, succeed, TempDir};
use ddirac::systems::PendulumChain;
use ddirac::{InitialMomentum, Method, OutputOptions, Problem, Rule};

#[test]
fn the_example_keeps_the_energy_of_its_initial_arch() {
    let dir = TempDir::new("chain");
    let run = succeed(&example("pendulum_chain.toml"), &[], &dir);
    let names: Vec<String> = (1..=8).map(|i| format!("theta{i}")).collect();
    assert_eq!(run.summary["coordinates"], serde_json::json!(names));
    assert_eq!(run.summary["parameters"]["links"], 8.0);
    assert_eq!(run.summary["steps"], 6000);

    // Released from rest: E = −g m l Σ_i μ_i cos θ_i with μ_i = 9 − i bobs at and below link i.
    let q0 = numbers(&run.summary["initial"]["q"]);
    let energy0: f64 = q0.iter().enumerate().map(|(i, theta)| -9.8 * (8 - i) as f64 * theta.cos()).sum();
    let energy = run.column("energy");
    assert!((energy[0] - energy0).abs() <= 1e-13 * energy0.abs(), "{} vs {energy0}", energy[0]);
    // Bounded (measured relative spread 4.2·10⁻⁷) and without drift between the first and last thirds.
    let deviation = |rows: &[f64]| rows.iter().map(|e| (e - energy0).abs()).fold(0.0, f64::max);
    let third = energy.len() / 3;
    let (first, last) = (deviation(&energy[..third]), deviation(&energy[2 * third..]));
    assert!(first.max(last) <= 2e-6 * energy0.abs(), "{first:e}, {last:e}");
    assert!(last <= 2.0 * first, "the energy error grows: {first:e} → {last:e}");
    // The chain moves: its last link swings back and forth.
    let theta8 = run.column("theta8");
    let (lo, hi) = theta8.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    assert!(lo < -0.5 && hi > 0.5, "theta8 in [{lo}, {hi}]");

    // The library's typed chain with the same data gives the same q_N.
    let problem = Problem::new(0.005, 6000, q0, InitialMomentum::Momentum(vec![0.0; 8]));
    let method = Method { rule: Rule::Midpoint, ..Method::default() };
    let solution = ddirac::solve(
        &PendulumChain::<8>::default(),
        &problem,
        &method,
        &OutputOptions { every: 6000, ..Default::default() },
    )
    .unwrap();
    let difference = solution.summary.final_q.iter().zip(run.final_q()).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(difference <= 1e-12, "{difference:e}");
}

#[test]
fn unsupported_numbers_of_links_and_reduction_are_refused() {
    let dir = TempDir::new("chain-refused");
    let spec = example("pendulum_chain.toml");
    for (links, shown) in [("2.5", "2.5"), ("0", "0")] {
        let stderr = assert_fails(
            &run(&spec, &[&format!("parameters.links={links}")], &dir),
            &dir,
            &[&format!("invalid parameter `links`: {shown} is not a number of links: a positive whole number")],
        );
        assert_eq!(common::underlined(&stderr, "links ="), [links]);
    }
    let stderr = assert_fails(
        &run(&spec, &["parameters.links=5000"], &dir),
        &dir,
        &["invalid parameter `links`: 5000 links are more than 4096"],
    );
    assert_eq!(common::underlined(&stderr, "links ="), ["5000"]);
    // A supported size with the wrong number of initial angles.
    assert_fails(
        &run(&spec, &["parameters.links=9"], &dir),
        &dir,
        &["`initial.q` has 8 entries, but the system has 9 coordinates"],
    );
    let stderr = assert_fails(
        &run(&spec, &["method.reduced=true"], &dir),
        &dir,
        &["reduction needs at least one group coordinate; the system has none"],
    );
    assert_eq!(common::underlined(&stderr, "reduced = true"), ["true"]);
}

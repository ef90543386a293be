//! Glued where charts overlap ([`ddirac::blend`]), the compositions of order 6 and 8 lost their order:
//! their error holds the partition of unity's high derivatives, which at the steps they are taken with
//! dwarf the asymptotic error. The spherical pendulum going over the top at order 8 ended 4.6e-5,
//! 2.4e-5, 3.7e-6, 7.3e-9, 8.3e-7 and 9.3e-8 away from its reference at N = 500 … 1000 steps (not
//! monotone in N; the double spherical pendulum's work-precision race fell from 0.75–1.04× DOP853's
//! time to 13–40×). These orders now switch charts at a step ([`ddirac::atlas::glues`]), each step
//! with one chart's compiled scheme.
//!
//! The reference is independent of the atlas: the main chart alone, at 64 000 steps of the same order.

use super::issue_30_atlas_error_regular_in_h::{distance, last_bob, over_the_top};
use ddirac::Composition;

/// The final bob of [`over_the_top`], the largest departure of H(q_k, p_k) from its initial value
/// relative to it, and the chart switches.
fn final_bob(steps: usize, atlas: bool, composition: Composition) -> ([f64; 3], f64, usize) {
    let solution = over_the_top(steps, atlas, composition);
    let e0 = solution.energy[0];
    let departure = solution.energy.iter().fold(0.0f64, |m, e| m.max((e - e0).abs())) / e0.abs();
    (last_bob(&solution), departure, solution.summary.chart_switches)
}

/// (N, the atlas's error, its max |ΔH/H₀|, the main chart's error alone) for each N.
fn sweep(composition: Composition, steps: &[usize]) -> Vec<(usize, f64, f64, f64)> {
    let (reference, _, _) = final_bob(64_000, false, composition);
    steps
        .iter()
        .map(|&n| {
            let (bob, departure, switches) = final_bob(n, true, composition);
            assert!(switches > 0, "no switch at N = {n}");
            let (main, _, _) = final_bob(n, false, composition);
            (n, distance(&bob, &reference), departure, distance(&main, &reference))
        })
        .collect()
}

#[test]
fn order_8_in_an_atlas_keeps_its_accuracy() {
    let errors = sweep(Composition::KahanLi17, &[500, 600, 700, 800, 900, 1000, 1600]);
    for &(n, error, departure, main) in &errors {
        println!("N = {n}: error {error:.2e} (main chart alone {main:.2e}), max |ΔH/H₀| {departure:.1e}");
        // Glued: 4.6e-5, 2.4e-5, 3.7e-6, 7.3e-9, 8.3e-7 and 9.3e-8 at N = 500 … 1000; switched at a
        // step: 4.1e-8, 7.0e-8, 1.4e-7, 3.1e-9, 9.1e-9, 2.3e-10, and 1.3e-11 at N = 1600.
        let bound = if n >= 1600 { 1e-10 } else { 3e-7 };
        assert!(error < bound, "N = {n}: error {error:.2e} against {bound:.0e}");
        assert!(departure < 1e-7, "N = {n}: max |ΔH/H₀| {departure:.1e}");
        // The main chart alone passes near its pole: 3.2e-3 … 1.5e-6.
        assert!(error < 1e-2 * main, "N = {n}: atlas {error:.2e}, main chart alone {main:.2e}");
    }
}

#[test]
fn order_6_in_an_atlas_keeps_its_accuracy() {
    let errors = sweep(Composition::KahanLi9, &[500, 600, 700, 800, 900, 1000]);
    for &(n, error, departure, main) in &errors {
        println!("N = {n}: error {error:.2e} (main chart alone {main:.2e}), max |ΔH/H₀| {departure:.1e}");
        // Switched at a step: 1.9e-5, 4.6e-6, 2.8e-5, 4.8e-7, 2.6e-6, 2.2e-7 (the main chart alone:
        // 1.9e-2 … 6.6e-5).
        assert!(error < 1e-4 && error < 0.1 * main, "N = {n}: atlas {error:.2e}, main chart alone {main:.2e}");
        assert!(departure < 1e-5, "N = {n}: max |ΔH/H₀| {departure:.1e}");
    }
}

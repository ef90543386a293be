//! Re-centred charts (paper §6): a large offset of a coordinate must not cost digits, and angles are
//! reported continuous or wrapped on request.

use std::f64::consts::PI;

use ddirac::chart::wrap;
use ddirac::systems::ChargedParticle;
use ddirac::{solve, Method, OutputOptions, Rule};

/// The charged particle's θ is cyclic and q3 is free: shifting either by 10⁷ must leave the motion
/// unchanged to round-off. In a global chart the velocity (θ1 − θ0)/h would be formed from numbers of
/// size 10⁷ and lose about 10⁷ · ε / h ≈ 10⁻⁸ per step.
#[test]
fn a_large_offset_costs_no_digits_in_the_unreduced_scheme() {
    let system = ChargedParticle::default();
    let method = Method { rule: Rule::Midpoint, reduced: false, ..Method::default() };
    let base = ChargedParticle::paper_problem(400);
    let mut shifted = base.clone();
    shifted.q0[2] = 1e7;
    shifted.q0[3] = 1e7;
    let a = solve(&system, &base, &method, &OutputOptions::default()).unwrap();
    let b = solve(&system, &shifted, &method, &OutputOptions::default()).unwrap();
    let mut worst = 0.0f64;
    for (qa, qb) in a.q.iter().zip(&b.q) {
        worst = worst.max((qa[0] - qb[0]).abs()).max((qa[1] - qb[1]).abs());
        worst = worst.max(((qb[2] - 1e7) - qa[2]).abs() / 1e7 * 1e-7); // q3 itself carries 10⁷'s rounding
    }
    for (pa, pb) in a.p.iter().zip(&b.p) {
        worst = worst.max((0..4).fold(0.0f64, |m, i| m.max((pa[i] - pb[i]).abs())));
    }
    eprintln!("largest difference with a 1e7 offset: {worst:.2e}");
    assert!(worst < 1e-13, "{worst:e}");
}

#[test]
fn angles_are_continuous_by_default_and_wrapped_on_request() {
    let system = ChargedParticle::default();
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let problem = ChargedParticle::paper_problem(200);
    let continuous = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
    let wrapped = solve(&system, &problem, &method, &OutputOptions { every: 1, wrap_angles: true }).unwrap();
    // θ̇ = p_θ − ⟨A, q̇⟩ stays near 1 + ½ r² ≥ 1, so θ passes π several times over T = 20.
    let theta: Vec<f64> = continuous.q.iter().map(|q| q[3]).collect();
    assert!(theta.last().unwrap() > &(4.0 * PI), "θ_N = {}", theta.last().unwrap());
    assert!(theta.windows(2).all(|w| (w[1] - w[0]).abs() < 1.0), "continuous output has no jumps");
    for (c, w) in continuous.q.iter().zip(&wrapped.q) {
        assert!(w[3] > -PI && w[3] <= PI);
        assert!((wrap(c[3]) - w[3]).abs() < 1e-12);
        assert_eq!(&c[..3], &w[..3], "real coordinates are never wrapped");
    }
}

//! Chord Newton (the default: one Jacobian per step, or kept across steps for n ≥ 9) against
//! classical Newton (a Jacobian at every iterate): the same trajectories within what the Newton
//! tolerance allows, with far fewer Jacobians.

use crate::common;

use common::{max_scaled_row_diff, run};
use ddirac::dim::Fixed;
use ddirac::newton::KeptJacobian;
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler, PendulumChain};
use ddirac::{Differentiation, InitialMomentum, Method, NewtonOptions, Problem, Rule, Solution, System, Variant};

/// Both runs on dual numbers, whose cost ratio sets when a Jacobian is kept across steps.
fn pair<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: Method) -> (Solution, Solution) {
    let method = Method { differentiation: Differentiation::Dual, ..method };
    let chord = run(
        system,
        problem,
        &Method { newton: NewtonOptions { reuse_jacobian: true, ..method.newton }, ..method.clone() },
    );
    let classical =
        run(system, problem, &Method { newton: NewtonOptions { reuse_jacobian: false, ..method.newton }, ..method });
    (chord, classical)
}

/// Largest row-wise difference of q and of p, each relative to max(1, ‖·‖∞).
fn differences(a: &Solution, b: &Solution) -> (f64, f64) {
    (max_scaled_row_diff(&a.q, &b.q), max_scaled_row_diff(&a.p, &b.p))
}

fn per_step(count: usize, s: &Solution) -> f64 {
    count as f64 / s.summary.steps as f64
}

fn check<S: System<N>, const N: usize>(name: &str, system: &S, problem: &Problem, method: Method, bound: f64) {
    let (chord, classical) = pair(system, problem, method);
    let (dq, dp) = differences(&chord, &classical);
    let (jc, jn) = (
        per_step(chord.summary.newton.total_jacobians, &chord),
        per_step(classical.summary.newton.total_jacobians, &classical),
    );
    eprintln!("{name}: chord vs classical q {dq:.1e}, p {dp:.1e}; Jacobians per step {jc:.3} vs {jn:.3}");
    assert!(dq <= bound && dp <= bound, "{name}: q differs by {dq:e}, p by {dp:e} (bound {bound:e})");
    // Classical Newton evaluates a Jacobian at every iterate, the last included.
    let classical_iterations = per_step(classical.summary.newton.total_iterations, &classical);
    assert!(
        (jn - (classical_iterations + 1.0)).abs() < 1e-12,
        "{name}: {jn} Jacobians for {classical_iterations} corrections"
    );
    if KeptJacobian::new(Fixed::<N>).across_solves() {
        assert!(jc < 0.5, "{name}: {jc} Jacobians per step although they are kept across steps");
    } else {
        assert!((1.0..1.1).contains(&jc), "{name}: {jc} Jacobians per step, expected one (rarely two)");
    }
}

#[test]
fn charged_particle_chord_equals_classical() {
    let system = ChargedParticle::default();
    for rule in [Rule::Left, Rule::Midpoint] {
        for reduced in [true, false] {
            let method = Method { rule, variant: Variant::Plus, reduced, ..Method::default() };
            check(
                &format!("charged particle {}, reduced {reduced}", rule.name()),
                &system,
                &ChargedParticle::paper_problem(1000),
                method,
                1e-13,
            );
        }
    }
}

#[test]
fn double_spherical_pendulum_chord_equals_classical() {
    // The reduced steps of the main chart: with the atlas, the steps where charts overlap are glued
    // unreduced steps (`ddirac::blend`), whose momenta the two Newton variants leave apart by what the
    // tolerance allows at |p| ≈ 6e5 (3.5e-10 relative), a comparison of another scheme.
    let method = Method { rule: Rule::Midpoint, reduced: true, atlas: false, ..Method::default() };
    // The first 1000 steps of the paper's run, before the passage near the pole that amplifies
    // round-off about 10⁵ times.
    let mut problem = DoubleSphericalPendulum::paper_problem(10_000);
    problem.steps = 1000;
    check("double spherical pendulum", &DoubleSphericalPendulum::default(), &problem, method, 1e-10);
}

#[test]
fn kepler_and_heavy_top_chord_equal_classical() {
    let kepler = Problem::new(0.01, 2000, vec![1.0, 0.3], InitialMomentum::Momentum(vec![0.2, 1.2]));
    check(
        "kepler",
        &Kepler::default(),
        &kepler,
        Method { rule: Rule::Midpoint, reduced: true, ..Method::default() },
        1e-12,
    );
    let top = Problem::new(1e-3, 2000, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0]));
    check(
        "heavy top",
        &HeavyTop::default(),
        &top,
        Method { rule: Rule::Midpoint, reduced: true, ..Method::default() },
        1e-12,
    );
}

#[test]
fn a_long_chain_keeps_its_jacobian_across_steps() {
    const N: usize = 16;
    assert!(KeptJacobian::new(Fixed::<N>).across_solves());
    // Iterates of a Jacobian kept across steps converge linearly: each step lands within about
    // 10⁻¹³ of classical Newton's, and 200 steps add these up (measured 6e-11).
    let method = Method { rule: Rule::Midpoint, ..Method::default() };
    check("chain of 16 pendula", &PendulumChain::<N>::default(), &PendulumChain::<N>::problem(200, 0.01), method, 1e-9);
}

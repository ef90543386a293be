//! Conservation laws of the discrete flows.
//!
//! * Discrete Noether theorem: the momentum map J(q, p) = p_g (Lemma 2.1) is constant. The reduced
//!   schemes carry μ_{k+1} = μ_k as an equation of motion (paper eq. `geometricequations`), so it
//!   holds to round-off. The unreduced flow conserves it because L_d is G-invariant: D1 L_d + D2 L_d
//!   has no group component, so J_{k+1} − J_k is the group component of the Newton residual of the
//!   step p_k + D1 L_d(q_k, q_{k+1}) = 0. Its drift is therefore bounded by N times the largest
//!   accepted residual (plus round-off), which is what the unreduced runs are held to.
//! * Energy: a variational integrator does not conserve the Hamiltonian exactly, but keeps it
//!   oscillating about its initial value with no drift over long runs.

use crate::common;

use common::{method, run};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TwoBody};
use ddirac::{Connection, InitialMomentum, Problem, Rule, Solution, Variant};

fn two_body_problem() -> Problem {
    Problem::new(0.01, 1000, vec![0.3, -0.2, 1.0, 0.0], InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]))
}

/// The double spherical pendulum with p_ϑ1 = 3·10⁴ (a rotation about the vertical); the paper's
/// other initial data, 2000 steps over T = 20. Its momenta reach 10⁶, so the Newton residual
/// threshold (10⁻¹² relative to the momenta) is about 10⁻⁶: the unreduced run's J drifts by about
/// 3·10⁻¹⁰ relative, all of it accounted for by the residuals, while the reduced run keeps J exact.
fn spinning_pendulum_problem() -> Problem {
    Problem::new(0.01, 2000, vec![0.0, 2.25, 2.0, 3.0], InitialMomentum::Momentum(vec![3e4, 0.0, 1.0, 1.0]))
}

/// The largest relative drift of J from the rows (independent of the summary's own bookkeeping).
/// The largest |J_k − J_0| of the rows, relative to the larger of ‖J_0‖∞ and the rows' largest |p_i|
/// (the summary's scale, when every step is a row).
fn row_drift(solution: &Solution) -> f64 {
    let j0 = &solution.momentum_map[0];
    let scale = solution.p.iter().map(|p| common::sup_norm(p)).fold(common::sup_norm(j0), f64::max);
    solution.momentum_map.iter().map(|j| common::max_abs_diff(j, j0)).fold(0.0, f64::max) / scale
}

fn check_momentum_map<S: ddirac::System<4>>(
    name: &str,
    system: &S,
    problem: &Problem,
    rule: Rule,
    connection: Option<Connection>,
    expected: &[f64],
) {
    for reduced in [true, false] {
        let solution = run(system, problem, &method(rule, Variant::Plus, reduced, connection.clone()));
        let drift = &solution.summary.momentum_map;
        let relative = drift.max_relative_drift.expect("J0 ≠ 0 in these problems");
        let rows = row_drift(&solution);
        eprintln!(
            "{name}, reduced = {reduced}: J0 = {:?}, max relative drift {:.3e} (summary), {rows:.3e} (rows)",
            drift.initial, relative
        );
        let j0_error = common::max_abs_diff(&drift.initial, expected);
        assert!(
            j0_error <= 1e-12 * common::sup_norm(expected),
            "{name}: J0 = {:?}, expected {expected:?}",
            drift.initial
        );
        assert!(
            (rows - relative).abs() <= 1e-15 + 1e-6 * rows,
            "summary's drift {relative} disagrees with the rows' {rows}"
        );
        if reduced {
            assert!(relative <= 1e-12, "{name}: reduced drift {relative}");
        } else {
            let newton = solution.summary.newton;
            let scale = common::sup_norm(expected).max(1.0);
            let bound = problem.steps as f64 * (newton.max_residual + 1e-15 * scale);
            eprintln!(
                "  unreduced: |J_k − J_0| ≤ {:.3e}, bound N·(max Newton residual {:.3e} + round-off) = {bound:.3e}",
                drift.max_drift, newton.max_residual
            );
            assert!(drift.max_drift <= bound, "{name}: unreduced drift {} above {bound}", drift.max_drift);
            // At the default Newton tolerance: 3.2e-10 measured for the spinning pendulum, 1e-14 for
            // the others.
            assert!(relative <= 1e-9, "{name}: unreduced drift {relative}");
        }
    }
}

#[test]
fn charged_particle_momentum_map_is_constant() {
    let system = ChargedParticle::default();
    check_momentum_map("charged particle", &system, &ChargedParticle::paper_problem(1000), Rule::Left, None, &[1.0]);
}

/// J = p_{r1} = m1 ṙ1 + m2 (ṙ1 + ṙ) is the total linear momentum: (1.5·0.1, 1.5·0.05 + 0.5·1.1).
#[test]
fn two_body_momentum_map_is_the_total_momentum_and_constant() {
    let system = TwoBody::default();
    let expected = [0.15, 0.625];
    check_momentum_map("two body, K = 0", &system, &two_body_problem(), Rule::Midpoint, None, &expected);
    let k = Some(system.centre_of_mass_connection().unwrap());
    check_momentum_map("two body, K = -m2/M I", &system, &two_body_problem(), Rule::Midpoint, k, &expected);
}

#[test]
fn spinning_double_spherical_pendulum_momentum_map_is_constant() {
    let system = DoubleSphericalPendulum::default();
    check_momentum_map(
        "double spherical pendulum, p_vartheta1 = 3e4",
        &system,
        &spinning_pendulum_problem(),
        Rule::Midpoint,
        None,
        &[3e4],
    );
}

/// Relative energy error |H_k − H_0| / |H_0| over the rows, and the relative difference of the mean
/// energy over the first and the last tenth of the run.
fn energy_behaviour(solution: &Solution) -> (f64, f64) {
    let e = &solution.energy;
    let e0 = e[0];
    let oscillation = e.iter().map(|x| (x - e0).abs()).fold(0.0, f64::max) / e0.abs();
    let tenth = e.len() / 10;
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    let drift = (mean(&e[e.len() - tenth..]) - mean(&e[..tenth])).abs() / e0.abs();
    (oscillation, drift)
}

/// The paper's run (N = 10⁴, T = 100, midpoint): the energy spikes by about 0.6 % while the
/// pendulum passes near the lower pole, but the mean energy at the end equals that at the start to
/// far better than the spikes.
#[test]
fn double_spherical_pendulum_energy_oscillates_without_drift() {
    let system = DoubleSphericalPendulum::default();
    let problem = DoubleSphericalPendulum::paper_problem(10_000);
    for reduced in [true, false] {
        let solution = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, reduced, None));
        let (oscillation, drift) = energy_behaviour(&solution);
        eprintln!(
            "double spherical pendulum, reduced = {reduced}: H0 = {:.6e}, max |H_k − H0|/|H0| = {oscillation:.3e}, \
             |mean(last tenth) − mean(first tenth)|/|H0| = {drift:.3e}",
            solution.energy[0]
        );
        // μ0 = 0 here: the drift is relative to the momenta, and the absolute one is bounded by the
        // residuals.
        let (j, newton) = (&solution.summary.momentum_map, solution.summary.newton);
        eprintln!(
            "  J0 = {:?}, max |J_k − J0| = {:.3e}, max Newton residual {:.3e}",
            j.initial, j.max_drift, newton.max_residual
        );
        assert_eq!(j.initial, vec![0.0]);
        let largest = solution.p.iter().map(|p| common::sup_norm(p)).fold(0.0, f64::max);
        assert!(j.scale >= largest && j.scale > 0.0, "scale {} below the rows' momenta {largest}", j.scale);
        assert_eq!(j.max_relative_drift, Some(j.max_drift / j.scale));
        assert!(j.max_drift <= problem.steps as f64 * (newton.max_residual + 1e-15), "J drift {}", j.max_drift);
        assert!(oscillation <= 1e-2, "reduced = {reduced}: energy oscillation {oscillation:e}");
        assert!(drift <= 1e-4, "reduced = {reduced}: energy drift {drift:e}");
        assert!(
            drift <= 0.05 * oscillation,
            "reduced = {reduced}: drift {drift:e} not far below spikes {oscillation:e}"
        );
    }
}

/// H = ½|p_x − μA(q)|²/m + ½μ² is conserved to round-off by all three rules: the rules coincide
/// on this system (A is linear with A(Δq)·Δq = 0) and the scheme keeps |Δq_k| constant.
#[test]
fn charged_particle_energy_is_conserved_to_round_off() {
    let system = ChargedParticle::default();
    for rule in [Rule::Left, Rule::Midpoint, Rule::Trapezoid] {
        for reduced in [true, false] {
            let problem = ChargedParticle::paper_problem(1000);
            let solution = run(&system, &problem, &method(rule, Variant::Plus, reduced, None));
            let (oscillation, drift) = energy_behaviour(&solution);
            eprintln!(
                "charged particle, {} rule, reduced = {reduced}, N = 1000: H0 = {}, max |H_k − H0|/|H0| = {oscillation:.3e}, \
                 drift {drift:.3e}",
                rule.name(),
                solution.energy[0]
            );
            assert!((solution.energy[0] - 1.5).abs() <= 1e-15, "H0 = ½(1 + 1) + ½ = 1.5");
            assert!(oscillation <= 1e-13, "{rule:?}, reduced = {reduced}: energy error {oscillation:e}");
        }
    }
}

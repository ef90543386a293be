//! Reduced-then-reconstructed equals unreduced: the reduced (+) and (−) schemes (paper eqs.
//! `geometricequations`, `geometricequationsminus` with the erratum of the implementation notes) and
//! the unreduced discrete Lagrange–Dirac flow (paper §2.3.2) must produce the same trajectory, for
//! the paper's two systems (connection K = 0) and for two bodies with the centre-of-mass connection
//! K = −m2/(m1 + m2)·I, where h_{d,Q}, h_{d,Σ} and h_d^0 are all non-zero.

use crate::common;

use common::{max_abs_diff, max_row_diff, max_scaled_row_diff, method, relative_diff, run};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TwoBody};
use ddirac::{Connection, InitialMomentum, Problem, Rule, Variant};

/// The eccentric two-body orbit: r1 = (0.3, −0.2), r = r2 − r1 = (1, 0), ṙ1 = (0.1, 0.05),
/// ṙ = (0, 1.1). With m1 = 1, m2 = 0.5, k = 1 the relative orbit has e ≈ 0.6 and period ≈ 1.8;
/// T = 10 covers five to six periods.
fn two_body_problem() -> Problem {
    Problem::new(0.01, 1000, vec![0.3, -0.2, 1.0, 0.0], InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]))
}

#[test]
fn charged_particle_reduced_plus_equals_unreduced_on_every_row() {
    let system = ChargedParticle::default();
    for steps in [10, 100, 1000] {
        let problem = ChargedParticle::paper_problem(steps);
        let unreduced = run(&system, &problem, &method(Rule::Left, Variant::Plus, false, None));
        let reduced = run(&system, &problem, &method(Rule::Left, Variant::Plus, true, None));
        let dq_final = max_abs_diff(&reduced.summary.final_q, &unreduced.summary.final_q);
        let dq = max_row_diff(&reduced.q, &unreduced.q);
        let dp = max_scaled_row_diff(&reduced.p, &unreduced.p);
        eprintln!("charged particle N = {steps}: |dq_N| = {dq_final:.3e}, max_k |dq_k| = {dq:.3e}, scaled max_k |dp_k| = {dp:.3e}");
        assert!(dq_final <= 1e-10, "N = {steps}: final q differs by {dq_final:e}");
        assert!(dq <= 1e-10, "N = {steps}: rows' q differ by up to {dq:e}");
        assert!(dp <= 1e-10, "N = {steps}: rows' p differ by up to {dp:e} (relative to max(1, |p|))");
    }
}

/// The paper's run (§7.2, N = 10⁴, T = 100, midpoint). Its passage within |sin φ| ≈ 2·10⁻³ of the
/// lower pole amplifies round-off about 10⁵×, so 10⁻⁷ relative is what double precision allows.
#[test]
fn double_spherical_pendulum_reduced_plus_equals_unreduced() {
    let system = DoubleSphericalPendulum::default();
    let problem = DoubleSphericalPendulum::paper_problem(10_000);
    let unreduced = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, false, None));
    let reduced = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, true, None));
    let dq = relative_diff(&reduced.summary.final_q, &unreduced.summary.final_q);
    let n = reduced.discrete_energy.len() - 1; // the last row has no L_d(q_N, q_{N+1})
    let de = max_abs_diff(&reduced.discrete_energy[..n], &unreduced.discrete_energy[..n]);
    let scale = common::sup_norm(&unreduced.discrete_energy[..n]);
    eprintln!(
        "double spherical pendulum N = 10^4: q_N(reduced) = {:?}, q_N(unreduced) = {:?}",
        reduced.summary.final_q, unreduced.summary.final_q
    );
    eprintln!(
        "  relative |dq_N| = {dq:.3e}; max_k |dL_d(q_k, q_k+1)| = {de:.3e} (max |L_d| = {scale:.3e}, ratio {:.3e})",
        de / scale
    );
    eprintln!(
        "  wall time: reduced {:.3} s, unreduced {:.3} s",
        reduced.summary.wall_seconds, unreduced.summary.wall_seconds
    );
    assert!(dq <= 1e-7, "relative difference of q_N {dq:e} exceeds 1e-7");
    assert!(de <= 1e-7 * scale, "discrete energy series differ by {de:e} (scale {scale:e})");
}

/// With K ≠ 0 the reduced unknowns and momenta are w = p_x + Kᵀ p_g and γ = g1 − g0 − K Δx, but the
/// reconstructed motion is the same: the connection only changes coordinates on the reduced space.
#[test]
fn two_body_reduced_with_and_without_connection_equals_unreduced() {
    let system = TwoBody::default();
    let problem = two_body_problem();
    let k = Some(system.centre_of_mass_connection().unwrap());
    let unreduced = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, false, None));
    let with_k = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, true, k));
    let without_k = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, true, None));
    let d_k = relative_diff(&with_k.summary.final_q, &unreduced.summary.final_q);
    let d_0 = relative_diff(&without_k.summary.final_q, &unreduced.summary.final_q);
    let d_k0 = relative_diff(&with_k.summary.final_q, &without_k.summary.final_q);
    let dp_k = max_scaled_row_diff(&with_k.p, &unreduced.p);
    let min_r = unreduced.q.iter().map(|q| q[2].hypot(q[3])).fold(f64::INFINITY, f64::min);
    eprintln!("two body: q_N = {:?}, min |r| = {min_r:.3}", unreduced.summary.final_q);
    eprintln!("  relative |dq_N|: K vs unreduced {d_k:.3e}, K = 0 vs unreduced {d_0:.3e}, K vs K = 0 {d_k0:.3e}");
    eprintln!("  scaled max_k |dp_k| (K vs unreduced) = {dp_k:.3e}");
    assert!(min_r < 0.3, "the orbit should be eccentric (min |r| = {min_r})");
    assert!(d_k <= 1e-9, "K ≠ 0 reduced vs unreduced: {d_k:e}");
    assert!(d_0 <= 1e-9, "K = 0 reduced vs unreduced: {d_0:e}");
    assert!(d_k0 <= 1e-9, "K ≠ 0 vs K = 0: {d_k0:e}");
    assert!(dp_k <= 1e-9, "K ≠ 0 reduced vs unreduced momenta: {dp_k:e}");
}

/// Reduced (−), reduced (+) and unreduced runs of one problem; returns the largest row-wise
/// differences of q, relative to ‖q_N‖∞ of the unreduced run: ((−) vs (+), (+) vs unreduced,
/// (−) vs unreduced), and the scaled largest difference of p between (−) and unreduced.
fn three_ways<S: ddirac::System<4>>(
    system: &S,
    problem: &Problem,
    rule: Rule,
    connection: Option<Connection>,
) -> ([f64; 3], f64) {
    let reduced = |variant| run(system, problem, &method(rule, variant, true, connection.clone()));
    let (minus, plus) = (reduced(Variant::Minus), reduced(Variant::Plus));
    let unreduced = run(system, problem, &method(rule, Variant::Plus, false, None));
    let scale = common::sup_norm(&unreduced.summary.final_q).max(1.0);
    let dq = [
        max_row_diff(&minus.q, &plus.q) / scale,
        max_row_diff(&plus.q, &unreduced.q) / scale,
        max_row_diff(&minus.q, &unreduced.q) / scale,
    ];
    (dq, max_scaled_row_diff(&minus.p, &unreduced.p))
}

fn report(name: &str, (dq, dp): ([f64; 3], f64)) {
    eprintln!(
        "{name}: max_k |dq_k| / max(1, |q_N|): (−) vs (+) {:.3e}, (+) vs unreduced {:.3e}, (−) vs unreduced {:.3e}; \
         scaled max_k |dp_k| (−) vs unreduced {dp:.3e}",
        dq[0], dq[1], dq[2]
    );
}

#[test]
fn charged_particle_minus_equals_plus_equals_unreduced() {
    let result = three_ways(&ChargedParticle::default(), &ChargedParticle::paper_problem(100), Rule::Left, None);
    report("charged particle, N = 100", result);
    let (dq, dp) = result;
    assert!(dq.iter().all(|&d| d <= 1e-10), "q differs: {dq:?}");
    assert!(dp <= 1e-10, "p differs: {dp:e}");
}

#[test]
fn double_spherical_pendulum_minus_equals_plus_equals_unreduced() {
    let problem = Problem { step: 0.01, steps: 2000, ..DoubleSphericalPendulum::paper_problem(1) };
    let result = three_ways(&DoubleSphericalPendulum::default(), &problem, Rule::Midpoint, None);
    report("double spherical pendulum, 2000 steps over T = 20", result);
    let (dq, dp) = result;
    assert!(dq.iter().all(|&d| d <= 1e-9), "q differs: {dq:?}");
    assert!(dp <= 1e-9, "p differs: {dp:e}");
}

#[test]
fn two_body_minus_equals_plus_equals_unreduced_for_both_connections() {
    let system = TwoBody::default();
    for (name, k) in [("K = -m2/M I", Some(system.centre_of_mass_connection().unwrap())), ("K = 0", None)] {
        let result = three_ways(&system, &two_body_problem(), Rule::Midpoint, k);
        report(&format!("two body, {name}"), result);
        let (dq, dp) = result;
        assert!(dq.iter().all(|&d| d <= 1e-9), "{name}: q differs: {dq:?}");
        assert!(dp <= 1e-9, "{name}: p differs: {dp:e}");
    }
}

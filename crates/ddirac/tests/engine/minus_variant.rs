//! The sign erratum of the reduced (−) equations.
//!
//! The paper's display `geometricequationsminus` prints the opposite sign on every momentum term.
//! Used as printed, the charged particle of paper §7.1 (p_θ = +1, p_z = 1) integrates the
//! time-reversed motion: θ̇ = −1 and z(20) = −20 instead of the exact z(t) = t. The correct signs,
//! derived from the reduced (−) Dirac structure and Dirac differential
//! (`prop:reduceddiractructurelocalminus`, `prop:reduceddiracdifferentiallocalminus`) with Lemma
//! `lemma:partialderivativesldminus`, are
//!
//! ```text
//! w_k = −∂l₋/∂x0,   μ_k = −∂l₋/∂γ,   w_{k+1} = ∂l₋/∂x1,   g_{k+1} = g_k − γ_k + K Δx,
//! ```
//!
//! and the (−) run must move forward like the (+) and unreduced runs. These tests would fail under
//! the printed signs.

use crate::common;

use common::{max_abs_diff, method, run};
use ddirac::systems::{ChargedParticle, TABLE_1};
use ddirac::{Rule, Variant};

#[test]
fn reduced_minus_charged_particle_moves_forward_in_time() {
    let system = ChargedParticle::default();
    let problem = ChargedParticle::paper_problem(100);
    let minus = run(&system, &problem, &method(Rule::Left, Variant::Minus, true, None));
    let plus = run(&system, &problem, &method(Rule::Left, Variant::Plus, true, None));
    let (q_minus, q_plus) = (&minus.summary.final_q, &plus.summary.final_q);
    eprintln!("(−) q_N = {q_minus:?}");
    eprintln!("(+) q_N = {q_plus:?}");

    // z is free flight with p_z = 1: z(t) = t exactly, and the left-rule scheme reproduces it.
    let z_error = minus.t.iter().zip(&minus.q).fold(0.0f64, |m, (t, q)| m.max((q[2] - t).abs()));
    eprintln!("(−) max_k |z_k − t_k| = {z_error:.3e}, z_N = {}", q_minus[2]);
    assert!((q_minus[2] - 20.0).abs() <= 1e-9, "z(20) = {} (printed signs give −20)", q_minus[2]);
    assert!(z_error <= 1e-9, "z_k departs from t_k by {z_error:e}");

    // θ: same direction and value as the (+) run, and increasing overall (θ̇ = p_θ − A·q̇).
    let theta_diff = (q_minus[3] - q_plus[3]).abs();
    eprintln!("θ_N: (−) {}, (+) {}, |difference| = {theta_diff:.3e}", q_minus[3], q_plus[3]);
    assert!(q_minus[3] > 0.0 && q_plus[3] > 0.0, "θ_N must be positive: (−) {}, (+) {}", q_minus[3], q_plus[3]);
    assert!(theta_diff <= 1e-10, "θ_N differs between (−) and (+) by {theta_diff:e}");
    let dq = max_abs_diff(q_minus, q_plus);
    assert!(dq <= 1e-10, "q_N differs between (−) and (+) by {dq:e}");

    // The whole configuration follows the exact helix with the published error (Table 1, N = 100).
    let error = minus.summary.reference_error.expect("exact solution");
    eprintln!("(−) ‖q(T) − q_N‖ = {error:.6} (paper: {})", TABLE_1[2].1);
    assert!((error - TABLE_1[2].1).abs() <= 5e-6, "‖q(T) − q_N‖ = {error}, paper prints {}", TABLE_1[2].1);
}

/// On the exact motion θ̇ = p_θ − A·q̇ = 3/2 − cos(t)/2 ≥ 1, so θ(t) = 3t/2 − sin(t)/2; the (−) run
/// must increase θ on every step (the printed signs decrease it) and agree with the unreduced run
/// along the whole trajectory, momenta included.
#[test]
fn reduced_minus_theta_increases_and_matches_unreduced_rows() {
    let system = ChargedParticle::default();
    let problem = ChargedParticle::paper_problem(200);
    let minus = run(&system, &problem, &method(Rule::Left, Variant::Minus, true, None));
    let unreduced = run(&system, &problem, &method(Rule::Left, Variant::Minus, false, None));
    let min_increment = minus.q.windows(2).map(|w| w[1][3] - w[0][3]).fold(f64::INFINITY, f64::min);
    let h = problem.step;
    let theta_exact = 1.5 * 20.0 - 0.5 * 20f64.sin();
    let theta_n = minus.summary.final_q[3];
    let dp = common::max_scaled_row_diff(&minus.p, &unreduced.p);
    let dq = common::max_row_diff(&minus.q, &unreduced.q);
    eprintln!(
        "(−), N = 200: min_k (θ_k+1 − θ_k)/h = {:.4}; θ_N = {theta_n:.6}, exact θ(20) = {theta_exact:.6}",
        min_increment / h
    );
    eprintln!("(−) reduced vs unreduced: max_k |dq_k| = {dq:.3e}, scaled max_k |dp_k| = {dp:.3e}");
    assert!(min_increment >= 0.9 * h, "θ must grow at a rate ≥ 1 on every step; smallest rate {}", min_increment / h);
    assert!((theta_n - theta_exact).abs() <= 0.05, "θ_N = {theta_n}, exact {theta_exact}");
    assert!(minus.momentum_map.iter().all(|j| j[0] == 1.0), "μ must stay exactly +1");
    assert!(dq <= 1e-10 && dp <= 1e-10, "(−) reduced departs from unreduced: dq {dq:e}, dp {dp:e}");
}

//! Derivatives by automatic differentiation against the paper's hand-derived equations.
//!
//! Paper §7.1 writes the reduced (+) equations of the charged particle out by hand
//! (eq. `reduceddiscreteequationsem`), with A(q) = (B0/2)(−q2, q1, 0), Δ = q_{k+1} − q_k and
//! ∇⟨A, Δ⟩ = (B0/2)(Δ2, −Δ1, 0):
//!
//! ```text
//! (m/h) Δ + μ_{k+1} A(q_k) = w_{k+1}
//! (1/h) (⟨A(q_k), Δ⟩ + θ_{k+1}) = μ_{k+1}          (θ_{k+1} = γ_k, the group increment)
//! (m/h) Δ − μ_{k+1} (∇⟨A, Δ⟩ − A(q_k)) = w_k
//! μ_{k+1} = μ_k
//! ```
//!
//! The library never sees these formulas; it differentiates L_d. Every step of a computed reduced
//! trajectory must satisfy them to round-off.

use ddirac::mechanics::legendre;
use ddirac::systems::ChargedParticle;
use ddirac::{solve, Method, OutputOptions, Rule, System};

fn potential(b0: f64, q: &[f64]) -> [f64; 3] {
    [-0.5 * b0 * q[1], 0.5 * b0 * q[0], 0.0]
}

#[test]
fn reduced_charged_particle_satisfies_the_papers_hand_written_equations() {
    let system = ChargedParticle { m: 1.3, b0: 0.7 };
    let (m, b0) = (system.m, system.b0);
    let steps = 100;
    let mut problem = ChargedParticle::paper_problem(steps);
    problem.q0 = vec![0.3, -0.2, 0.1, 0.5];
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let s = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
    let h = problem.step;
    let mut worst = 0.0f64;
    for k in 0..steps {
        let (q0, q1) = (&s.q[k], &s.q[k + 1]);
        // K = 0: w = p_x, μ = p_θ
        let (w0, w1, mu0, mu1) = (&s.p[k][..3], &s.p[k + 1][..3], s.p[k][3], s.p[k + 1][3]);
        let d: Vec<f64> = (0..3).map(|i| q1[i] - q0[i]).collect();
        let gamma = q1[3] - q0[3];
        let a = potential(b0, q0);
        let a_dot_d: f64 = (0..3).map(|i| a[i] * d[i]).sum();
        let grad_a_d = [0.5 * b0 * d[1], -0.5 * b0 * d[0], 0.0];
        let scale = 1.0 + mu1.abs() + w1.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..3 {
            worst = worst.max((m / h * d[i] + mu1 * a[i] - w1[i]).abs() / scale);
            worst = worst.max((m / h * d[i] - mu1 * (grad_a_d[i] - a[i]) - w0[i]).abs() / scale);
        }
        worst = worst.max(((a_dot_d + gamma) / h - mu1).abs() / scale);
        worst = worst.max((mu1 - mu0).abs() / scale);
    }
    eprintln!("largest scaled residual of eq. reduceddiscreteequationsem: {worst:.2e}");
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn legendre_transform_matches_the_papers_momenta() {
    // p = m q̇ + (⟨A, q̇⟩ + θ̇) A(q),  p_θ = ⟨A, q̇⟩ + θ̇   (paper §7.1)
    let system = ChargedParticle { m: 2.0, b0: 1.5 };
    let q = [0.4, -1.1, 3.0, 0.2];
    let v = [0.3, 0.8, -0.5, 1.7];
    let a = potential(system.b0, &q);
    let coupling = a[0] * v[0] + a[1] * v[1] + v[3];
    let expected = [
        system.m * v[0] + coupling * a[0],
        system.m * v[1] + coupling * a[1],
        system.m * v[2] + coupling * a[2],
        coupling,
    ];
    let p = legendre::momentum(&system, &q, &v);
    for i in 0..4 {
        assert!((p[i] - expected[i]).abs() < 1e-14, "{p:?} vs {expected:?}");
    }
    // The inverse transform recovers v, and H = ½ m |q̇|² + ½ p_θ² (no potential).
    let (back, mismatch) = legendre::velocity(&system, &q, &p);
    assert!(mismatch < 1e-13);
    assert!((0..4).all(|i| (back[i] - v[i]).abs() < 1e-12), "{back:?}");
    let h = legendre::hamiltonian(&system, &q, &p);
    let expected_h = 0.5 * system.m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * coupling * coupling;
    assert!((h - expected_h).abs() < 1e-13 * expected_h);
    assert!(legendre::is_regular(&system, &q, &v));
    assert_eq!(system.lagrangian(&q, &v), expected_h);
}

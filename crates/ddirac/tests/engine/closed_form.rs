//! The closed-form step (`compiled::LinearStep`): runs whose step equations are linear in the
//! unknowns, after γ is eliminated with the conserved μ, take one compiled solve per step and no
//! Newton iteration. They agree with the hand-written step of the same scheme, with the dual-number
//! Newton path and with an exact discrete solution; runs whose equations are not linear keep Newton.

use crate::common;

use common::max_scaled_row_diff;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum};
use ddirac::{
    solve, Coordinate, DerivativePath, Differentiation, InitialMomentum, Method, OutputOptions, Problem, Rule,
    Solution, System, Variant,
};
use num_dual::DualNum;

fn run<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: &Method, how: Differentiation) -> Solution {
    let method = Method { differentiation: how, ..method.clone() };
    solve(system, problem, &method, &OutputOptions::default()).unwrap_or_else(|e| panic!("{method:?}: {e}"))
}

fn closed_form(solution: &Solution) -> Option<usize> {
    match solution.summary.derivatives {
        DerivativePath::Compiled { closed_form, .. } => closed_form,
        DerivativePath::Dual { .. } => None,
    }
}

#[test]
fn charged_particle_reduced_steps_are_solved_in_closed_form() {
    let problem = ChargedParticle::paper_problem(2000);
    for rule in Rule::ALL {
        for variant in [Variant::Plus, Variant::Minus] {
            let method = Method { rule, variant, reduced: true, ..Method::default() };
            let compiled = run(&ChargedParticle::default(), &problem, &method, Differentiation::Compiled);
            let instructions = closed_form(&compiled);
            assert!(instructions.is_some(), "{method:?}: {}", compiled.summary.derivatives);
            assert_eq!(compiled.summary.newton.total_iterations, problem.steps, "{method:?}");
            assert_eq!(compiled.summary.newton.total_jacobians, problem.steps, "{method:?}");
            let dual = run(&ChargedParticle::default(), &problem, &method, Differentiation::Dual);
            let d = max_scaled_row_diff(&compiled.q, &dual.q).max(max_scaled_row_diff(&compiled.p, &dual.p));
            eprintln!("{rule:?} {variant:?}: {instructions:?} instructions, closed form vs dual Newton {d:.1e}");
            assert!(d < 1e-12, "{method:?}: {d:e}");
        }
    }
}

#[test]
fn closed_form_charged_particle_matches_the_hand_written_step() {
    let steps = 20_000;
    let problem = ChargedParticle::paper_problem(steps);
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let engine = run(&ChargedParticle::default(), &problem, &method, Differentiation::Compiled);
    assert!(closed_form(&engine).is_some());
    let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h: problem.step };
    let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
    let end = stepper.run(start, steps);
    let q = &engine.summary.final_q;
    let expected = [end.q[0], end.q[1], end.q[2], end.theta];
    let d = q.iter().zip(&expected).fold(0.0f64, |m, (a, b)| m.max((a - b).abs() / b.abs().max(1.0)));
    assert!(d < 1e-11, "engine {q:?} vs hand-written {expected:?}: {d:e}");
    let p = &engine.summary.final_p;
    let w = [end.w[0], end.w[1], end.w[2], end.mu];
    let dp = p.iter().zip(&w).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(dp < 1e-11, "momenta {p:?} vs {w:?}: {dp:e}");
}

#[test]
fn nonlinear_step_equations_keep_newton() {
    let method = Method { rule: Rule::Left, reduced: false, ..Method::default() };
    let problem = ChargedParticle::paper_problem(400);
    let unreduced = run(&ChargedParticle::default(), &problem, &method, Differentiation::Compiled);
    assert_eq!(closed_form(&unreduced), None, "unreduced charged particle: {}", unreduced.summary.derivatives);
    assert!(unreduced.summary.newton.total_iterations > problem.steps);

    let mut problem = DoubleSphericalPendulum::paper_problem(10_000);
    problem.steps = 200;
    for reduced in [false, true] {
        let method = Method { reduced, ..Method::default() };
        let pendulum = run(&DoubleSphericalPendulum::default(), &problem, &method, Differentiation::Compiled);
        assert_eq!(closed_form(&pendulum), None, "pendulum, reduced {reduced}: {}", pendulum.summary.derivatives);
    }
}

/// A harmonic oscillator, L = ½ m v² − ½ k x²: its midpoint-rule equations are linear.
struct Oscillator;

impl System<1> for Oscillator {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("x")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        v[0] * v[0] * 1.5 - q[0] * q[0] * 6.0
    }
}

#[test]
fn a_linear_unreduced_system_follows_its_exact_discrete_solution() {
    // m = 3, k = 12, ω = 2. The midpoint rule's discrete Euler–Lagrange equations
    // (m/h)(x_{k+1} − 2x_k + x_{k−1}) + (kh/4)(x_{k+1} + 2x_k + x_{k−1}) = 0 rotate with
    // cos(θ) = (1 − (ωh/2)²) / (1 + (ωh/2)²) per step.
    let (h, steps, x0, v0) = (0.05, 6000, 0.7, 0.4);
    let problem = Problem::new(h, steps, vec![x0], InitialMomentum::Momentum(vec![3.0 * v0]));
    let method = Method { rule: Rule::Midpoint, ..Method::default() };
    let solution = run(&Oscillator, &problem, &method, Differentiation::Compiled);
    assert!(closed_form(&solution).is_some(), "{}", solution.summary.derivatives);
    assert_eq!(solution.summary.newton.total_iterations, steps);
    let c = (h * h).mul_add(-1.0, 1.0) / (h * h).mul_add(1.0, 1.0);
    let theta = c.acos();
    let x1 = solution.q[1][0];
    // x_k = A cos(kθ) + B sin(kθ) through x_0 and the engine's x_1 (the first step is the same
    // linear map, so this checks the other 5999).
    let (a, b) = (x0, (x1 - x0 * theta.cos()) / theta.sin());
    let worst = solution.q.iter().enumerate().fold(0.0f64, |m, (k, q)| {
        let exact = a * (k as f64 * theta).cos() + b * (k as f64 * theta).sin();
        m.max((q[0] - exact).abs())
    });
    assert!(worst < 1e-11, "largest deviation from the exact discrete solution {worst:e}");
    let dual = run(&Oscillator, &problem, &method, Differentiation::Dual);
    assert!(max_scaled_row_diff(&solution.q, &dual.q) < 1e-12);
}

//! Reduced Dirac structures and Dirac differentials (paper §3.4, §4): trajectories computed by the
//! reduced integrators satisfy [Ω̂♭_{d±}](X) = [D̂^±L_d](…) step by step, the general forms
//! eq:geometricequations and the corrected eq:geometricequationsminus, and NOT the printed
//! eq:geometricequationsminus. Lemmas partialderivativesld(minus) are checked against AD of L_d.

use ddirac::reduction::reduced_lagrangian::ReducedLagrangian;
use ddirac::systems::{ChargedParticle, TwoBody};
use ddirac::{solve, Connection, InitialMomentum, Method, OutputOptions, Problem, Rule, Split, System, Variant};
use ddirac_oracle::dirac_structure::*;
use ddirac_oracle::reduced_lagrangian::{ld_partials, partials_minus, partials_plus};
use ddirac_oracle::trivialization::SplitVector;

use crate::common;
use common::sampler;

/// One step of a trajectory in split form: (x_k, g_k, w_k, μ_k) and the same at k + 1.
struct Point {
    x: Vec<f64>,
    g: Vec<f64>,
    w: Vec<f64>,
    mu: Vec<f64>,
}

/// Runs the reduced integrator and returns its rows as (x, g, w = p_x + Kᵀp_g, μ = p_g).
fn reduced_run<S: System<4>>(
    system: &S,
    problem: &Problem,
    rule: Rule,
    variant: Variant,
    k: &[Vec<f64>],
) -> Vec<Point> {
    let method =
        Method { rule, variant, reduced: true, connection: Some(Connection::new(k).unwrap()), ..Method::default() };
    let solution = solve(system, problem, &method, &OutputOptions::default()).expect("the run succeeds");
    let split = Split::new(&system.coordinates());
    assert_eq!(solution.q.len(), problem.steps + 1);
    solution
        .q
        .iter()
        .zip(&solution.p)
        .map(|(q, p)| {
            let (px, pg) = (split.x(p), split.g(p));
            let w = (0..split.n_x()).map(|i| px[i] + (0..split.n_g()).map(|j| k[j][i] * pg[j]).sum::<f64>()).collect();
            Point { x: split.x(q), g: split.g(q), w, mu: pg }
        })
        .collect()
}

/// K (x1 − x0).
fn k_dx(k: &[Vec<f64>], x0: &[f64], x1: &[f64]) -> Vec<f64> {
    k.iter().map(|row| row.iter().zip(x1.iter().zip(x0)).map(|(kji, (b, a))| kji * (b - a)).sum()).collect()
}

fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(u, v)| u - v).collect()
}

fn scale_of(points: &[Point]) -> f64 {
    points.iter().flat_map(|p| p.x.iter().chain(&p.w).chain(&p.mu)).fold(1.0f64, |m, v| m.max(v.abs()))
}

/// (X, γ_k) of the (+) equations: q_{k+1} relative to g_k, γ_k = g_{k+1} − g_k − K(x_{k+1} − x_k).
fn step_plus(k: &[Vec<f64>], a: &Point, b: &Point) -> (ReducedStepPlus, Vec<f64>) {
    let rel = sub(&b.g, &a.g);
    let gamma = sub(&rel, &k_dx(k, &a.x, &b.x));
    let step = ReducedStepPlus {
        x0: a.x.clone(),
        w0: a.w.clone(),
        mu0: a.mu.clone(),
        q1: SplitVector::new(b.x.clone(), rel),
        w1: b.w.clone(),
        mu1: b.mu.clone(),
    };
    (step, gamma)
}

/// (X, γ_k) of the (−) equations: q_k relative to g_{k+1}, γ_k = g_k − g_{k+1} + K(x_{k+1} − x_k).
fn step_minus(k: &[Vec<f64>], a: &Point, b: &Point) -> (ReducedStepMinus, Vec<f64>) {
    let rel = sub(&a.g, &b.g);
    let gamma: Vec<f64> = rel.iter().zip(k_dx(k, &a.x, &b.x)).map(|(r, d)| r + d).collect();
    let step = ReducedStepMinus {
        q0: SplitVector::new(a.x.clone(), rel),
        w0: a.w.clone(),
        mu0: a.mu.clone(),
        x1: b.x.clone(),
        w1: b.w.clone(),
        mu1: b.mu.clone(),
    };
    (step, gamma)
}

/// Checks every step of a (+) run: membership in [D̂^{d+}] and eq:geometricequations.
fn check_plus<S: System<4>>(reduction: &ReducedLagrangian<S>, k: &[Vec<f64>], points: &[Point]) -> (f64, f64) {
    let scale = scale_of(points);
    let (mut dirac, mut general) = (0.0f64, 0.0f64);
    for pair in points.windows(2) {
        let (step, gamma) = step_plus(k, &pair[0], &pair[1]);
        dirac = dirac.max(dirac_residual_plus(reduction, &step, &pair[1].x, &gamma).unwrap() / scale);
        general = general.max(general_form_plus(reduction, &step, &pair[1].x, &gamma).unwrap().max_abs() / scale);
    }
    (dirac, general)
}

/// Checks every step of a (−) run: membership in [D̂^{d−}], the corrected general form, and the
/// smallest residual of the printed general form over all steps relative to that step's momenta.
fn check_minus<S: System<4>>(reduction: &ReducedLagrangian<S>, k: &[Vec<f64>], points: &[Point]) -> (f64, f64, f64) {
    let scale = scale_of(points);
    let (mut dirac, mut corrected, mut printed_min) = (0.0f64, 0.0f64, f64::INFINITY);
    for pair in points.windows(2) {
        let (step, gamma) = step_minus(k, &pair[0], &pair[1]);
        dirac = dirac.max(dirac_residual_minus(reduction, &step, &pair[0].x, &gamma).unwrap() / scale);
        let form = |signs| general_form_minus(reduction, &step, &pair[0].x, &gamma, signs).unwrap().max_abs() / scale;
        corrected = corrected.max(form(Signs::Corrected));
        let momenta = pair.iter().flat_map(|p| p.w.iter().chain(&p.mu)).fold(0.0f64, |m, v| m.max(v.abs()));
        printed_min = printed_min.min(form(Signs::AsPrinted) * scale / momenta);
    }
    (dirac, corrected, printed_min)
}

const TOLERANCE: f64 = 1e-10;

#[test]
fn charged_particle_plus_run_lies_in_the_reduced_dirac_structure() {
    let system = ChargedParticle::default();
    let k = vec![vec![0.0; 3]];
    let points = reduced_run(&system, &ChargedParticle::paper_problem(100), Rule::Left, Variant::Plus, &k);
    let reduction = ReducedLagrangian::new(&system, Rule::Left, 0.2, Connection::new(&k).unwrap()).unwrap();
    let (dirac, general) = check_plus(&reduction, &k, &points);
    eprintln!("charged particle (+): Dirac residual {dirac:.2e}, general form {general:.2e}");
    assert!(dirac < TOLERANCE && general < TOLERANCE);
}

#[test]
fn charged_particle_minus_run_satisfies_the_corrected_equations_only() {
    let system = ChargedParticle::default();
    let k = vec![vec![0.0; 3]];
    let points = reduced_run(&system, &ChargedParticle::paper_problem(100), Rule::Left, Variant::Minus, &k);
    let reduction = ReducedLagrangian::new(&system, Rule::Left, 0.2, Connection::new(&k).unwrap()).unwrap();
    let (dirac, corrected, printed) = check_minus(&reduction, &k, &points);
    eprintln!("charged particle (−): Dirac {dirac:.2e}, corrected {corrected:.2e}, printed (min) {printed:.2e}");
    assert!(dirac < TOLERANCE && corrected < TOLERANCE);
    assert!(printed > 0.5, "the printed eq:geometricequationsminus must fail on every step");
}

fn two_body_problem() -> Problem {
    Problem::new(0.01, 500, vec![0.0, 0.0, 1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.0, 0.0, 1.1]))
}

#[test]
fn two_body_plus_run_with_centre_of_mass_connection() {
    let system = TwoBody::default();
    let k = system.centre_of_mass_connection().unwrap().rows();
    let points = reduced_run(&system, &two_body_problem(), Rule::Midpoint, Variant::Plus, &k);
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.01, Connection::new(&k).unwrap()).unwrap();
    let (dirac, general) = check_plus(&reduction, &k, &points);
    eprintln!("two bodies (+): Dirac residual {dirac:.2e}, general form {general:.2e}");
    assert!(dirac < TOLERANCE && general < TOLERANCE);
    // The run is not trivial: the relative position sweeps a large part of the ellipse.
    let r_min = points.iter().map(|p| p.x[0].hypot(p.x[1])).fold(f64::INFINITY, f64::min);
    assert!(r_min < 0.5, "pericentre {r_min}");
}

#[test]
fn two_body_minus_run_satisfies_the_corrected_equations_only() {
    let system = TwoBody::default();
    let k = system.centre_of_mass_connection().unwrap().rows();
    let points = reduced_run(&system, &two_body_problem(), Rule::Midpoint, Variant::Minus, &k);
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.01, Connection::new(&k).unwrap()).unwrap();
    let (dirac, corrected, printed) = check_minus(&reduction, &k, &points);
    eprintln!("two bodies (−): Dirac {dirac:.2e}, corrected {corrected:.2e}, printed (min) {printed:.2e}");
    assert!(dirac < TOLERANCE && corrected < TOLERANCE);
    assert!(printed > 0.5, "the printed eq:geometricequationsminus must fail on every step");
}

fn two_body_reduction<'a>(system: &'a TwoBody, k: &[Vec<f64>]) -> ReducedLagrangian<&'a TwoBody> {
    ReducedLagrangian::new(system, Rule::Trapezoid, 0.1, Connection::new(k).unwrap()).unwrap()
}

fn assert_close(a: &SplitVector, b: &SplitVector, tol: f64) {
    let all = |v: &SplitVector| v.x.iter().chain(&v.g).copied().collect::<Vec<f64>>();
    for (u, v) in all(a).iter().zip(all(b)) {
        assert!((u - v).abs() <= tol * (1.0 + u.abs()), "{a:?} vs {b:?}");
    }
}

/// Lemmas partialderivativesld and partialderivativesldminus: D_i L_d from the partials of l± (with
/// the connection maps as printed) equals D_i L_d by AD, for a connection that is not diagonal.
#[test]
fn lemmas_on_partial_derivatives_hold_for_a_general_connection() {
    let system = TwoBody::default();
    let k = vec![vec![-0.4, 0.3], vec![0.2, -0.7]];
    let reduction = two_body_reduction(&system, &k);
    let mut u = sampler(7);
    for _ in 0..20 {
        let x0 = vec![1.0 + 0.3 * u(), 0.2 * u()];
        let x1 = vec![1.0 + 0.3 * u(), 0.2 * u()];
        let g = vec![0.5 * u(), 0.5 * u()];
        let (d1, d2) = ld_partials_from_plus(&reduction, &x0, &x1, &g).unwrap();
        let q1g: Vec<f64> = g.iter().zip(k_dx(&k, &x0, &x1)).map(|(a, b)| a + b).collect();
        let (e1, e2) =
            ld_partials(&reduction, &SplitVector::new(x0.clone(), vec![0.0; 2]), &SplitVector::new(x1.clone(), q1g))
                .unwrap();
        assert_close(&d1, &e1, 1e-12);
        assert_close(&d2, &e2, 1e-12);

        let (d1, d2) = ld_partials_from_minus(&reduction, &x0, &g, &x1).unwrap();
        let q0g: Vec<f64> = g.iter().zip(k_dx(&k, &x1, &x0)).map(|(a, b)| a + b).collect();
        let (e1, e2) =
            ld_partials(&reduction, &SplitVector::new(x0.clone(), q0g), &SplitVector::new(x1, vec![0.0; 2])).unwrap();
        assert_close(&d1, &e1, 1e-12);
        assert_close(&d2, &e2, 1e-12);
    }
}

/// l₊ and l₋ are L_d read through λ_d and λ̃_d: L_d(q0, q1) = l₊(x0, x1, ω_d(q0, q1)) =
/// l₋(x0, ω_d(q1, q0), x1) for any g0, g1 (eq:reducedlagrangianlocal and …minus with invariance).
#[test]
fn reduced_lagrangians_are_l_d_in_trivialized_coordinates() {
    let system = TwoBody::default();
    let k = vec![vec![-0.4, 0.3], vec![0.2, -0.7]];
    let reduction = two_body_reduction(&system, &k);
    let mut u = sampler(11);
    for _ in 0..20 {
        let q0 = [u(), u(), 1.0 + 0.3 * u(), 0.2 * u()];
        let q1 = [u(), u(), 1.0 + 0.3 * u(), 0.2 * u()];
        let (x0, x1, g0, g1) = (&q0[2..], &q1[2..], &q0[..2], &q1[..2]);
        let value = reduction.ld.value(&q0, &q1);
        let omega = sub(&sub(g1, g0), &k_dx(&k, x0, x1));
        let omega_minus = sub(&sub(g0, g1), &k_dx(&k, x1, x0));
        let plus = reduction.lagrangian_plus(x0, x1, &omega).unwrap();
        let minus = reduction.lagrangian_minus(x0, &omega_minus, x1).unwrap();
        assert!((plus - value).abs() < 1e-12 * value.abs() && (minus - value).abs() < 1e-12 * value.abs());
    }
}

/// eq:geometricequations in general form agrees with the simplified form of the notes
/// (w_k = −∂l₊/∂x0, μ_k = μ_{k+1} = ∂l₊/∂γ, w_{k+1} = ∂l₊/∂x1) for a general K; the corrected (−)
/// form agrees with w_k = −∂l₋/∂x0, μ_k = μ_{k+1} = −∂l₋/∂γ, w_{k+1} = ∂l₋/∂x1.
#[test]
fn general_forms_agree_with_the_simplified_equations() {
    let system = TwoBody::default();
    let k = vec![vec![-0.4, 0.3], vec![0.2, -0.7]];
    let reduction = two_body_reduction(&system, &k);
    let mut u = sampler(3);
    for _ in 0..20 {
        let (x0, x1, gamma) = (vec![1.0 + 0.3 * u(), 0.2 * u()], vec![1.0 + 0.3 * u(), 0.2 * u()], vec![u(), u()]);
        let neg = |v: &[f64]| v.iter().map(|a| -a).collect::<Vec<f64>>();

        let l = partials_plus(&reduction, &x0, &x1, &gamma).unwrap();
        let g1: Vec<f64> = gamma.iter().zip(k_dx(&k, &x0, &x1)).map(|(a, b)| a + b).collect();
        let step = ReducedStepPlus {
            x0: x0.clone(),
            w0: neg(&l.x0),
            mu0: l.gamma.clone(),
            q1: SplitVector::new(x1.clone(), g1),
            w1: l.x1.clone(),
            mu1: l.gamma.clone(),
        };
        let scale = 1.0 + l.x0.iter().chain(&l.x1).chain(&l.gamma).fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(general_form_plus(&reduction, &step, &x1, &gamma).unwrap().max_abs() < 1e-13 * scale);
        assert!(dirac_residual_plus(&reduction, &step, &x1, &gamma).unwrap() < 1e-13 * scale);
        let mut wrong = step.clone();
        wrong.w0[0] += 1e-3;
        assert!(general_form_plus(&reduction, &wrong, &x1, &gamma).unwrap().max_abs() > 0.9e-3);

        let l = partials_minus(&reduction, &x0, &gamma, &x1).unwrap();
        let rel: Vec<f64> = gamma.iter().zip(k_dx(&k, &x0, &x1)).map(|(a, b)| a - b).collect();
        let step = ReducedStepMinus {
            q0: SplitVector::new(x0.clone(), rel),
            w0: neg(&l.x0),
            mu0: neg(&l.gamma),
            x1: x1.clone(),
            w1: l.x1.clone(),
            mu1: neg(&l.gamma),
        };
        let scale = 1.0 + l.x0.iter().chain(&l.x1).chain(&l.gamma).fold(0.0f64, |m, v| m.max(v.abs()));
        let form = |signs| general_form_minus(&reduction, &step, &x0, &gamma, signs).unwrap().max_abs();
        assert!(form(Signs::Corrected) < 1e-13 * scale);
        assert!(dirac_residual_minus(&reduction, &step, &x0, &gamma).unwrap() < 1e-13 * scale);
        assert!(form(Signs::AsPrinted) > 1e-3);
    }
}

#[test]
fn mismatched_connection_is_refused() {
    let system = TwoBody::default();
    let result = ReducedLagrangian::new(&system, Rule::Midpoint, 0.1, Connection::zero(3, 1));
    assert!(matches!(result, Err(ddirac::Error::Invalid { .. })));
}

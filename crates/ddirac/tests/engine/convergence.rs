//! Observed order of accuracy: the error ‖q(T) − q_N‖ against an exact solution, for N doubling
//! from 100 to 1600, fitted by least squares on a log–log scale. The midpoint and trapezoid
//! discrete Lagrangians are second order; so is the left rule on the charged particle (paper
//! Table 1: halving h quarters the error). Reduced and unreduced runs must show the same order.
//!
//! On the charged particle the three rules give the same trajectory: A is linear and
//! A(Δq)·Δq = 0, so A(q̄)·Δq = A(q0)·Δq = A(q1)·Δq and the rules only differ in where they evaluate
//! a term that does not depend on it. The polar oscillator separates them: the midpoint and
//! trapezoid rules are of order 2 there and the left rule of order 1, which also shows the fitted
//! slope can tell the orders apart.

use crate::common;

use common::{log_log_slope, method, run};
use ddirac::systems::ChargedParticle;
use ddirac::{Coordinate, InitialMomentum, Problem, Rule, System, Variant};
use num_dual::DualNum;

const STEPS: [usize; 5] = [100, 200, 400, 800, 1600];
const T: f64 = 20.0;

/// The isotropic harmonic oscillator in the plane, in polar coordinates (r, φ) with φ a group
/// angle: L = ½ (ṙ² + r² φ̇²) − ½ ω² r².
struct PolarOscillator {
    omega: f64,
}

impl System<2> for PolarOscillator {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("r"), Coordinate::group("phi").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        let r = q[0];
        (v[0] * v[0] + r * r * v[1] * v[1] - r * r * (self.omega * self.omega)) * 0.5
    }

    /// In Cartesian coordinates X(t) = X0 cos ωt + (V0/ω) sin ωt, an ellipse centred at the origin.
    /// Every half period X is exactly −X at the previous half period, so φ advances by ±π (the sign
    /// of the angular momentum p_φ); the rest, less than half a turn, comes from atan2.
    fn exact_solution(&self, q0: &[f64; 2], p0: &[f64; 2], t: f64) -> Option<[Option<f64>; 2]> {
        let (r0, phi0, w) = (q0[0], q0[1], self.omega);
        let (vr, vphi) = (p0[0], p0[1] / (r0 * r0));
        let (c0, s0) = (phi0.cos(), phi0.sin());
        let x0 = [r0 * c0, r0 * s0];
        let v0 = [vr * c0 - r0 * vphi * s0, vr * s0 + r0 * vphi * c0];
        let half = std::f64::consts::PI / w;
        let turns = (t / half).floor();
        let rest = t - turns * half;
        let sign = if turns as i64 % 2 == 0 { 1.0 } else { -1.0 };
        let start = [sign * x0[0], sign * x0[1]];
        let (c, s) = ((w * rest).cos(), (w * rest).sin());
        let end = [start[0] * c + sign * v0[0] / w * s, start[1] * c + sign * v0[1] / w * s];
        let swept = (start[0] * end[1] - start[1] * end[0]).atan2(start[0] * end[0] + start[1] * end[1]);
        let phi = phi0 + turns * std::f64::consts::PI * p0[1].signum() + swept;
        Some([Some(end[0].hypot(end[1])), Some(phi)])
    }
}

/// Errors for each N of [`STEPS`], and the fitted slope.
fn order<S: System<N>, const N: usize>(
    system: &S,
    problem: impl Fn(usize) -> Problem,
    rule: Rule,
    reduced: bool,
    all_steps: &[usize],
) -> (Vec<f64>, f64) {
    let (mut h, mut err) = (vec![], vec![]);
    for &steps in all_steps {
        let problem = problem(steps);
        let solution = run(system, &problem, &method(rule, Variant::Plus, reduced, None));
        h.push(problem.step);
        err.push(solution.summary.reference_error.expect("exact solution"));
    }
    let slope = log_log_slope(&h, &err);
    (err, slope)
}

fn scientific(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|v| format!("{v:.4e}")).collect();
    format!("[{}]", parts.join(", "))
}

fn assert_order_two<S: System<N>, const N: usize>(
    name: &str,
    system: &S,
    problem: impl Fn(usize) -> Problem,
    rule: Rule,
) {
    for reduced in [false, true] {
        let (err, slope) = order(system, &problem, rule, reduced, &STEPS);
        let ratios: Vec<String> = err.windows(2).map(|e| format!("{:.3}", e[0] / e[1])).collect();
        eprintln!(
            "{name}, {} rule, reduced = {reduced}: errors {}, ratios [{}], slope {slope:.4}",
            rule.name(),
            scientific(&err),
            ratios.join(", ")
        );
        assert!((slope - 2.0).abs() <= 0.1, "{name}, {rule:?}, reduced = {reduced}: slope {slope}");
    }
}

#[test]
fn charged_particle_midpoint_is_second_order() {
    assert_order_two("charged particle", &ChargedParticle::default(), ChargedParticle::paper_problem, Rule::Midpoint);
}

#[test]
fn charged_particle_left_is_second_order() {
    assert_order_two("charged particle", &ChargedParticle::default(), ChargedParticle::paper_problem, Rule::Left);
}

#[test]
fn charged_particle_trapezoid_is_second_order() {
    assert_order_two("charged particle", &ChargedParticle::default(), ChargedParticle::paper_problem, Rule::Trapezoid);
}

/// The circular orbit r = 1, φ = ωt (p_φ = ω) is a relative equilibrium that the midpoint L_d
/// reproduces exactly: with r0 = r1 = 1 and Δφ = ωh both discrete momentum equations hold
/// (p_r = h·r̄·(φ̇² − ω²)/2 = 0, p_φ = r̄² φ̇ = ω). So it shows no error to converge: every N must give
/// round-off only.
#[test]
fn polar_oscillator_circular_orbit_is_exact_for_midpoint() {
    let system = PolarOscillator { omega: 1.3 };
    let exact = system.exact_solution(&[1.0, 0.0], &[0.0, 1.3], T).unwrap();
    assert!((exact[0].unwrap() - 1.0).abs() < 1e-12 && (exact[1].unwrap() - 1.3 * T).abs() < 1e-12);
    for reduced in [false, true] {
        for steps in STEPS {
            let problem =
                Problem::new(T / steps as f64, steps, vec![1.0, 0.0], InitialMomentum::Momentum(vec![0.0, 1.3]));
            let solution = run(&system, &problem, &method(Rule::Midpoint, Variant::Plus, reduced, None));
            let error = solution.summary.reference_error.unwrap();
            eprintln!("polar oscillator, circular, N = {steps}, reduced = {reduced}: ‖q(T) − q_N‖ = {error:.3e}");
            assert!(error <= 1e-12, "N = {steps}, reduced = {reduced}: error {error:e}");
        }
    }
}

/// An eccentric orbit (r0 = 1, φ0 = 0.5, ṙ0 = 0.4, φ̇0 = 0.6 ω, ω = 1.3): r oscillates between
/// about 0.56 and 1.06 and φ makes four turns over T = 20.
#[test]
fn polar_oscillator_midpoint_is_second_order() {
    let system = PolarOscillator { omega: 1.3 };
    let eccentric =
        |steps| Problem::new(T / steps as f64, steps, vec![1.0, 0.5], InitialMomentum::Velocity(vec![0.4, 0.78]));
    assert_order_two("polar oscillator, eccentric", &system, eccentric, Rule::Midpoint);
    assert_order_two("polar oscillator, eccentric", &system, eccentric, Rule::Trapezoid);
}

/// The left rectangle rule is only first order in general (its truncation error is not symmetric in
/// time). The first-order term dominates only for small steps (over N = 100 … 1600 the fitted slope
/// is about 1.4), hence the finer steps here.
#[test]
fn polar_oscillator_left_is_first_order() {
    let system = PolarOscillator { omega: 1.3 };
    let eccentric =
        |steps| Problem::new(T / steps as f64, steps, vec![1.0, 0.5], InitialMomentum::Velocity(vec![0.4, 0.78]));
    for reduced in [false, true] {
        let (err, slope) = order(&system, eccentric, Rule::Left, reduced, &[3200, 6400, 12800, 25600]);
        eprintln!(
            "polar oscillator, eccentric, left rule, reduced = {reduced}: errors {}, slope {slope:.4}",
            scientific(&err)
        );
        assert!((slope - 1.0).abs() <= 0.1, "reduced = {reduced}: slope {slope}");
    }
}

//! Newton's residual test had an absolute floor: a step was accepted when ‖r‖∞ ≤ 10⁻¹² · max(‖p‖∞, 1).
//! A system whose momenta and Jacobian are tiny in its units — an electron's mass in SI units,
//! 9.1·10⁻³¹ kg — has every residual below 10⁻¹², so the predictor was accepted without a single
//! correction: an oscillator released at rest stayed at rest, exit status 0, no warning. The floor
//! now follows the Jacobian's scale where that is below 1 (`NewtonOptions::threshold_at`).

use ddirac::num_dual::DualNum;
use ddirac::{solve, Coordinate, Method, OutputOptions, Problem, Rule, System};

/// A harmonic oscillator of mass `m` and angular frequency ω: L = ½ m (v² − ω² x²).
struct Oscillator {
    m: f64,
    omega: f64,
}

impl System<1> for Oscillator {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("x")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        (v[0] * v[0] - q[0] * q[0] * self.omega.powi(2)) * (0.5 * self.m)
    }
}

#[test]
fn an_oscillator_with_an_electrons_mass_moves_as_the_midpoint_rule_says() {
    let (h, steps, omega) = (0.01, 500, 3.0);
    for m in [1.0, 9.109e-31, 1e-40] {
        let system = Oscillator { m, omega };
        let problem = Problem::with_momentum(h, steps, [1.0], [0.0]);
        let method = Method { rule: Rule::Midpoint, ..Method::default() };
        let solution = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
        // The midpoint rule turns (x, p/(mω)) by 2 atan(ωh/2) per step: x_k = cos(2k atan(ωh/2)).
        let x = solution.summary.final_q[0];
        let discrete = (2.0 * steps as f64 * (omega * h / 2.0).atan()).cos();
        assert!((x - discrete).abs() < 1e-10, "m = {m:e}: x = {x} against {discrete}");
        let p = solution.summary.final_p[0] / m;
        let discrete_p = -omega * (2.0 * steps as f64 * (omega * h / 2.0).atan()).sin();
        assert!((p - discrete_p).abs() < 1e-9, "m = {m:e}: p/m = {p} against {discrete_p}");
    }
}

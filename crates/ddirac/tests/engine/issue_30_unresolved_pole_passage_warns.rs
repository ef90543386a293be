//! The spherical pendulum in its main chart alone (`atlas = false`) with L_z = 1e-6 swings through
//! the pole of its chart at every half period. The flow turns the azimuth by π within a time far
//! shorter than any step; the steps turned it by about 0.14 rad, under the fixed limit of a radian
//! per step, while the energy moved by 3e-4 per step, under its threshold: the bob ended 0.05–0.10
//! off for h = 0.02 … 0.002, without a warning. The chart watch now judges an angle's advance by what
//! the step resolves: a kick far above the angle's typical advance whose rate changes by its own
//! size within one step.
//!
//! The reference is independent of the engine: with L_z → 0 the motion is the planar pendulum
//! ϑ'' = −(g/l) sin ϑ from ϑ = 1 at rest, integrated here by classical Runge–Kutta with a tiny step.

use ddirac::systems::SphericalPendulum;
use ddirac::{solve, InitialMomentum, Method, OutputOptions, Problem, Solution, WarningKind};

const T: f64 = 10.0;

/// ϑ(T) of the planar pendulum (g = 9.8, l = 1) from ϑ = 1 at rest.
fn planar_reference() -> f64 {
    let f = |y: [f64; 2]| [y[1], -9.8 * y[0].sin()];
    let (mut y, n) = ([1.0f64, 0.0f64], 200_000);
    let h = T / n as f64;
    for _ in 0..n {
        let k1 = f(y);
        let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        for i in 0..2 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    y[0]
}

fn run(h: f64, atlas: bool) -> Solution {
    let steps = (T / h).round() as usize;
    let q0 = vec![0.0, std::f64::consts::PI - 1.0];
    let problem = Problem::new(h, steps, q0, InitialMomentum::Momentum(vec![1e-6, 0.0]));
    let method = Method { reduced: true, atlas, ..Method::default() };
    let output = OutputOptions { every: steps, ..Default::default() };
    solve(&SphericalPendulum::default(), &problem, &method, &output).expect("the run completes")
}

/// The distance of the final bob from the planar pendulum's (in the plane of the azimuth 0).
fn bob_error(solution: &Solution, reference: f64) -> f64 {
    let q = solution.q.last().unwrap();
    let bob = SphericalPendulum::default().unit_position(&[q[0], q[1]]);
    let expected = [reference.sin(), 0.0, -reference.cos()];
    bob.iter().zip(expected).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
}

#[test]
fn an_unresolved_pole_passage_in_the_main_chart_is_reported() {
    let reference = planar_reference();
    for h in [0.02, 0.01, 0.005, 0.002] {
        let solution = run(h, false);
        let error = bob_error(&solution, reference);
        let warned = solution
            .summary
            .warnings
            .iter()
            .find(|w| matches!(w.kind, WarningKind::SingularChart | WarningKind::UnderResolved));
        // A bob 1e-2 off on a unit sphere is not a second-order error at these steps (the atlas
        // run below is within 1e-3).
        assert!(error < 1e-2 || warned.is_some(), "h = {h}: bob {error:.3} off, no warning");
        if let Some(warning) = warned {
            assert!(warning.message.contains("`theta`"), "{}", warning.message);
        }
    }
}

#[test]
fn the_same_passages_through_the_atlas_are_right_and_quiet() {
    let reference = planar_reference();
    for h in [0.01, 0.005] {
        let solution = run(h, true);
        let error = bob_error(&solution, reference);
        assert!(error < 1e-3 * (h / 0.005f64).powi(2), "h = {h}: bob {error:.2e} off");
        assert!(solution.summary.warnings.is_empty(), "h = {h}: {:?}", solution.summary.warnings);
    }
}

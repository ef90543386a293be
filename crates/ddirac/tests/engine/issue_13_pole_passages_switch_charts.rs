//! Issue 13, finding 2: a spherical pendulum passing near its pole with a small azimuthal momentum
//! ended with the bob at the antipodal point and energy errors up to 169 %, exit code 0. With the
//! built-in atlas the run leaves the polar chart near the pole, and its error is that of a run far
//! from the pole, second order, against an independent reference without chart singularity (the
//! pendulum in Cartesian coordinates with its constraint, by a fine Runge–Kutta method).

use std::f64::consts::PI;

use ddirac::systems::SphericalPendulum;
use ddirac::{InitialMomentum, Method, Problem, Stepper};

const G: f64 = 9.8;

/// The bob's position at time `t` from (θ, φ) = q0 with p = (l_z, 0), by classical Runge–Kutta on
/// r̈ = −g e_z + λ r, λ = g r_z − |ṙ|² (unit sphere, unit mass), with 2·10⁵ steps per unit time.
fn reference(q0: [f64; 2], l_z: f64, t: f64) -> [f64; 3] {
    let (s, c) = q0[1].sin_cos();
    let theta_dot = l_z / (s * s);
    let r = [s * q0[0].cos(), s * q0[0].sin(), c];
    let v = [-s * q0[0].sin() * theta_dot, s * q0[0].cos() * theta_dot, 0.0];
    let field = |y: &[f64; 6]| -> [f64; 6] {
        let (r, v) = ([y[0], y[1], y[2]], [y[3], y[4], y[5]]);
        let lambda = G * r[2] - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        [v[0], v[1], v[2], lambda * r[0], lambda * r[1], lambda * r[2] - G]
    };
    let mut y = [r[0], r[1], r[2], v[0], v[1], v[2]];
    let steps = (t * 2e5).round() as usize;
    let h = t / steps as f64;
    let add = |y: &[f64; 6], k: &[f64; 6], a: f64| -> [f64; 6] { std::array::from_fn(|i| y[i] + a * k[i]) };
    for _ in 0..steps {
        let k1 = field(&y);
        let k2 = field(&add(&y, &k1, h / 2.0));
        let k3 = field(&add(&y, &k2, h / 2.0));
        let k4 = field(&add(&y, &k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    [y[0], y[1], y[2]]
}

struct Outcome {
    error: f64,
    energy: f64,
    momentum: f64,
    switches: usize,
}

fn run(l_z: f64, h: f64, reduced: bool, atlas: bool) -> Outcome {
    let system = SphericalPendulum::default();
    let q0 = [0.3, PI - 1.0];
    let steps = (10.0 / h).round() as usize;
    let problem = Problem::new(h, steps, q0.to_vec(), InitialMomentum::Momentum(vec![l_z, 0.0]));
    let method = Method { reduced, atlas, ..Method::default() };
    let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
    let h0 = stepper.row().energy;
    let mut energy = 0.0f64;
    let mut momentum = 0.0f64;
    while !stepper.is_finished() {
        stepper.step().unwrap();
        let row = stepper.row();
        energy = energy.max(((row.energy - h0) / h0).abs());
        momentum = momentum.max((row.p[0] - l_z).abs());
    }
    let summary = stepper.finish().unwrap();
    let q: [f64; 2] = summary.final_q.clone().try_into().unwrap();
    let r = system.unit_position(&q);
    let exact = reference(q0, l_z, 10.0);
    let error = (0..3).map(|i| (r[i] - exact[i]).powi(2)).sum::<f64>().sqrt();
    Outcome { error, energy, momentum, switches: summary.chart_switches }
}

/// The cases: L_z from 10⁻⁶ to 10⁻¹, h = 0.01 and 0.0025, reduced and unreduced.
#[test]
fn pole_passages_are_as_accurate_as_runs_far_from_the_pole() {
    // A run that stays far from the pole (L_z = 1, the polar chart throughout) sets the scale.
    let far = run(1.0, 0.01, true, false);
    eprintln!("far from the pole, h = 0.01: error {:.3e}, energy {:.3e}", far.error, far.energy);
    for l_z in [1e-6, 1e-4, 1e-2, 1e-1] {
        for reduced in [false, true] {
            let (coarse, fine) = (run(l_z, 0.01, reduced, true), run(l_z, 0.0025, reduced, true));
            let order = (coarse.error / fine.error).log2() / 2.0;
            eprintln!(
                "L_z = {l_z:e}, reduced {reduced}: error {:.3e} (h = 0.01), {:.3e} (h = 0.0025), order {order:.3}; \
                 energy {:.2e}; momentum map {:.1e}; {} switches",
                coarse.error, fine.error, coarse.energy, coarse.momentum, coarse.switches
            );
            assert!(
                coarse.error <= far.error,
                "L_z = {l_z:e}: error {:e} against {:e} far from the pole",
                coarse.error,
                far.error
            );
            assert!((order - 2.0).abs() < 0.1, "L_z = {l_z:e}: order {order}");
            assert!(coarse.energy <= far.energy, "L_z = {l_z:e}: energy {:e} against {:e}", coarse.energy, far.energy);
            assert!(fine.energy <= far.energy / 10.0, "L_z = {l_z:e}: energy {:e} at h = 0.0025", fine.energy);
            // In the polar caps the steps are unreduced; the momentum map is conserved by the discrete
            // Noether theorem, to the Newton tolerance.
            assert!(coarse.momentum.max(fine.momentum) < 5e-12, "L_z = {l_z:e}: momentum map {:e}", coarse.momentum);
            assert!(coarse.switches >= 1);
        }
    }
}

/// The same runs in the polar chart alone (`atlas = false`) are what the issue found: wrong by up to
/// the size of the sphere.
#[test]
fn without_the_atlas_the_polar_chart_alone_is_wrong_near_the_pole() {
    let polar = run(1e-2, 0.01, true, false);
    assert!(polar.error > 0.5 && polar.switches == 0, "error {:e}", polar.error);
}

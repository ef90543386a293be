//! The hand-written baselines against independent numbers: the specialised reduced (+) left step
//! against the generic engine and the paper's Table 1, the Boris pusher against the exact helix.

use ddirac::baselines::boris::Boris;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::{ChargedParticle, TABLE_1};
use ddirac::{solve, Method, OutputOptions, Rule, Variant};

/// The paper's exact motion (§7.1, m = e = B0 = 1, q0 = 0, q̇0 = (1, 0, 1)): (sin t, cos t − 1, t).
fn exact(t: f64) -> [f64; 3] {
    [t.sin(), t.cos() - 1.0, t]
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// The paper's initial data in reduced coordinates: q0 = 0, θ0 = 0, w0 = (1, 0, 1), μ0 = 1.
const START: ReducedState = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };

fn paper_stepper(steps: usize) -> ChargedParticleStep {
    ChargedParticleStep { m: 1.0, b0: 1.0, h: 20.0 / steps as f64 }
}

#[test]
fn the_specialised_step_reproduces_the_engine_at_every_step() {
    let steps = 100;
    let method = Method { rule: Rule::Left, variant: Variant::Plus, reduced: true, ..Method::default() };
    let engine =
        solve(&ChargedParticle::default(), &ChargedParticle::paper_problem(steps), &method, &OutputOptions::default())
            .expect("the paper problem runs");
    assert_eq!(engine.q.len(), steps + 1);
    let stepper = paper_stepper(steps);
    let mut state = START;
    let (mut worst_q, mut worst_theta, mut worst_w) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..=steps {
        let (q, p) = (&engine.q[k], &engine.p[k]);
        for i in 0..3 {
            worst_q = worst_q.max((q[i] - state.q[i]).abs());
            // K = 0: w = p_q.
            worst_w = worst_w.max((p[i] - state.w[i]).abs());
        }
        worst_theta = worst_theta.max((q[3] - state.theta).abs());
        assert_eq!(p[3], state.mu, "μ is conserved exactly by both at step {k}");
        state = stepper.step(&state);
    }
    eprintln!("largest differences over 100 steps: q {worst_q:.1e}, θ {worst_theta:.1e}, w {worst_w:.1e}");
    assert!(worst_q <= 1e-12, "q differs by {worst_q:e}");
    assert!(worst_theta <= 1e-12, "θ differs by {worst_theta:e}");
    assert!(worst_w <= 1e-12, "w differs by {worst_w:e}");
    // θ advances by h μ − ⟨A(q_k), Δ⟩ each step: about T = 20 in all, so the comparison is not trivial.
    assert!(state.theta > 15.0, "θ_N = {}", state.theta);
}

#[test]
fn the_specialised_step_reproduces_table_1() {
    // Paper Table 1, to half a unit of the last printed digit.
    let tolerances = [5e-5, 5e-6, 5e-6, 5e-6];
    for ((steps, printed), tolerance) in TABLE_1.into_iter().zip(tolerances) {
        let end = paper_stepper(steps).run(START, steps);
        let error = distance(&end.q, &exact(20.0));
        eprintln!("N = {steps}: ‖q(T) − q_N‖ = {error:.6} (paper {printed})");
        assert!((error - printed).abs() <= tolerance, "N = {steps}: {error} vs {printed}");
    }
}

const PARTICLE: Boris = Boris { e: 1.0, m: 1.0, b0: 1.0 };

#[test]
fn the_boris_pusher_is_second_order() {
    let errors: Vec<(f64, f64)> = [100usize, 200, 400, 800, 1600]
        .iter()
        .map(|&steps| {
            let h = 20.0 / steps as f64;
            let end = PARTICLE.run(h, steps, [0.0; 3], [1.0, 0.0, 1.0]);
            (h, distance(&end.position, &exact(20.0)))
        })
        .collect();
    let slopes: Vec<f64> = errors.windows(2).map(|w| (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln()).collect();
    eprintln!("Boris (h, error) {errors:?}, slopes {slopes:?}");
    assert!(slopes.iter().all(|s| (s - 2.0).abs() < 0.1), "{slopes:?}");
    assert!(errors[0].1 > 1e-3, "the coarsest run must carry a visible error: {errors:?}");
}

#[test]
fn the_boris_pusher_keeps_the_speed_to_round_off() {
    let v0: [f64; 3] = [1.0, 0.0, 1.0];
    let speed0 = (v0[0] * v0[0] + v0[1] * v0[1] + v0[2] * v0[2]).sqrt();
    let steps = 100_000;
    // Field and charge not 1, a coarse step (rotation ≈ 0.7 rad per step).
    let particle = Boris { e: -1.5, m: 0.7, b0: 0.3 };
    let end = particle.run(1.1, steps, [0.5, -0.2, 0.1], v0);
    let v = end.velocity;
    let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let drift = (speed - speed0).abs() / speed0;
    eprintln!("relative speed drift after {steps} steps: {drift:.1e}");
    assert!(drift < 1e-12, "{drift:e}");
    assert_eq!(v[2], v0[2], "the velocity along B is untouched");
    // The velocity did rotate: it is not v0 (within the same bound).
    assert!((v[0] - v0[0]).abs() + (v[1] - v0[1]).abs() > 1e-3, "{v:?}");
}

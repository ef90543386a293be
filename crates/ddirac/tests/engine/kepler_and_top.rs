//! The Kepler problem's closed-form solution against an independent Runge–Kutta integration, the
//! integrators' order against it, and the heavy top's two momenta.

use ddirac::systems::{HeavyTop, Kepler};
use ddirac::{solve, InitialMomentum, Method, OutputOptions, Problem, Rule, System};

/// Hamilton's equations of the Kepler problem, H = p_r²/(2m) + p_φ²/(2 m r²) − k/r, by classical RK4.
fn rk4(system: &Kepler, y0: [f64; 4], t: f64, steps: usize) -> [f64; 4] {
    let (m, k) = (system.m, system.k);
    let f = |y: [f64; 4]| {
        let [r, _, pr, pphi] = y;
        [pr / m, pphi / (m * r * r), pphi * pphi / (m * r.powi(3)) - k / (r * r), 0.0]
    };
    let h = t / steps as f64;
    let mut y = y0;
    for _ in 0..steps {
        let add = |a: [f64; 4], b: [f64; 4], s: f64| std::array::from_fn::<f64, 4, _>(|i| a[i] + s * b[i]);
        let k1 = f(y);
        let k2 = f(add(y, k1, h / 2.0));
        let k3 = f(add(y, k2, h / 2.0));
        let k4 = f(add(y, k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    y
}

const Q0: [f64; 2] = [1.0, 0.3];
const P0: [f64; 2] = [0.2, 1.2]; // eccentric bound orbit (E ≈ −0.26, e ≈ 0.45)

#[test]
fn the_exact_kepler_solution_matches_runge_kutta() {
    let system = Kepler { m: 1.5, k: 2.0 };
    let mut worst = 0.0f64;
    for t in [0.3, 2.0, 7.5, 20.0] {
        let exact = system.exact_solution(&Q0, &P0, t).unwrap();
        let y = rk4(&system, [Q0[0], Q0[1], P0[0], P0[1]], t, 200_000);
        worst = worst.max((exact[0].unwrap() - y[0]).abs()).max((exact[1].unwrap() - y[1]).abs());
    }
    eprintln!("largest |exact − RK4| = {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
    // Unbound motion has no closed form here.
    assert!(system.exact_solution(&Q0, &[0.0, 5.0], 1.0).is_none());
}

#[test]
fn the_midpoint_rule_is_second_order_on_an_eccentric_orbit() {
    let system = Kepler::default();
    let method = Method { rule: Rule::Midpoint, reduced: true, ..Method::default() };
    let errors: Vec<(f64, f64)> = [400usize, 800, 1600, 3200]
        .iter()
        .map(|&steps| {
            let problem = Problem::new(10.0 / steps as f64, steps, Q0.to_vec(), InitialMomentum::Momentum(P0.to_vec()));
            let opts = OutputOptions { every: steps, wrap_angles: false };
            let s = solve(&system, &problem, &method, &opts).unwrap().summary;
            (problem.step, s.reference_error.unwrap())
        })
        .collect();
    let slopes: Vec<f64> = errors.windows(2).map(|w| (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln()).collect();
    eprintln!("errors {errors:?}, slopes {slopes:?}");
    assert!(slopes.iter().all(|s| (s - 2.0).abs() < 0.1), "{slopes:?}");
}

#[test]
fn the_heavy_top_keeps_both_momenta_and_reduced_equals_unreduced() {
    let system = HeavyTop::default();
    let steps = 20_000;
    // Fast spin: ψ̇ ≈ 30 → ψ reaches about 600 rad over T = 20.
    let problem = Problem::new(1e-3, steps, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0]));
    let opts = OutputOptions { every: 100, wrap_angles: false };
    let reduced = solve(&system, &problem, &Method { reduced: true, ..Method::default() }, &opts).unwrap();
    let unreduced = solve(&system, &problem, &Method::default(), &opts).unwrap();
    let (r, u) = (&reduced.summary, &unreduced.summary);
    eprintln!("ψ_N = {}, momentum drift reduced {:?}, unreduced {:?}", r.final_q[2], r.momentum_map, u.momentum_map);
    assert!(r.final_q[2] > 300.0, "ψ_N = {}", r.final_q[2]);
    assert!(r.momentum_map.max_relative_drift.unwrap() < 1e-12);
    let diff = r.final_q.iter().zip(&u.final_q).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!("reduced vs unreduced: {diff:.2e}");
    assert!(diff < 1e-9 * r.final_q[2], "{diff:e}");
    let spread = (r.energy.max - r.energy.min) / r.energy.initial.abs();
    eprintln!("energy spread {spread:.2e}");
    assert!(spread < 1e-3, "{spread:e}");
}

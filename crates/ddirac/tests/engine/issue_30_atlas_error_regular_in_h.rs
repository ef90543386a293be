//! With the atlas, the final error of a spherical pendulum going over the top jumped by 20× between
//! neighbouring steps (error/h² from 69 to 272 over h = 0.0102 … 0.0098, 3.9× apart), where the main
//! chart alone gave a steady 374: each chart's method conserves its own modified energy, and each
//! switch, at a point that moves with h's phase against the orbit, moved its level by O(h³). The
//! charts' discrete Lagrangians are now glued by a partition of unity ([`ddirac::blend`]) into one
//! discrete Lagrangian on Q × Q, and the atlas's error is as regular in h as one chart's.
//!
//! The reference is independent of the atlas: the main chart alone at 64 000 steps (its own error
//! there, 374 h², is 4e-5, below 0.3 % of the errors compared).

use ddirac::systems::SphericalPendulum;
use ddirac::{solve, Composition, InitialMomentum, Method, OutputOptions, Problem, Solution};

const DURATION: f64 = 20.0;

/// `steps` reduced midpoint steps composed by `composition` over T = 20 from 2 rad off the downward
/// vertical, with polar rate 4 and azimuthal rate 2.5 (over the top, 69 chart switches with the
/// atlas), asserted free of warnings.
pub(crate) fn over_the_top(steps: usize, atlas: bool, composition: Composition) -> Solution {
    let h = DURATION / steps as f64;
    let q0 = vec![0.0, std::f64::consts::PI - 2.0];
    let problem = Problem::new(h, steps, q0, InitialMomentum::Velocity(vec![2.5, -4.0]));
    let method = Method { reduced: true, atlas, composition, ..Method::default() };
    let solution =
        solve(&SphericalPendulum::default(), &problem, &method, &OutputOptions::default()).expect("the run completes");
    assert!(solution.summary.warnings.is_empty(), "{:?}", solution.summary.warnings);
    solution
}

/// The bob (a unit vector) at the last row of `solution`.
pub(crate) fn last_bob(solution: &Solution) -> [f64; 3] {
    let q = solution.q.last().expect("a last row");
    let (s, c) = q[1].sin_cos();
    [s * q[0].cos(), s * q[0].sin(), c]
}

/// The final bob of [`over_the_top`] and the chart switches.
fn final_bob(steps: usize, atlas: bool, composition: Composition) -> ([f64; 3], usize) {
    let solution = over_the_top(steps, atlas, composition);
    (last_bob(&solution), solution.summary.chart_switches)
}

pub(crate) fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
}

/// error/h^order for each number of steps.
fn scaled_errors(steps: &[usize], atlas: bool, composition: Composition, reference: &[f64; 3]) -> Vec<f64> {
    let order = composition.order() as i32;
    steps
        .iter()
        .map(|&n| {
            let (bob, switches) = final_bob(n, atlas, composition);
            assert_eq!(switches > 0, atlas, "{switches} switches");
            distance(&bob, reference) / (DURATION / n as f64).powi(order)
        })
        .collect()
}

fn spread(values: &[f64]) -> f64 {
    let (low, high) = values.iter().fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
    high / low
}

#[test]
fn the_atlas_error_over_h_squared_is_as_regular_as_one_charts() {
    let (reference, _) = final_bob(64_000, false, Composition::Basic);
    let steps: Vec<usize> = (1960..=2040).step_by(10).collect();
    let atlas = scaled_errors(&steps, true, Composition::Basic, &reference);
    let main = scaled_errors(&steps, false, Composition::Basic, &reference);
    println!("error/h², atlas:      {atlas:.1?}\nerror/h², main chart: {main:.1?}");
    // Before the charts were glued: 69 … 272 (3.9×); the main chart alone: 374 … 377 (1.01×).
    assert!(spread(&atlas) < 1.1, "atlas error/h² spread {:.2}×: {atlas:.1?}", spread(&atlas));
    assert!(spread(&main) < 1.1, "main chart error/h² spread {:.2}×: {main:.1?}", spread(&main));
    // And the atlas stays the more accurate of the two.
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    assert!(mean(&atlas) < mean(&main), "atlas {:.1} against main chart {:.1}", mean(&atlas), mean(&main));
}

/// Suzuki's order-4 composition takes sub-steps beyond the step's ends (one backwards): a step counts
/// as one chart's only if every sub-step ends where that chart alone has weight.
#[test]
fn the_atlas_error_of_a_composition_is_regular_in_h() {
    let composition = Composition::Suzuki5;
    let (reference, _) = final_bob(64_000, false, composition);
    let steps: Vec<usize> = (1960..=2040).step_by(20).collect();
    let atlas = scaled_errors(&steps, true, composition, &reference);
    let main = scaled_errors(&steps, false, composition, &reference);
    println!("error/h⁴, atlas:      {atlas:.1?}\nerror/h⁴, main chart: {main:.1?}");
    // Switched at a step (before the charts were glued): 132 … 1009 over these steps (7.6×).
    assert!(spread(&atlas) < 1.2, "atlas error/h⁴ spread {:.2}×: {atlas:.1?}", spread(&atlas));
    assert!(spread(&main) < 1.2, "main chart error/h⁴ spread {:.2}×: {main:.1?}", spread(&main));
}

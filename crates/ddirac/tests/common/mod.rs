//! Helpers shared by the integration tests: building a method, running a problem, comparing
//! trajectories. Each test binary uses a subset of them.
#![allow(dead_code)]

use ddirac::{solve, Connection, Method, OutputOptions, Problem, Rule, Solution, System, Variant};

/// A method with the default Newton options and the invariance check on, in the main chart only
/// (the paper's scheme in the paper's coordinates, without the atlas's chart switches).
pub fn method(rule: Rule, variant: Variant, reduced: bool, connection: Option<Connection>) -> Method {
    Method { rule, variant, reduced, connection, atlas: false, ..Method::default() }
}

/// Runs `problem`, keeping every row (angles unwrapped); panics with the library's message on error.
pub fn run<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: &Method) -> Solution {
    solve(system, problem, method, &OutputOptions::default()).unwrap_or_else(|e| panic!("run failed ({method:?}): {e}"))
}

/// ‖a − b‖∞.
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "vectors of different lengths");
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// ‖a‖∞.
pub fn sup_norm(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// ‖a − b‖∞ / ‖b‖∞.
pub fn relative_diff(a: &[f64], b: &[f64]) -> f64 {
    max_abs_diff(a, b) / sup_norm(b)
}

/// The largest row-wise ‖a_k − b_k‖∞ over two trajectories with the same rows.
pub fn max_row_diff(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len(), "trajectories with different numbers of rows");
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max(max_abs_diff(x, y)))
}

/// The largest row-wise ‖a_k − b_k‖∞ / max(1, ‖b_k‖∞).
pub fn max_scaled_row_diff(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len(), "trajectories with different numbers of rows");
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max(max_abs_diff(x, y) / sup_norm(y).max(1.0)))
}

/// Least-squares slope of log(err) against log(h).
pub fn log_log_slope(h: &[f64], err: &[f64]) -> f64 {
    let (x, y): (Vec<f64>, Vec<f64>) = h.iter().zip(err).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// Deterministic pseudo-random numbers in [−1, 1).
pub fn sampler(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

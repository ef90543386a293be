//! Finding: `examples/kepler.toml` reported "reference error none" although the Kepler problem has an
//! exact solution (and the built-in `kepler` computes it). The example now runs the built-in system,
//! whose summary gives the distance of the final state from the exact orbit; the `[system]` table
//! version is `examples/kepler_expression.toml`.

use std::f64::consts::PI;

use crate::common;

use common::{succeed, TempDir};

/// The exact orbit from the apocentre r0 with angular momentum ℓ (m = k = 1), at time t: (r, φ), by
/// Kepler's equation solved by bisection (independent of the library's Newton iteration).
fn exact(r0: f64, ell: f64, t: f64) -> (f64, f64) {
    let energy = ell * ell / (2.0 * r0 * r0) - 1.0 / r0;
    let a = -1.0 / (2.0 * energy);
    let e = (1.0 + 2.0 * energy * ell * ell).sqrt();
    let n = (1.0 / (a * a * a)).sqrt();
    // At the apocentre the mean anomaly is π.
    let mean = PI + n * t;
    let (mut lo, mut hi) = (mean - 2.0, mean + 2.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid - e * mid.sin() < mean {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let big_e = 0.5 * (lo + hi);
    let r = a * (1.0 - e * big_e.cos());
    // The true anomaly, continuous in 𝓔: ν = 2 atan(√((1+e)/(1−e)) tan(𝓔/2)), unwrapped by turns.
    let turns = ((big_e + PI) / (2.0 * PI)).floor();
    let half = big_e / 2.0 - turns * PI;
    let nu = 2.0 * (((1.0 + e) / (1.0 - e)).sqrt() * half.tan()).atan() + 2.0 * PI * turns;
    (r, nu - PI)
}

#[test]
fn the_kepler_example_reports_its_distance_from_the_exact_orbit() {
    let dir = TempDir::new("kepler-reference");
    let run = succeed(&common::example("kepler.toml"), &[], &dir);
    let reference = run.summary["reference_error"].as_f64().expect("a reference error, not none");
    let q = run.final_q();
    let (r, phi) = exact(1.0, 0.8, 40.0);
    let distance = ((q[0] - r).powi(2) + (q[1] - phi).powi(2)).sqrt();
    assert!(distance > 1e-6 && distance < 1e-3, "the run is {distance:e} from the exact orbit");
    // The summary's number is that (Euclidean) distance (the library's own exact solution agrees with this
    // bisection to ~1e-12).
    assert!((reference - distance).abs() <= 1e-9, "reference error {reference:e} vs {distance:e}");
}

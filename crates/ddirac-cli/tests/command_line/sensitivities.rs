//! `method.sensitivities = true`: summary.json's `sensitivity.state`, the tangent map
//! d(q_N, p_N)/d(q_0, p_0) (4 × 4 for the spherical pendulum, q then p in the spec's coordinate order),
//! held against central differences of whole runs of the command line with perturbed initial data,
//! and symplectic; absent by default; refused for a rigid body.

use crate::common;

use common::{assert_fails, numbers, run, stderr, TempDir};
use serde_json::Value;

fn summary(dir: &TempDir) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.out().join("summary.json")).unwrap()).unwrap()
}

/// (θ, φ, p_θ, p_φ) at the end of a reduced run of the example from the given initial data.
fn final_state(x: [f64; 4], extra: &[&str], dir: &TempDir) -> (Vec<f64>, Value) {
    let spec = common::example("spherical_pendulum.toml");
    let sets = [
        format!("initial.q.theta={:e}", x[0]),
        format!("initial.q.phi={:e}", x[1]),
        format!("initial.p.theta={:e}", x[2]),
        format!("initial.p.phi={:e}", x[3]),
        "time.duration=1".to_owned(),
        "method.tolerance=1e-14".to_owned(),
    ];
    let mut all: Vec<&str> = sets.iter().map(String::as_str).collect();
    all.extend(extra);
    let output = run(&spec, &all, dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let s = summary(dir);
    let state = numbers(&s["final"]["q"]).into_iter().chain(numbers(&s["final"]["p"])).collect();
    (state, s)
}

#[test]
fn the_tangent_map_equals_finite_differences_and_is_symplectic() {
    let dir = TempDir::new("sensitivities");
    let x0 = [1.0, 0.2, 0.3, 1.2];
    let (_, s) = final_state(x0, &["method.sensitivities=true"], &dir);
    assert_eq!(s["method"]["sensitivities"], Value::Bool(true));
    let phi: Vec<Vec<f64>> = s["sensitivity"]["state"].as_array().unwrap().iter().map(numbers).collect();
    assert_eq!((phi.len(), phi[0].len()), (4, 4));
    let largest = phi.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    // ΦᵀJΦ = J, J = [[0, I], [−I, 0]].
    for a in 0..4 {
        for b in 0..4 {
            let form: f64 = (0..2).map(|i| phi[i][a] * phi[i + 2][b] - phi[i + 2][a] * phi[i][b]).sum();
            let j = if b == a + 2 {
                1.0
            } else if a == b + 2 {
                -1.0
            } else {
                0.0
            };
            assert!((form - j).abs() < 1e-9 * largest.powi(2).max(1.0), "ΦᵀJΦ[{a}][{b}] = {form}");
        }
    }
    for j in 0..4 {
        let delta = 1e-6 * (1.0 + x0[j].abs());
        let at = |sign: f64| {
            let mut x = x0;
            x[j] += sign * delta;
            final_state(x, &[], &dir).0
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        for i in 0..4 {
            let fd = (plus[i] - minus[i]) / (2.0 * delta);
            assert!((fd - phi[i][j]).abs() < 1e-5 * largest, "entry ({i}, {j}): IFT {} FD {fd}", phi[i][j]);
        }
    }
}

#[test]
fn no_sensitivity_unless_asked() {
    let dir = TempDir::new("sensitivities-off");
    let (_, s) = final_state([1.0, 0.2, 0.3, 1.2], &[], &dir);
    assert!(s.get("sensitivity").is_none());
    assert_eq!(s["method"]["sensitivities"], Value::Bool(false));
}

#[test]
fn a_rigid_body_is_refused() {
    let dir = TempDir::new("sensitivities-rigid");
    let output = run(&common::example("dzhanibekov.toml"), &["method.sensitivities=true"], &dir);
    assert_fails(&output, &dir, &["a rigid body has no tangent map yet", "method.sensitivities"]);
}

//! A tangent map that stopped being finite was written to summary.json as `null`s with exit 0 and no
//! word: a run with `method.sensitivities = true` now warns `sensitivity_lost`, naming the step, on
//! stderr and in summary.json.
//!
//! The case: a particle resting on the top of a saddle, L = ½ẋ² + ½λ²x² with λ = 10. It stays at
//! x = 0 exactly (the motion is right), while the flow stretches: for this quadratic Lagrangian the
//! midpoint step is the Cayley transform of h·[[0, 1], [λ², 0]], whose eigenvalues are
//! μ^{±1}, μ = (1 + hλ/2)/(1 − hλ/2), so Φ_N = M^N has Φ_xx = (μ^N + μ^{−N})/2 and entries up to
//! about (λ/2)·μ^N, past the largest double (1.8e308) from N = (ln 1.8e308 − ln 5)/ln μ ≈ 7076,
//! t ≈ 70.8 — closed forms independent of the run.

use crate::common;

use common::{numbers, run, stderr, summary, TempDir};
use serde_json::Value;

const SADDLE: &str = r#"
[system]
name = "a particle resting on a saddle"
shape = ["x"]
lagrangian = "0.5*x_dot^2 + 50*x^2"

[method]
rule = "midpoint"
sensitivities = true

[time]
step = 0.01
duration = 100.0

[initial]
q = { x = 0.0 }
v = { x = 0.0 }
"#;

#[test]
fn an_overflowing_tangent_map_is_reported_with_its_step() {
    let dir = TempDir::new("sensitivity-lost");
    let spec = dir.file("saddle.toml", SADDLE);
    let output = run(&spec, &[], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("warning [sensitivity_lost]"), "{}", stderr(&output));
    let s = summary(&dir);
    assert_eq!(numbers(&s["final"]["q"]), vec![0.0], "the motion itself stays at rest");
    let warnings = s["warnings"].as_array().unwrap();
    let lost: Vec<&Value> = warnings.iter().filter(|w| w["kind"] == "sensitivity_lost").collect();
    assert_eq!(lost.len(), 1, "{warnings:?}");
    let t = lost[0]["t"].as_f64().unwrap();
    assert!((70.0..71.5).contains(&t), "lost at t = {t}, expected near 70.8");
    assert!(lost[0]["message"].as_str().unwrap().contains("overflowed"), "{}", lost[0]["message"]);
    assert!(s["sensitivity"]["state"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap())
        .all(Value::is_null));
}

#[test]
fn a_tangent_map_that_stays_finite_has_no_warning() {
    let dir = TempDir::new("sensitivity-kept");
    let spec = dir.file("saddle.toml", SADDLE);
    let output = run(&spec, &["time.duration=60"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let s = summary(&dir);
    assert_eq!(s["warnings"].as_array().unwrap().len(), 0, "{}", s["warnings"]);
    // Φ_xx = (μ^N + μ^−N)/2 after N = 6000 steps.
    let phi_xx = numbers(&s["sensitivity"]["state"][0])[0];
    let mu: f64 = (1.0 + 0.05) / (1.0 - 0.05);
    let expected = 0.5 * (mu.powi(6000) + mu.powi(-6000));
    assert!((phi_xx / expected - 1.0).abs() < 1e-9, "Φ_xx = {phi_xx:e}, closed form {expected:e}");
}

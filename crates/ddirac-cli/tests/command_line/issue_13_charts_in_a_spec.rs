//! Issue 13: an atlas in a spec (`[[system.charts]]`). The spherical pendulum example, started
//! with a small azimuthal velocity so that it passes near its lower pole, switches to a polar cap
//! and follows the built-in spherical pendulum (whose coordinates are the example's under
//! θ_b = φ, φ_b = π − θ, and whose atlas has the same caps); without the atlas it does not. Errors
//! in a chart are reported at their key.

use crate::common;

use common::{assert_fails, example, run, succeed, underlined, TempDir};

/// Initial data near the lower pole: 1 rad from the bottom, a slow azimuthal velocity.
const NEAR_POLE: [&str; 3] = ["initial.v.phi=0.001", "time.duration=10.0", "output.every=1"];

/// The built-in spherical pendulum from the same state, in its own coordinates.
const BUILT_IN: &str = r#"
system = "spherical_pendulum"
[method]
rule = "midpoint"
reduced = true
[time]
step = 0.005
duration = 10.0
[initial]
q = { theta = 0.0, phi = 2.141592653589793 }
v = { theta = 0.001, phi = 0.0 }
"#;

/// The bob's position from the example's (θ, φ): θ from the downward vertical.
fn position(q: &[f64]) -> [f64; 3] {
    [q[0].sin() * q[1].cos(), q[0].sin() * q[1].sin(), -q[0].cos()]
}

#[test]
fn the_spherical_pendulum_example_switches_to_a_cap_near_the_pole_and_follows_the_built_in() {
    let (dir, built_in_dir, polar_dir) =
        (TempDir::new("sp-atlas"), TempDir::new("sp-built-in"), TempDir::new("sp-polar"));
    let text = succeed(&example("spherical_pendulum.toml"), &NEAR_POLE, &dir);
    let built_in = succeed(&built_in_dir.file("spec.toml", BUILT_IN), &[], &built_in_dir);
    let polar =
        succeed(&example("spherical_pendulum.toml"), &[&NEAR_POLE[..], &["method.atlas=false"]].concat(), &polar_dir);
    assert!(text.summary["chart_switches"].as_u64().unwrap() > 0);
    assert!(text.column("chart").contains(&1.0), "the lower cap is used");
    assert_eq!(text.summary["coordinates"], serde_json::json!(["theta", "phi"]));
    let b = built_in.final_q();
    let expected = [b[1].sin() * b[0].cos(), b[1].sin() * b[0].sin(), b[1].cos()];
    let apart = |q: &[f64]| (0..3).map(|i| (position(q)[i] - expected[i]).abs()).fold(0.0, f64::max);
    let (with_atlas, without) = (apart(&text.final_q()), apart(&polar.final_q()));
    eprintln!("final position against the built-in: {with_atlas:.2e} with the atlas, {without:.2e} without");
    assert!(with_atlas < 1e-9, "{with_atlas:e}");
    assert!(without > 1e-3, "{without:e}");
    // The momentum map: conserved in the caps and the overlaps as far as the steps' L_d is invariant in
    // floating point (measured 2.9e-13).
    let j = text.column("momentum_phi");
    let drift = j.iter().map(|v| (v - j[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 2e-12, "{drift:e}");
}

/// The example with `from` replaced by `to`, written to `dir`.
fn edited(dir: &TempDir, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(example("spherical_pendulum.toml")).unwrap();
    assert!(text.contains(from), "the example has no `{from}`");
    dir.file("spec.toml", &text.replacen(from, to, 1))
}

#[test]
fn errors_in_a_chart_are_reported_at_their_key() {
    let dir = TempDir::new("sp-bad-map");
    let spec = edited(&dir, r#"phi = "atan2(y, x)" }"#, r#"phi = "atan2(y, z)" }"#);
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["`to_main.phi` of chart 1", "unknown name `z`"]);
    assert_eq!(underlined(&stderr, "to_main = "), ["z"]);

    let dir = TempDir::new("sp-missing-map");
    let spec = edited(&dir, r#", y = "sin(theta)*sin(phi)" }"#, " }");
    assert_fails(&run(&spec, &[], &dir), &dir, &["`from_main.y` of chart 1 is missing"]);

    let dir = TempDir::new("sp-no-quality");
    let spec = edited(&dir, "quality = \"abs(sin(theta))\"\n", "");
    assert_fails(&run(&spec, &[], &dir), &dir, &["give `quality`"]);

    let dir = TempDir::new("sp-chart-lists");
    let spec = edited(&dir, r#"shape = ["x", "y"]"#, r#"shape = ["x", "x"]"#);
    assert_fails(&run(&spec, &[], &dir), &dir, &["`x` appears twice in `system.charts (chart 1).shape`"]);
}

//! Finding 1: the invariance check was relative to |L_d|, so adding a large constant to L made a
//! non-invariant Lagrangian pass (and a reduced run then reported zero momentum drift while the true
//! momentum drifts). The verdict must not change when L is shifted by a constant or scaled.

use crate::common;

use common::{check, line, run, stdout, TempDir};

/// A spherical pendulum whose gravity is tilted by `eps` from the axis of the azimuth `theta`: not
/// invariant under translations of `theta` unless eps = 0. `scale` multiplies L, `c` is added to it.
const TILTED: &str = r#"
[system]
name = "tilted spherical pendulum"
shape = ["phi"]
group = ["theta"]
angles = ["phi", "theta"]
lagrangian = "scale*(0.5*(phi_dot^2 + sin(phi)^2*theta_dot^2) - g*(cos(eps)*cos(phi) + sin(eps)*sin(phi)*cos(theta))) + c"

[parameters]
g = 9.81
eps = 0.01
scale = 1.0
c = 0.0

[method]
reduced = true

[time]
step = 0.01
steps = 200

[initial]
q = [1.0, 0.0]
v = [0.0, 1.0]
"#;

fn invariance_line(report: &str) -> &str {
    line(report, "invariance")
}

#[test]
fn a_tilted_pendulum_is_not_invariant_whatever_constant_or_factor_l_carries() {
    let dir = TempDir::new("shifted-constant");
    let spec = dir.file("tilted.toml", TILTED);
    for (c, scale) in [("0.0", "1.0"), ("1e9", "1.0"), ("-1e12", "1.0"), ("1e9", "1e-6"), ("0.0", "1e8")] {
        let sets = [format!("parameters.c={c}"), format!("parameters.scale={scale}")];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let output = check(&spec, &sets, &dir);
        let report = stdout(&output);
        assert!(!output.status.success(), "c = {c}, scale = {scale}: check accepted\n{report}");
        assert!(invariance_line(&report).contains("NOT invariant"), "c = {c}, scale = {scale}\n{report}");
        let deviation: f64 =
            invariance_line(&report).split("deviation ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
        // The tilt changes L_d by about h·g·sin(eps) per unit shift, against a slope of order |p| ~ 1.
        assert!(deviation > 1e-4, "c = {c}, scale = {scale}: deviation {deviation}");
        let refused = run(&spec, &sets, &dir);
        assert!(!refused.status.success(), "c = {c}, scale = {scale}: the reduced run was accepted");
        assert!(String::from_utf8_lossy(&refused.stderr).contains("not invariant under translation"));
    }
}

#[test]
fn an_upright_pendulum_stays_invariant_whatever_constant_or_factor_l_carries() {
    let dir = TempDir::new("shifted-invariant");
    let spec = dir.file("upright.toml", TILTED);
    for (c, scale) in [("0.0", "1.0"), ("1e9", "1.0"), ("-1e12", "1e-6"), ("0.0", "1e8")] {
        let sets = ["parameters.eps=0.0".to_owned(), format!("parameters.c={c}"), format!("parameters.scale={scale}")];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let output = check(&spec, &sets, &dir);
        let report = stdout(&output);
        assert!(output.status.success(), "c = {c}, scale = {scale}: check refused\n{report}");
        assert!(invariance_line(&report).ends_with(": invariant"), "{report}");
    }
}

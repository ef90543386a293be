//! `ddirac equilibria`: the relative equilibrium of the reduced discrete map against the closed forms
//! of the continuous motion — the spherical pendulum's conical motion (μ² = m²gl³ sin⁴θ*/cos θ*,
//! small-oscillation frequency ω² = g(1 + 3cos²θ*)/(l cos θ*)) and Kepler's circular orbit (r* = μ²/(mk),
//! radial frequency = orbital frequency μ/(m r*²)): the discrete fixed point converges at order 2 in h
//! (Kepler's is exact: r constant makes the midpoint rule's equations for r the continuous ones), the
//! multipliers lie on the unit circle to 1e-10 and their angle / h tends to the frequency; an
//! upright pendulum is unstable; a map with a multiplier 1 and a rigid body are refused.

use crate::common;

use common::{assert_fails, ddirac, stderr, TempDir};
use serde_json::Value;

/// Runs `ddirac equilibria` and returns the first equilibrium of equilibria.json.
fn equilibrium(spec: &str, sets: &[String], dir: &TempDir) -> Value {
    let out = dir.out();
    let mut args = vec!["equilibria", spec, "--out", out.to_str().unwrap(), "--quiet"];
    for set in sets {
        args.extend(["--set", set]);
    }
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    file["equilibria"][0].clone()
}

fn multipliers(e: &Value) -> Vec<(f64, f64)> {
    e["multipliers"].as_array().unwrap().iter().map(|m| (m[0].as_f64().unwrap(), m[1].as_f64().unwrap())).collect()
}

/// The root of a monotone `f` in (a, b) by bisection.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (f(m) > 0.0) == (f(a) > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[test]
fn the_conical_pendulum_is_found_at_order_2_with_its_frequency() {
    let dir = TempDir::new("equilibria-conical");
    let spec = common::example("spherical_pendulum.toml");
    let (m, g, l, mu) = (1.0f64, 9.8f64, 1.0f64, 1.6f64);
    let theta_star = bisect(|t| t.sin().powi(4) / t.cos() - mu * mu / (m * m * g * l.powi(3)), 1e-6, 1.5);
    let omega = (g * (1.0 + 3.0 * theta_star.cos().powi(2)) / (l * theta_star.cos())).sqrt();
    let azimuthal = mu / (m * l * l * theta_star.sin().powi(2));
    let mut errors = vec![];
    for h in [0.01, 0.005, 0.0025] {
        let sets = [
            format!("time.step={h}"),
            "initial.q.theta=1.0".to_owned(),
            format!("initial.p.phi={mu}"),
            "initial.p.theta=0.0".to_owned(),
        ];
        let e = equilibrium(&spec, &sets, &dir);
        assert_eq!(e["stable"], true, "h = {h}: {e}");
        assert_eq!(e["momentum"][0].as_f64().unwrap(), mu);
        let theta = e["shape"]["theta"].as_f64().unwrap();
        assert!(e["shape_momentum"]["theta"].as_f64().unwrap().abs() < 1e-12, "{e}");
        errors.push((theta - theta_star).abs());
        let pairs = multipliers(&e);
        assert_eq!(pairs.len(), 2);
        for (re, im) in &pairs {
            assert!((re.hypot(*im) - 1.0).abs() < 1e-10, "h = {h}: |λ| = {}", re.hypot(*im));
        }
        let frequency = pairs[1].1.atan2(pairs[1].0) / h;
        let velocity = e["group_velocity"][0].as_f64().unwrap();
        if h == 0.0025 {
            assert!((frequency - omega).abs() < 1e-3 * omega, "angle / h = {frequency}, ω = {omega}");
            assert!((velocity - azimuthal).abs() < 1e-3 * azimuthal, "φ̇ = {velocity}, closed form {azimuthal}");
        }
    }
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((order - 2.0).abs() < 0.1, "order {order} from {errors:?}");
    }
}

#[test]
fn keplers_circular_orbit_has_the_radial_frequency_of_its_revolution() {
    let dir = TempDir::new("equilibria-kepler");
    let spec = common::example("kepler.toml");
    let mu = 0.8f64;
    let r_star = mu * mu; // m = k = 1
    let orbital = mu / (r_star * r_star);
    let mut errors = vec![];
    for h in [0.01, 0.005, 0.0025] {
        let sets = [format!("time.step={h}"), "initial.q.r=0.9".to_owned(), format!("initial.p.phi={mu}")];
        let e = equilibrium(&spec, &sets, &dir);
        assert_eq!(e["stable"], true, "{e}");
        // With r constant the midpoint rule's equations for r are the continuous ones: the discrete
        // circular orbit is the exact one, and so is its angular velocity.
        let r = e["shape"]["r"].as_f64().unwrap();
        assert!((r - r_star).abs() < 1e-14, "h = {h}: r = {r}, r* = {r_star}");
        let velocity = e["group_velocity"][0].as_f64().unwrap();
        assert!((velocity - orbital).abs() < 1e-12 * orbital, "φ̇ = {velocity}, orbital {orbital}");
        let pairs = multipliers(&e);
        assert!(pairs.iter().all(|(re, im)| (re.hypot(*im) - 1.0).abs() < 1e-10), "{pairs:?}");
        // The radial oscillation's frequency converges at order 2.
        let radial = pairs[1].1.atan2(pairs[1].0) / h;
        errors.push((radial - orbital).abs());
        if h == 0.0025 {
            assert!(errors[2] < 1e-3 * orbital, "radial {radial}, orbital {orbital}");
        }
    }
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((order - 2.0).abs() < 0.1, "order {order} from {errors:?}");
    }
}

/// A pendulum in a plane that can also slide freely along x (the group): upright, it is unstable.
const UPRIGHT: &str = r#"[system]
name = "sliding pendulum"
shape = ["theta"]
group = ["x"]
angles = ["theta"]
lagrangian = "0.5*theta_dot^2 + 0.5*x_dot^2 + cos(theta)"
[method]
rule = "midpoint"
[time]
step = 0.01
steps = 10
[initial]
q = { theta = 3.0, x = 0.0 }
p = { theta = 0.0, x = 0.25 }
"#;

#[test]
fn an_upright_pendulum_is_found_unstable_with_its_growth_rate() {
    let dir = TempDir::new("equilibria-upright");
    let spec = dir.file("upright.toml", UPRIGHT);
    let out = dir.out();
    let output = ddirac(&["equilibria", &spec, "--out", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(text.contains("verdict          unstable"), "{text}");
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    let e = &file["equilibria"][0];
    assert_eq!(e["stable"], false);
    assert!((e["shape"]["theta"].as_f64().unwrap() - std::f64::consts::PI).abs() < 1e-12, "{e}");
    // u'' = u about θ = π: multipliers e^{±h} to O(h³) (the midpoint rule: (1 ± h/2)/(1 ∓ h/2)).
    let h: f64 = 0.01;
    let mut moduli: Vec<f64> = multipliers(e).iter().map(|(re, im)| re.hypot(*im)).collect();
    moduli.sort_by(f64::total_cmp);
    let exact = (1.0 + h / 2.0) / (1.0 - h / 2.0);
    assert!((moduli[1] - exact).abs() < 1e-8 && (moduli[0] - 1.0 / exact).abs() < 1e-8, "{moduli:?}");
    assert!((e["group_velocity"][0].as_f64().unwrap() - 0.25).abs() < 1e-12, "{e}");
}

#[test]
fn a_map_with_a_multiplier_one_and_a_rigid_body_are_refused() {
    let dir = TempDir::new("equilibria-refused");
    // A free particle: every state at rest is fixed, Φ_h − I is singular.
    let free = dir.file(
        "free.toml",
        "[system]\nshape = [\"x\"]\nlagrangian = \"0.5*x_dot^2\"\n[time]\nstep = 0.1\nsteps = 10\n[initial]\nq = [0.0]\n\
         p = [0.0]\n",
    );
    let out = dir.out();
    let output = ddirac(&["equilibria", &free, "--out", out.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["no relative equilibrium found", "multiplier 1"]);
    let output = ddirac(&["equilibria", &common::example("dzhanibekov.toml"), "--out", out.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["this command does not take the rigid body yet"]);
}

#[test]
fn a_step_that_turns_the_group_angle_by_more_than_a_quarter_turn_warns() {
    let dir = TempDir::new("equilibria-ambiguous");
    let spec = common::example("spherical_pendulum.toml");
    let out = dir.out();
    let sets = ["initial.q.theta=1.0", "initial.p.phi=1.6", "initial.p.theta=0.0", "time.step=1.0"];
    let mut args = vec!["equilibria", &spec, "--out", out.to_str().unwrap()];
    for set in &sets {
        args.extend(["--set", set]);
    }
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("warning [ambiguous_group_velocity]: `phi` turns by more than π/2"));
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    assert_eq!(file["equilibria"][0]["ambiguous_group_velocity"][0], "phi");
    // At h = 0.01 the increment is small and nothing is said.
    let fine = TempDir::new("equilibria-unambiguous");
    let out = fine.out();
    let mut args = vec!["equilibria", &spec, "--out", out.to_str().unwrap(), "--set", "time.step=0.01"];
    for set in &sets[..3] {
        args.extend(["--set", set]);
    }
    let output = ddirac(&args, &fine.0);
    assert!(output.status.success() && !stderr(&output).contains("ambiguous"), "{}", stderr(&output));
}

/// A body in a central field −1/r − a/r³: for p_phi = μ above μ_c = (12a)^{1/4} it has two circular
/// orbits, r² − μ² r + 3a = 0, the outer stable and the inner unstable; they meet at the fold μ_c.
const TWO_CIRCLES: &str = r#"[system]
name = "orbits with an inner unstable circle"
shape = ["r"]
group = ["phi"]
angles = ["phi"]
lagrangian = "0.5*(r_dot^2 + r^2*phi_dot^2) + 1/r + a/r^3"
[parameters]
a = 0.1
[method]
rule = "midpoint"
[time]
step = 0.01
steps = 10
[initial]
q = { r = 1.5, phi = 0.0 }
p = { r = 0.0, phi = 1.4 }
"#;

fn circles(mu: f64) -> (f64, f64) {
    let root = (mu.powi(4) - 1.2).sqrt();
    ((mu * mu - root) / 2.0, (mu * mu + root) / 2.0)
}

#[test]
fn a_family_is_continued_through_its_fold_onto_the_inner_circles() {
    let dir = TempDir::new("equilibria-family");
    let spec = dir.file("circles.toml", TWO_CIRCLES);
    let out = dir.out();
    let output = ddirac(&["equilibria", &spec, "--family", "phi=1.4:1.0:41", "--out", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    let members = file["equilibria"].as_array().unwrap();
    let fold = 1.2f64.powf(0.25);
    // Down the outer circles to the last value above the fold (1.05), through the fold, and up the
    // inner circles over the same values back to 1.4: each member the exact circle (the midpoint rule's
    // fixed point is exact here), the outer stable and the inner unstable.
    let mu = |m: &Value| m["momentum"][0].as_f64().unwrap();
    let outer = members.iter().take_while(|m| m["stable"] == true).count();
    assert_eq!((outer, members.len()), (36, 72), "{text}");
    for (k, m) in members.iter().enumerate() {
        let (mu, r) = (mu(m), m["shape"]["r"].as_f64().unwrap());
        let expected = if k < outer { circles(mu).1 } else { circles(mu).0 };
        assert!((r - expected).abs() < 1e-10 * r, "member {k}, μ = {mu}: r = {r}, the circle is at {expected}");
        assert_eq!(m["stable"], k < outer, "member {k}, μ = {mu}");
        let value = if k < outer { 1.4 - 0.01 * k as f64 } else { 1.4 - 0.01 * (71 - k) as f64 };
        assert!((mu - value).abs() < 1e-12, "member {k}: μ = {mu}, the value {value}");
    }
    // The fold: where the circles meet, μ⁴ = 12a, r = √(3a).
    let family = &file["family"];
    assert_eq!(family["along"], "phi");
    let folds = family["folds"].as_array().unwrap();
    assert_eq!(folds.len(), 1, "{text}");
    let (at, r) = (folds[0]["momentum"].as_f64().unwrap(), folds[0]["shape"]["r"].as_f64().unwrap());
    assert!((at - fold).abs() < 1e-9, "the fold at μ = {at}, the closed form {fold}");
    assert!((r - 0.3f64.sqrt()).abs() < 1e-6, "the fold at r = {r}, the closed form {}", 0.3f64.sqrt());
    assert_eq!(folds[0]["next_member"], 36);
    let changes = family["stability_changes"].as_array().unwrap();
    assert_eq!(changes.len(), 1, "{changes:?}");
    assert!(family["ended"].is_null(), "{}", family["ended"]);
    assert!(text.contains("the family turns back at a fold at p_phi = 1.046"), "{text}");
    assert!(text.contains("fold: the family turns back"), "{text}");
    for figure in ["family.png", "family.svg"] {
        assert!(std::fs::metadata(out.join(figure)).map(|m| m.len() > 1000).unwrap_or(false), "{figure}");
    }
    // Over values on both sides of the fold, the family turns at it and comes back over the values
    // above it; those below it (no circle there) are not searched.
    let below = TempDir::new("equilibria-family-below");
    let out = below.out();
    let args = [
        "equilibria",
        &spec,
        "--family",
        "phi=1.1:0.9:21",
        "--set",
        "initial.q.r=0.9",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    let output = ddirac(&args, &below.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    let members = file["equilibria"].as_array().unwrap();
    assert_eq!(file["family"]["folds"].as_array().unwrap().len(), 1);
    assert_eq!(members.len(), 12, "1.1 … 1.05 outer, 1.05 … 1.1 inner");
    assert!(file["family"]["ended"].is_null());
    // The inner circles, from a guess near them, upwards: all unstable. (They shrink as 3a/μ², and turn
    // at μ/r² = 340 rad/s at μ = 2: h = 0.001 resolves them.)
    let inner = TempDir::new("equilibria-family-inner");
    let out = inner.out();
    let args = [
        "equilibria",
        &spec,
        "--family",
        "phi=1.4:2.0:7",
        "--set",
        "initial.q.r=0.2",
        "--set",
        "time.step=0.001",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    let output = ddirac(&args, &inner.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let file: Value = serde_json::from_str(&std::fs::read_to_string(out.join("equilibria.json")).unwrap()).unwrap();
    let members = file["equilibria"].as_array().unwrap();
    assert_eq!(members.len(), 7);
    for m in members {
        let mu = m["momentum"][0].as_f64().unwrap();
        let r = m["shape"]["r"].as_f64().unwrap();
        assert!((r - circles(mu).0).abs() < 1e-10 * r, "μ = {mu}: r = {r}, inner circle {}", circles(mu).0);
        assert_eq!(m["stable"], false, "μ = {mu}");
    }
    assert!(file["family"]["ended"].is_null());
}

#[test]
fn a_family_of_wrong_shape_is_refused() {
    let dir = TempDir::new("equilibria-family-refused");
    let spec = dir.file("circles.toml", TWO_CIRCLES);
    let out = dir.out();
    for (family, needle) in [
        ("r=1:2:3", "`r` is not a group coordinate; the group coordinates are phi"),
        ("phi=1:2", "NAME=FROM:TO:COUNT"),
        ("phi=1:x:3", "NAME=FROM:TO:COUNT"),
        ("phi=1:2:1", "at least 2"),
        ("phi=1:inf:3", "finite"),
    ] {
        let output = ddirac(&["equilibria", &spec, "--family", family, "--out", out.to_str().unwrap()], &dir.0);
        assert_fails(&output, &dir, &[needle]);
    }
    // A search whose iterates run off to large r (where the step barely moves r and the residual fades)
    // says so, naming the coordinate, instead of only that they did not settle.
    let output = ddirac(&["equilibria", &spec, "--set", "initial.p.phi=1.1", "--out", out.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["the iterates ran off to r = "]);
    // A family whose first member is not found fails as the single search does.
    let output = ddirac(&["equilibria", &spec, "--family", "phi=0.5:0.6:2", "--out", out.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["no relative equilibrium found"]);
}

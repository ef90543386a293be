//! `ddirac run` of the rigid body (`system = "rigid_body"`): its trajectory and summary against
//! Euler's equations integrated here by RK4 (Π̇ = Π × Ω + m g Γ × c, Γ = Rᵀe3, Ṙ = R Ω̂), the
//! reduced run against the unreduced one, the fixed column and key names, and every wrong,
//! degenerate and extreme input refused, warned or right.

use crate::common;

use common::{assert_fails, euler_rk4, run, succeed, TempDir, M3};

const FREE: &str = r#"system = "rigid_body"
[parameters]
I1 = 1.0
I2 = 2.0
I3 = 3.0
m = 0.0
[method]
order = 4
[time]
step = 0.01
duration = 5.0
[initial]
R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
Omega = [0.01, 2.0, 0.01]
[output]
every = 10
"#;

/// A heavy asymmetric top tilted by 0.3 rad about the first axis.
fn heavy() -> String {
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    format!(
        "system = \"rigid_body\"\n[parameters]\nI1 = 1.0\nI2 = 1.3\nI3 = 0.4\nm = 1.0\ng = 9.8\nc1 = 0.05\nc3 = 0.5\n\
         [method]\norder = 4\n[time]\nstep = 0.005\nduration = 3.0\n[initial]\n\
         R = [[1, 0, 0], [0, {c:?}, {:?}], [0, {s:?}, {c:?}]]\nPi = [0.3, -0.2, 1.5]\n[output]\nevery = 20\n",
        -s
    )
}

fn final_state(summary: &serde_json::Value) -> (M3, [f64; 3]) {
    let rows = summary["final"]["R"].as_array().expect("final.R is a list of rows");
    assert_eq!(rows.len(), 3);
    let mut r = [[0.0; 3]; 3];
    for (i, row) in rows.iter().enumerate() {
        let row = common::numbers(row);
        assert_eq!(row.len(), 3);
        r[i] = [row[0], row[1], row[2]];
    }
    let pi = common::numbers(&summary["final"]["Pi"]);
    (r, [pi[0], pi[1], pi[2]])
}

fn distance(a: &(M3, [f64; 3]), b: &(M3, [f64; 3])) -> f64 {
    let r = (0..9).map(|k| (a.0[k / 3][k % 3] - b.0[k / 3][k % 3]).abs()).fold(0.0, f64::max);
    (0..3).map(|i| (a.1[i] - b.1[i]).abs()).fold(r, f64::max)
}

#[test]
fn a_free_body_follows_eulers_equations_and_the_reduced_run_agrees_with_the_unreduced() {
    let dir = TempDir::new("rigid-free");
    let spec = dir.file("free.toml", FREE);
    let reference = euler_rk4(
        [1.0, 2.0, 3.0],
        [0.0; 3],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [0.01, 4.0, 0.03],
        5.0,
        50_000,
    );
    let unreduced = succeed(&spec, &[], &dir);
    let state = final_state(&unreduced.summary);
    // Order 4 at h = 0.01, |Ω| = 2: an error of order (h|Ω|)⁴ ≈ 1e-7 over the run.
    assert!(distance(&state, &reference) < 1e-6, "off by {:e}", distance(&state, &reference));
    let header: Vec<&str> = unreduced.columns.keys().map(String::as_str).collect();
    for name in [
        "t",
        "R11",
        "R12",
        "R13",
        "R21",
        "R22",
        "R23",
        "R31",
        "R32",
        "R33",
        "Pi1",
        "Pi2",
        "Pi3",
        "energy",
        "momentum_x",
        "momentum_y",
        "momentum_z",
    ] {
        assert!(header.contains(&name), "no column {name} in {header:?}");
    }
    assert_eq!(header.len(), 17);
    assert_eq!(unreduced.column("t").len(), 51);
    let s = &unreduced.summary;
    assert_eq!(s["system"], "rigid_body");
    assert_eq!(s["symmetry"], "SO(3)");
    assert!(s["casimir"]["max_relative_drift"].as_f64().unwrap() < 1e-13);
    assert!(s["momentum_map"]["max_relative_drift"].as_f64().unwrap() < 1e-13);
    assert!(s["orthogonality"].as_f64().unwrap() < 1e-14);
    assert!(s["warnings"].as_array().unwrap().is_empty());
    // The trajectory's last row is the summary's final state.
    let last = |name: &str| *unreduced.column(name).last().unwrap();
    assert_eq!(last("R23"), state.0[1][2]);
    assert_eq!(last("Pi2"), state.1[1]);

    let dir = TempDir::new("rigid-free-reduced");
    let reduced = succeed(&spec, &["method.reduced=true"], &dir);
    let other = final_state(&reduced.summary);
    assert!(distance(&state, &other) < 1e-12, "reduced and unreduced differ by {:e}", distance(&state, &other));
    assert_eq!(reduced.summary["method"]["reduced"], true);
}

#[test]
fn a_heavy_top_follows_eulers_equations_and_keeps_its_vertical_momentum() {
    let dir = TempDir::new("rigid-heavy");
    let spec = dir.file("heavy.toml", &heavy());
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let r0 = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    let reference = euler_rk4([1.0, 1.3, 0.4], [0.05 * 9.8, 0.0, 0.5 * 9.8], r0, [0.3, -0.2, 1.5], 3.0, 60_000);
    let run = succeed(&spec, &[], &dir);
    let state = final_state(&run.summary);
    assert!(distance(&state, &reference) < 1e-6, "off by {:e}", distance(&state, &reference));
    assert_eq!(run.summary["symmetry"], "vertical");
    assert_eq!(run.summary["momentum_map"]["conserved"], serde_json::json!(["z"]));
    let z = run.column("momentum_z");
    let spread = z.iter().map(|v| (v - z[0]).abs()).fold(0.0, f64::max);
    assert!(spread < 1e-13, "e3 · R Π moved by {spread:e}");
    // The horizontal components are not conserved: gravity turns them.
    let x = run.column("momentum_x");
    assert!(x.iter().map(|v| (v - x[0]).abs()).fold(0.0, f64::max) > 1e-2);
    // Reduction by all of SO(3) is refused, pointing at the key.
    let dir = TempDir::new("rigid-heavy-reduced");
    let output = common::run(&spec, &["method.reduced=true"], &dir);
    assert_fails(
        &output,
        &dir,
        &["reduction by SO(3) needs a Lagrangian invariant under every rotation", "reduced = true"],
    );
    assert_eq!(output.status.code(), Some(2));
}

#[test]
fn npy_files_hold_the_same_columns() {
    let dir = TempDir::new("rigid-npy");
    let spec = dir.file("free.toml", FREE);
    let output = run(&spec, &["output.format=[\"csv\", \"npy\"]"], &dir);
    assert!(output.status.success(), "{}", common::stderr(&output));
    for name in ["R11", "R33", "Pi1", "Pi3", "energy", "momentum_z", "t"] {
        let bytes = std::fs::read(dir.out().join("npy").join(format!("{name}.npy"))).unwrap();
        // 51 rows of f64 after a 128-byte header.
        assert_eq!(bytes.len(), 128 + 51 * 8, "{name}.npy");
    }
}

/// Runs FREE with the `--set` overrides, which must be refused (exit 2) naming every needle.
fn refused(sets: &[&str], needles: &[&str]) {
    let dir = TempDir::new("rigid-refused");
    let spec = dir.file("free.toml", FREE);
    let output = run(&spec, sets, &dir);
    assert_fails(&output, &dir, needles);
    assert_eq!(output.status.code(), Some(2), "{sets:?}");
}

#[test]
fn wrong_attitudes_are_refused() {
    refused(&["initial.R=[[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]"], &["not a rotation", "|RᵀR − I| is 1.00e-1"]);
    refused(&["initial.R=[[-1, 0, 0], [0, 1, 0], [0, 0, 1]]"], &["not a rotation", "det R = -1"]);
    refused(&["initial.R=[[1, 0, 0], [0, 1, 0]]"], &["`initial.R` has 2 rows"]);
    refused(&["initial.R=[[1, 0, 0, 0], [0, 1, 0], [0, 0, 1]]"], &["row 1 of `initial.R` has 4 entries"]);
    refused(&["initial.R=[[1, 0, 0], [0, nan, 0], [0, 0, 1]]"], &["entry 2 of row 2 of `initial.R` is not finite"]);
    refused(&["initial.R=[[0, 0, 0], [0, 0, 0], [0, 0, 0]]"], &["not a rotation"]);
    // 5e-12 off: over the 1e-12 the attitude is held to.
    refused(&["initial.R=[[1.000000000005, 0, 0], [0, 1, 0], [0, 0, 1]]"], &["not a rotation"]);
}

#[test]
fn a_rotation_written_to_full_precision_and_one_within_the_tolerance_are_taken() {
    let dir = TempDir::new("rigid-near");
    let spec = dir.file("free.toml", FREE);
    let (c, s) = (1.2f64.cos(), 1.2f64.sin());
    let rotation = format!("initial.R=[[{c:?}, {:?}, 0], [{s:?}, {c:?}, 0], [0, 0, 1]]", -s);
    succeed(&spec, &[&rotation], &dir);
    let dir = TempDir::new("rigid-near-2");
    succeed(&spec, &["initial.R=[[1.0000000000002, 0, 0], [0, 1, 0], [0, 0, 1]]"], &dir);
}

#[test]
fn wrong_initial_velocities_and_momenta_are_refused() {
    refused(&["initial.Pi=[1, 2, 3]"], &["`initial.Pi` and `initial.Omega` are both given"]);
    refused(&["initial.Omega=[1, 2]"], &["initial.Omega has 2 entries"]);
    refused(&["initial.Omega=[1, inf, 0]"], &["entry 2 of initial.Omega is not finite"]);
    refused(&["initial.Omega=[1e200, 0, 0]"], &["overflows"]);
    refused(&["initial.q=[0]"], &["a rigid body takes no `initial.q`"]);
    refused(&["initial.q.x=1"], &["`initial.q.x` names a shape coordinate, and this body has none"]);
}

#[test]
fn a_spec_without_pi_or_omega_or_r_is_refused() {
    let dir = TempDir::new("rigid-missing");
    let spec = dir.file("free.toml", &FREE.replace("Omega = [0.01, 2.0, 0.01]\n", ""));
    assert_fails(&run(&spec, &[], &dir), &dir, &["neither `initial.Pi` nor `initial.Omega` is given"]);
    let spec = dir.file("free2.toml", &FREE.replace("R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n", ""));
    assert_fails(&run(&spec, &[], &dir), &dir, &["`initial.R` is missing"]);
}

#[test]
fn keys_without_meaning_on_so3_are_refused() {
    refused(&["method.variant=minus"], &["no (+)/(−) choice"]);
    refused(&["method.connection=[[0]]"], &["a rigid body takes no `method.connection`"]);
    refused(&["method.atlas=true"], &["a rigid body takes no `method.atlas`"]);
    refused(&["method.derivatives=compiled"], &["compiled derivatives are not available for rigid bodies"]);
    refused(&["output.wrap_angles=true"], &["a rigid body takes no `output.wrap_angles`"]);
    refused(&["method.order=4", "method.rule=left"], &["order"]);
    refused(&["parameters.I4=1"], &["invalid parameter `I4`: unknown", "unknown parameter"]);
    refused(&["parameters.I1=0"], &["must be positive"]);
    refused(&["parameters.I2=-1"], &["must be positive"]);
    refused(&["parameters.m=nan"], &["parameter `m` is not finite"]);
}

#[test]
fn systems_lists_the_rigid_body() {
    let dir = TempDir::new("rigid-systems");
    let output = common::ddirac(&["systems"], &dir.0);
    let text = common::stdout(&output);
    assert!(text.contains("rigid_body\n    a rigid body on SO(3)"), "{text}");
    assert!(text.contains("parameters:  I1 = 1, I2 = 2, I3 = 3, m = 1, g = 9.81, c1 = 0, c2 = 0, c3 = 0.1"), "{text}");
}

#[test]
fn a_step_that_does_not_resolve_the_rotation_warns() {
    let dir = TempDir::new("rigid-coarse");
    let spec = dir.file("free.toml", FREE);
    let run = succeed(&spec, &["initial.Omega=[0.01, 300, 0.01]", "method.order=2"], &dir);
    let kinds: Vec<&str> =
        run.summary["warnings"].as_array().unwrap().iter().map(|w| w["kind"].as_str().unwrap()).collect();
    assert!(kinds.contains(&"under_resolved"), "{kinds:?}");
    // A body at rest stays at rest, with nothing to warn of.
    let dir = TempDir::new("rigid-rest");
    let run = succeed(&spec, &["initial.Omega=[0, 0, 0]"], &dir);
    assert_eq!(final_state(&run.summary).0, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(run.summary["warnings"].as_array().unwrap().is_empty());
}

#[test]
fn check_tests_the_declared_symmetry_and_gives_the_verdict_of_a_run() {
    let dir = TempDir::new("rigid-check");
    let spec = dir.file("free.toml", FREE);
    let output = common::check(&spec, &["method.reduced=true"], &dir);
    assert!(output.status.success(), "{}", common::stderr(&output));
    let report = common::stdout(&output);
    assert!(common::line(&report, "symmetry").contains("SO(3), every rotation of space"), "{report}");
    assert!(common::line(&report, "symmetry").ends_with("holds"), "{report}");
    assert!(common::line(&report, "reduction").contains("by SO(3)"), "{report}");
    // H0 = ½ Σ I_i Ω_i² = ½ (1e-4 + 8 + 3e-4) = 4.0002.
    assert!(common::line(&report, "Legendre").contains("H0 = 4.0002000000e0"), "{report}");
    assert!(common::line(&report, "verdict").ends_with("a run would be accepted"), "{report}");
    let heavy = dir.file("heavy.toml", &heavy());
    let output = common::check(&heavy, &["method.reduced=true"], &dir);
    assert_eq!(output.status.code(), Some(2));
    let report = common::stdout(&output);
    assert!(common::line(&report, "symmetry").contains("rotations about the vertical e3"), "{report}");
    assert!(common::line(&report, "reduction").contains("REFUSED"), "{report}");
    assert!(common::line(&report, "verdict").ends_with("a run would be refused"), "{report}");
    assert!(common::stderr(&output).contains("reduction by SO(3) needs a Lagrangian invariant"));
    let output = common::check(&spec, &["initial.R=[[0, 1, 0], [1, 0, 0], [0, 0, 1]]"], &dir);
    assert_fails(&output, &dir, &["not a rotation", "det R = -1"]);
}

#[test]
fn compare_runs_reduced_and_unreduced_and_refuses_a_heavy_body() {
    let dir = TempDir::new("rigid-compare");
    let out = dir.out();
    let spec = common::example("satellite_rotors.toml");
    let args = ["run", &spec, "--compare", "--out", out.to_str().unwrap(), "--set", "time.duration=2"];
    let output = common::ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", common::stderr(&output));
    assert!(common::stdout(&output).contains("satellite with three rotors: reduced (by SO(3)) and unreduced runs"));
    let table = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), 16);
    assert_eq!(header[..2], ["t", "d_R11"]);
    assert_eq!(header[15], "d_a3");
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 21);
    assert!(rows.iter().all(|r| r[1..].iter().all(|d| d.abs() < 1e-12)));
    for run in ["reduced", "unreduced"] {
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(run).join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["method"]["reduced"], run == "reduced");
    }
    assert!(out.join("compare.png").is_file() && out.join("compare.svg").is_file());
    // A heavy body cannot be reduced by SO(3): refused before anything runs.
    let dir = TempDir::new("rigid-compare-heavy");
    let out = dir.out();
    let spec = common::example("heavy_top_upright.toml");
    let output = common::ddirac(&["run", &spec, "--compare", "--out", out.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["--compare runs the reduced equations too", "`vertical`"]);
    assert_eq!(output.status.code(), Some(2));
}

/// `ddirac convergence` of a rigid body: the error of R_N (its nine entries, Frobenius) against the
/// reference run; checked against RK4 of Euler's equations: the table's error of each row is within
/// the reference run's own error of the distance of that row's R_N from RK4, and the order is 2.
#[test]
fn a_convergence_study_of_a_rigid_body_observes_order_2_against_rk4() {
    let dir = TempDir::new("rigid-convergence");
    let spec = dir.file("free.toml", &FREE.replace("order = 4", "order = 2"));
    let out = dir.out();
    let steps = [250usize, 500, 1000];
    let output = common::ddirac(
        &["convergence", &spec, "--steps", "250,500,1000", "--out", out.to_str().unwrap(), "--quiet"],
        &dir.0,
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let table = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let rows: Vec<Vec<String>> = table.lines().skip(1).map(|l| l.split(',').map(str::to_owned).collect()).collect();
    assert_eq!(rows.len(), 3, "{table}");
    let (exact_r, _) = euler_rk4(
        [1.0, 2.0, 3.0],
        [0.0; 3],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [0.01, 4.0, 0.03],
        5.0,
        200_000,
    );
    let mut errors = vec![];
    for (row, &n) in rows.iter().zip(&steps) {
        assert_eq!(row[0].parse::<usize>().unwrap(), n);
        let error: f64 = row[2].parse().unwrap();
        // The same run by `ddirac run`, against RK4.
        let run_dir = TempDir::new(&format!("rigid-convergence-{n}"));
        let finished = succeed(&spec, &[&format!("time.step={:?}", 5.0 / n as f64)], &run_dir);
        let (r, _) = final_state(&finished.summary);
        let to_rk4 = (0..9).map(|k| (r[k / 3][k % 3] - exact_r[k / 3][k % 3]).powi(2)).sum::<f64>().sqrt();
        assert!((error - to_rk4).abs() < 0.05 * to_rk4, "N = {n}: table {error:e}, against RK4 {to_rk4:e}");
        errors.push(error);
    }
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((order - 2.0).abs() < 0.1, "observed order {order}");
    }
}

#[test]
fn a_system_in_coordinates_refuses_the_rigid_body_s_keys() {
    let dir = TempDir::new("rigid-keys-in-coordinates");
    let spec = dir.file(
        "kepler.toml",
        &std::fs::read_to_string(common::example("kepler.toml"))
            .unwrap()
            .replace("[initial]", "[initial]\nPi = [0, 0, 1]"),
    );
    let output = run(&spec, &[], &dir);
    assert_fails(&output, &dir, &["`initial.Pi` belongs to a rigid body"]);
}

/// A free body written as text, with a rotor about its third axis.
const TEXT: &str = r#"[system]
name = "body with a rotor"
attitude = "SO(3)"
symmetry = "SO(3)"
shape = ["a"]
angles = ["a"]
lagrangian = "0.5*(I1*Omega1^2 + I2*Omega2^2 + I3*Omega3^2) + 0.5*K*(Omega3 + a_dot)^2"
[parameters]
I1 = 1.0
I2 = 2.0
I3 = 3.0
K = 0.5
[time]
step = 0.01
steps = 300
[initial]
R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
Omega = [0.3, 1.0, 0.2]
q = { a = 0.0 }
v = { a = 5.0 }
[output]
every = 300
"#;

#[test]
fn a_body_written_as_text_runs_as_the_built_in_one_when_it_is_the_same_body() {
    // With the rotor's momentum p_a = K (Ω3 + ȧ) = 0 (ȧ = −Ω3 at the start, and p_a is conserved), the
    // rotor stays at rest in space and the body moves exactly as the free body of moments (I1, I2, I3).
    let dir = TempDir::new("rigid-text");
    let spec = dir.file("text.toml", TEXT);
    let text = succeed(&spec, &["initial.v.a=-0.2", "method.order=4"], &dir);
    let builtin_dir = TempDir::new("rigid-text-builtin");
    let builtin = dir.file(
        "free.toml",
        &FREE.replace("Omega = [0.01, 2.0, 0.01]", "Omega = [0.3, 1.0, 0.2]").replace("duration = 5.0", "steps = 300"),
    );
    let body = succeed(&builtin, &["output.every=300"], &builtin_dir);
    let (a, b) = (final_state(&text.summary), final_state(&body.summary));
    assert!(distance(&a, &b) < 1e-12, "text and built-in differ by {:e}", distance(&a, &b));
    assert!(text.column("p_a").iter().all(|p| p.abs() < 1e-12));
    assert_eq!(text.summary["system"], "body with a rotor");
}

/// Runs TEXT with the `--set` overrides, which must be refused (exit 2) naming every needle.
fn text_refused(sets: &[&str], needles: &[&str]) -> String {
    let dir = TempDir::new("rigid-text-refused");
    let spec = dir.file("text.toml", TEXT);
    let output = run(&spec, sets, &dir);
    let stderr = assert_fails(&output, &dir, needles);
    assert_eq!(output.status.code(), Some(2), "{sets:?}");
    stderr
}

#[test]
fn wrong_text_rigid_systems_are_refused_where_they_are_wrong() {
    text_refused(&["system.symmetry=SO4"], &["unknown symmetry `SO4`"]);
    text_refused(&["system.attitude=SE3"], &["unknown attitude group `SE3`"]);
    text_refused(&["system.group=[\"a\"]"], &["a rigid system takes no `system.group`"]);
    text_refused(&["system.quality=\"1\""], &["a rigid system takes no `system.quality`"]);
    // A Lagrangian that depends on the attitude is not invariant under every rotation: refused at the
    // symmetry it declares, with what to declare instead; declared vertical, it runs.
    let lagrangian =
        "system.lagrangian=\"0.5*(I1*Omega1^2 + I2*Omega2^2 + I3*Omega3^2) + 0.5*K*(Omega3 + a_dot)^2 - 9.8*R33\"";
    text_refused(&[lagrangian], &["not invariant under its declared symmetry `SO(3)`", "symmetry = \"vertical\""]);
    let dir = TempDir::new("rigid-text-vertical");
    let spec = dir.file("text.toml", TEXT);
    let heavy = succeed(&spec, &[lagrangian, "system.symmetry=vertical"], &dir);
    assert_eq!(heavy.summary["symmetry"], "vertical");
    // A potential in the first row is not invariant about the vertical either.
    let tilted = "system.lagrangian=\"0.5*(I1*Omega1^2 + I2*Omega2^2 + I3*Omega3^2) + 0.5*K*(Omega3 + a_dot)^2 - R13\"";
    text_refused(&[tilted, "system.symmetry=vertical"], &["not invariant under its declared symmetry `vertical`"]);
    let stderr =
        text_refused(&["system.lagrangian=\"0.5*I1*Omgea1^2\""], &["unknown name `Omgea1` (did you mean `Omega1`?)"]);
    assert!(stderr.contains("the body angular velocity (Omega1, Omega2, Omega3)"), "{stderr}");
    text_refused(&["parameters.Omega1=1"], &["`Omega1`"]);
    // Momenta go with momenta: Π with the shape's p, Ω with its v.
    text_refused(&["initial.Omega=[0, nan, 0]"], &["entry 2 of initial.Omega is not finite"]);
    let dir = TempDir::new("rigid-text-mixed");
    let spec = dir.file("mixed.toml", &TEXT.replace("Omega = [0.3, 1.0, 0.2]", "Pi = [0.3, 2.0, 0.6]"));
    assert_fails(&run(&spec, &[], &dir), &dir, &["`initial.Pi` goes with the shape's `initial.p`"]);
    text_refused(&["initial.v.b=1"], &["`b` is not a shape coordinate; they are a"]);
    // `symmetry` belongs to rigid systems.
    let dir = TempDir::new("rigid-text-coordinates");
    let kepler = std::fs::read_to_string(common::example("kepler_expression.toml")).unwrap();
    let spec = dir.file("kepler.toml", &kepler);
    assert_fails(&run(&spec, &["system.symmetry=SO(3)"], &dir), &dir, &["`system.symmetry` belongs to rigid systems"]);
}

//! End-to-end tests of the `ddirac` binary: the shipped examples against the paper's numbers, the
//! `--set` overrides, and every kind of rejected spec (exit code, message, no finished output).

use crate::common;

use std::path::Path;
use std::process::Output;

use serde_json::Value;

use common::{ddirac, TempDir};

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");
const PENDULUM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/double_spherical_pendulum.toml");

/// Runs `spec` with `--out DIR --quiet` and the given `--set` assignments.
fn run(spec: &str, sets: &[&str], dir: &TempDir) -> Output {
    let out = dir.out();
    let mut args = vec!["run", spec, "--out", out.to_str().unwrap(), "--quiet"];
    for s in sets {
        args.extend(["--set", s]);
    }
    ddirac(&args, &dir.0)
}

fn succeed(spec: &str, sets: &[&str], dir: &TempDir) -> (Value, String) {
    let output = run(spec, sets, dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.stdout.is_empty(), "--quiet printed something");
    let summary = std::fs::read_to_string(dir.out().join("summary.json")).unwrap();
    let csv = std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap();
    (serde_json::from_str(&summary).unwrap(), csv)
}

fn numbers(value: &Value) -> Vec<f64> {
    value.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
}

fn reference_error(summary: &Value) -> f64 {
    summary["reference_error"].as_f64().unwrap()
}

/// Writes `text` as a spec in `dir` and returns its path.
fn spec_file(dir: &TempDir, text: &str) -> String {
    let path = dir.0.join("spec.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

/// The charged-particle example with one line replaced, for specs `--set` cannot express.
fn edited_example(dir: &TempDir, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(CHARGED_PARTICLE).unwrap();
    assert!(text.contains(from), "the example has no `{from}`");
    spec_file(dir, &text.replace(from, to))
}

/// Asserts a failed run: non-zero exit, every `needle` in stderr, no finished or partial file.
fn assert_fails(output: &Output, dir: &TempDir, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "the run succeeded; stderr: {stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "stderr lacks `{needle}`:\n{stderr}");
    }
    for name in ["trajectory.csv", "summary.json", ".trajectory.csv.partial", ".summary.json.partial"] {
        assert!(!dir.out().join(name).exists(), "{name} left behind");
    }
}

#[test]
fn charged_particle_example_reproduces_table_1_for_n_100() {
    let dir = TempDir::new("cp");
    let (summary, csv) = succeed(CHARGED_PARTICLE, &[], &dir);
    // Paper, Table 1: ‖q(T) − q_N‖ = 0.06626 for N = 100.
    assert_eq!(format!("{:.5}", reference_error(&summary)), "0.06626");
    assert_eq!(summary["steps"], 100);
    assert_eq!(summary["method"]["rule"], "left");
    assert_eq!(summary["method"]["reduced"], true);

    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "t,q1,q2,q3,theta,p_q1,p_q2,p_q3,p_theta,energy,discrete_energy,momentum_theta");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 101);
    let last = rows.last().unwrap();
    assert_eq!(last[0].parse::<f64>().unwrap(), 20.0);
    assert_eq!(last[10], "", "discrete_energy must be empty on the last row");
    assert!(rows[..100].iter().all(|r| r[10].parse::<f64>().is_ok()));
    // The CSV is written with round-tripping precision: the last row is the final state exactly.
    let last_q: Vec<f64> = last[1..5].iter().map(|v| v.parse().unwrap()).collect();
    assert_eq!(last_q, numbers(&summary["final"]["q"]));
    // Exact motion q(20) = (sin 20, cos 20 − 1, 20): the error is that of Table 1.
    let exact = [20f64.sin(), 20f64.cos() - 1.0, 20.0];
    let error = exact.iter().zip(&last_q).map(|(e, q)| (e - q).powi(2)).sum::<f64>().sqrt();
    assert!((error - reference_error(&summary)).abs() < 1e-12);
}

#[test]
fn unreduced_run_reaches_the_same_final_configuration() {
    let (reduced_dir, unreduced_dir) = (TempDir::new("red"), TempDir::new("unred"));
    let (reduced, _) = succeed(CHARGED_PARTICLE, &[], &reduced_dir);
    let (unreduced, _) = succeed(CHARGED_PARTICLE, &["method.reduced=false"], &unreduced_dir);
    assert_eq!(unreduced["method"]["reduced"], false);
    let (a, b) = (numbers(&reduced["final"]["q"]), numbers(&unreduced["final"]["q"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-10, "{a:?} vs {b:?}");
    }
}

#[test]
fn ten_steps_over_the_same_duration_reproduce_table_1_for_n_10() {
    let dir = TempDir::new("n10");
    let (summary, csv) = succeed(CHARGED_PARTICLE, &["time.steps=10"], &dir);
    assert_eq!(summary["step"].as_f64().unwrap(), 2.0);
    assert_eq!(csv.lines().count(), 12);
    // Paper, Table 1: 1.6781 for N = 10.
    assert_eq!(format!("{:.4}", reference_error(&summary)), "1.6781");
}

#[test]
fn double_spherical_pendulum_conserves_the_momentum_map() {
    let (dir, unreduced_dir) = (TempDir::new("dsp"), TempDir::new("dsp-unred"));
    let sets = ["time.steps=1000", "time.duration=10"];
    let (summary, csv) = succeed(PENDULUM, &sets, &dir);
    assert_eq!(summary["steps"], 1000);
    assert!(summary["reference_error"].is_null());
    assert_eq!(numbers(&summary["momentum_map"]["initial"]), vec![0.0]);
    // The momenta reach 10⁶ here. While both bobs are near the bottom the run is in a chart without
    // group coordinates, or where charts overlap (glued unreduced steps, `ddirac::blend`): there the
    // discrete Noether theorem conserves the momentum map as far as the step's L_d is invariant in
    // floating point — through the charts' maps — and the Newton tolerance allows (measured 6.9e-12 of
    // the momenta over these 1000 steps; 6e-15 when the charts were switched at a step instead of
    // glued); in a reduced step it is exact.
    assert!(summary["momentum_map"]["max_relative_drift"].as_f64().unwrap() <= 2e-11);
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,vartheta1,phi1,vartheta2,phi2,p_vartheta1,p_phi1,p_vartheta2,p_phi2,energy,discrete_energy,momentum_vartheta1,chart"
    );
    assert_eq!(lines.count(), 101, "every = 10 over 1000 steps, plus the initial row");
    // The reduced-then-reconstructed run follows the unreduced one.
    let (unreduced, _) = succeed(PENDULUM, &[&sets[..], &["method.reduced=false"]].concat(), &unreduced_dir);
    let (a, b) = (numbers(&summary["final"]["q"]), numbers(&unreduced["final"]["q"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-7, "{a:?} vs {b:?}");
    }
}

#[test]
fn default_output_directory_is_named_after_the_spec() {
    let dir = TempDir::new("default-out");
    let spec = dir.0.join("helix.toml");
    std::fs::copy(CHARGED_PARTICLE, &spec).unwrap();
    let output = ddirac(&["run", "helix.toml", "--set", "time.steps=10"], &dir.0);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("reference error  1.678"), "{stdout}");
    assert!(dir.0.join("out/helix/summary.json").exists());

    let output = ddirac(&["run", "helix.toml", "-q", "--set", "output.directory=\"elsewhere\""], &dir.0);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(dir.0.join("elsewhere/trajectory.csv").exists());
}

#[test]
fn systems_lists_every_built_in_with_its_defaults() {
    let output = ddirac(&["systems"], Path::new("."));
    assert!(output.status.success());
    let text = String::from_utf8_lossy(&output.stdout);
    for system in ddirac::systems::BUILT_IN {
        assert!(text.contains(system.name), "{text}");
        for (name, value) in (system.defaults)() {
            assert!(text.contains(&format!("{name} = {value}")), "{text}");
        }
    }
    assert!(text.contains("theta (group, angle)"), "{text}");
}

#[test]
fn unknown_keys_are_refused_at_their_span() {
    let dir = TempDir::new("unknown-key");
    assert_fails(
        &run(CHARGED_PARTICLE, &["method.tolerence=1e-9"], &dir),
        &dir,
        &["unknown field `tolerence`", "tolerence = 1e-9", "unknown key"],
    );
    let spec = edited_example(&dir, "[output]", "[outputs]");
    assert_fails(&run(&spec, &[], &dir), &dir, &["unknown field `outputs`", "[outputs]"]);
}

#[test]
fn wrong_sizes_and_non_finite_values_are_refused() {
    let dir = TempDir::new("sizes");
    assert_fails(
        &run(CHARGED_PARTICLE, &["initial.q=[0, 0, 0]"], &dir),
        &dir,
        &["`initial.q` has 3 entries, but the system has 4 coordinates", "q1, q2, q3, theta"],
    );
    assert_fails(&run(CHARGED_PARTICLE, &["initial.v=[1, 0, 1, 1]"], &dir), &dir, &["`p` or `v`, not both"]);
    let spec = edited_example(&dir, "q = [0.0, 0.0, 0.0, 0.0]", "q = [0.0, nan, 0.0, 0.0]");
    assert_fails(&run(&spec, &[], &dir), &dir, &["`initial.q` entry for `q2` is not finite (NaN)", "nan"]);
    assert_fails(&run(CHARGED_PARTICLE, &["parameters.B0=inf"], &dir), &dir, &["parameter `B0` is not finite"]);
}

#[test]
fn unknown_systems_parameters_and_rules_are_refused() {
    let dir = TempDir::new("names");
    assert_fails(
        &run(CHARGED_PARTICLE, &["system=pendulum_on_a_cart"], &dir),
        &dir,
        &["unknown system `pendulum_on_a_cart`", "charged_particle, double_spherical_pendulum, two_body"],
    );
    assert_fails(
        &run(CHARGED_PARTICLE, &["parameters.mass=2"], &dir),
        &dir,
        &["unknown parameter `mass` of system `charged_particle`", "known parameters: m (default 1), B0 (default 1)"],
    );
    assert_fails(&run(CHARGED_PARTICLE, &["parameters.m=-1"], &dir), &dir, &["parameter `m`", "must be positive"]);
    assert_fails(
        &run(CHARGED_PARTICLE, &["method.rule=simpson"], &dir),
        &dir,
        &["unknown rule `simpson`", "rule = \"simpson\"", "left, right, midpoint, trapezoid"],
    );
    assert_fails(&run(CHARGED_PARTICLE, &["method.variant=both"], &dir), &dir, &["unknown variant `both`"]);
}

#[test]
fn inconsistent_time_grids_are_refused() {
    let dir = TempDir::new("time");
    assert_fails(
        &run(CHARGED_PARTICLE, &["time.step=0.3"], &dir),
        &dir,
        &["inconsistent `[time]`: step × steps = 30", "duration = 20"],
    );
    let spec = edited_example(&dir, "steps = 100", "step = 0.3");
    assert_fails(&run(&spec, &[], &dir), &dir, &["is not a whole number of steps"]);
    let spec = edited_example(&dir, "steps = 100", "");
    assert_fails(&run(&spec, &[], &dir), &dir, &["needs two of `step`, `steps`, `duration`; found only `duration`"]);
    assert_fails(&run(CHARGED_PARTICLE, &["time.steps=0"], &dir), &dir, &["`time.steps` must be at least 1"]);
}

#[test]
fn malformed_set_arguments_are_refused_by_name() {
    let dir = TempDir::new("set");
    for (arg, why) in [
        ("method.reduced", "no `=`"),
        ("=false", "the key is empty"),
        ("system.name=x", "`system` is a string, not a table"),
        ("method=3", "`method` is a table"),
    ] {
        assert_fails(&run(CHARGED_PARTICLE, &[arg], &dir), &dir, &[&format!("malformed `--set {arg}`"), why]);
    }
}

#[test]
fn newton_failures_leave_earlier_finished_files_untouched() {
    let dir = TempDir::new("newton");
    let (_, finished) = succeed(CHARGED_PARTICLE, &[], &dir);
    let finished_summary = std::fs::read(dir.out().join("summary.json")).unwrap();
    let output = run(CHARGED_PARTICLE, &["method.max_iterations=1", "method.tolerance=1e-16"], &dir);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("Newton's method failed after 1 iteration(s): no convergence within the iteration limit"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap(), finished);
    assert_eq!(std::fs::read(dir.out().join("summary.json")).unwrap(), finished_summary);
    assert!(!dir.out().join(".trajectory.csv.partial").exists());

    let fresh = TempDir::new("newton-fresh");
    assert_fails(
        &run(CHARGED_PARTICLE, &["method.max_iterations=1", "method.tolerance=1e-16"], &fresh),
        &fresh,
        &["the integration failed", "Newton's method"],
    );
    assert!(!fresh.out().exists(), "a directory created for a failed run stays behind");
}

#[test]
fn connections_of_the_wrong_shape_are_refused() {
    let dir = TempDir::new("connection");
    assert_fails(
        &run(CHARGED_PARTICLE, &["method.connection=[[0, 0]]"], &dir),
        &dir,
        &["row 1 of `method.connection` has 2 entries, expected 3", "one row per group coordinate (theta)"],
    );
    assert_fails(
        &run(CHARGED_PARTICLE, &["method.connection=[[0, 0, 0], [0, 0, 0]]"], &dir),
        &dir,
        &["`method.connection` has 2 rows, expected 1"],
    );
}

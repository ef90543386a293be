//! `ddirac run SPEC --compare`: both runs written as ordinary runs, `compare.csv` equal to the
//! differences of their trajectories, reduced and unreduced flows agreeing to round-off for the
//! charged particle (paper §7.1), and a quiet stderr.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

use common::TempDir;

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");
const PENDULUM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/double_spherical_pendulum.toml");

fn compare(spec: &str, extra: &[&str], dir: &TempDir) -> Output {
    let out = dir.out();
    let mut args = vec!["run", spec, "--compare", "--out", out.to_str().unwrap()];
    args.extend(extra);
    Command::new(env!("CARGO_BIN_EXE_ddirac")).args(&args).current_dir(&dir.0).output().unwrap()
}

/// A CSV file as its header and rows of optional numbers.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows = lines.map(|l| l.split(',').map(|v| (!v.is_empty()).then(|| v.parse().unwrap())).collect()).collect();
    (header, rows)
}

fn summary(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path.join("summary.json")).unwrap()).unwrap()
}

/// Checks compare.csv against the two trajectories; returns the largest |difference| of q and L_d.
fn check_table(out: &Path, coordinates: &[&str]) -> (f64, f64) {
    let (header, rows) = csv(&out.join("compare.csv"));
    let expected: Vec<String> = std::iter::once("t".to_owned())
        .chain(coordinates.iter().map(|c| format!("d_{c}")))
        .chain(["d_discrete_energy".to_owned()])
        .collect();
    assert_eq!(header, expected);
    let (names, reduced) = csv(&out.join("reduced/trajectory.csv"));
    let (_, unreduced) = csv(&out.join("unreduced/trajectory.csv"));
    assert_eq!(rows.len(), reduced.len());
    let column = |name: &str| names.iter().position(|n| n == name).unwrap();
    let (mut max_q, mut max_ld) = (0.0f64, 0.0f64);
    for ((row, r), u) in rows.iter().zip(&reduced).zip(&unreduced) {
        assert_eq!(row[0], r[column("t")]);
        for (i, c) in coordinates.iter().enumerate() {
            let d = r[column(c)].unwrap() - u[column(c)].unwrap();
            assert_eq!(row[1 + i], Some(d), "d_{c} at t = {:?}", row[0]);
            max_q = max_q.max(d.abs());
        }
        let ld = column("discrete_energy");
        let d = r[ld].zip(u[ld]).map(|(a, b)| a - b);
        assert_eq!(row[1 + coordinates.len()], d);
        max_ld = max_ld.max(d.map_or(0.0, f64::abs));
    }
    (max_q, max_ld)
}

#[test]
fn charged_particle_reduced_and_unreduced_agree_to_round_off() {
    let dir = TempDir::new("charged");
    let output = compare(CHARGED_PARTICLE, &[], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let out = dir.out();
    let (reduced, unreduced) = (summary(&out.join("reduced")), summary(&out.join("unreduced")));
    assert_eq!(reduced["method"]["reduced"], true);
    assert_eq!(unreduced["method"]["reduced"], false);
    assert_eq!(reduced["steps"], unreduced["steps"]);
    assert_eq!(reduced["method"]["rule"], unreduced["method"]["rule"]);

    let (max_q, max_ld) = check_table(&out, &["q1", "q2", "q3", "theta"]);
    assert!(max_q <= 1e-10 && max_ld <= 1e-10, "differences {max_q:e}, {max_ld:e}");
    // Both runs reproduce Table 1, N = 100.
    for s in [&reduced, &unreduced] {
        assert!((s["reference_error"].as_f64().unwrap() - 0.06626).abs() < 5e-6);
    }

    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("unreduced / reduced ="), "{stdout}");
    assert!(stdout.contains("max |difference|") && stdout.contains("theta"), "{stdout}");
    for file in ["compare.png", "compare.svg"] {
        assert!(std::fs::metadata(out.join(file)).unwrap().len() > 1000, "{file}");
    }
    let svg = std::fs::read_to_string(out.join("compare.svg")).unwrap();
    assert!(svg.contains("ΔL_d") && svg.contains("discrete energy, reduced − unreduced"));
    assert!(output.stderr.is_empty(), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn pendulum_differences_stay_at_round_off_level_amplified_by_the_pole() {
    // Paper §7.2: the reduced and unreduced discrete energies agree; the passage near the pole
    // amplifies round-off, so the bound is loose but far below the motion's own scale.
    let dir = TempDir::new("pendulum");
    // In the paper's chart (with the atlas, both runs take the same glued unreduced steps where the
    // bobs are, and agree bit for bit).
    let sets = ["--quiet", "--set", "time.steps=2000", "--set", "time.duration=20", "--set", "method.atlas=false"];
    let output = compare(PENDULUM, &sets, &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.stdout.is_empty() && output.stderr.is_empty(), "--quiet printed something");
    let (max_q, max_ld) = check_table(&dir.out(), &["vartheta1", "phi1", "vartheta2", "phi2"]);
    assert!(max_q < 1e-6 && max_ld < 1e-4, "differences {max_q:e}, {max_ld:e}");
    assert!(max_q > 0.0, "two different schemes cannot agree bit for bit over 2000 steps");
}

#[test]
fn plots_of_both_runs_are_drawn_when_the_spec_asks() {
    let dir = TempDir::new("plots");
    let output = compare(CHARGED_PARTICLE, &["--quiet", "--set", "output.plots=true"], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    for run in ["reduced", "unreduced"] {
        assert!(dir.out().join(run).join("coordinates.png").exists(), "{run}");
    }
}

#[test]
fn a_failed_comparison_leaves_no_directories() {
    let dir = TempDir::new("failed");
    // A Newton iteration limit of 1 stops the first (reduced) run.
    let output = compare(CHARGED_PARTICLE, &["--set", "method.max_iterations=1"], &dir);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("reduced run failed"), "{stderr}");
    assert!(!dir.out().exists(), "the output directory was left behind");
}

#[test]
fn no_progress_bar_when_stderr_is_not_a_terminal() {
    let dir = TempDir::new("progress");
    // 2 × 300 000 steps: over a second, when a terminal would show the bar.
    let output = compare(CHARGED_PARTICLE, &["--set", "time.steps=300000", "--set", "output.every=1000"], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    for mark in ["\r", "\x1b[", "steps/s", "█", "░"] {
        assert!(!stderr.contains(mark), "progress output on a pipe: {stderr:?}");
    }
}

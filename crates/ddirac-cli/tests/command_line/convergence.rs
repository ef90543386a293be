//! `ddirac convergence`: the paper's Table 1 for the charged particle, a finer reference run for a
//! system without exact solution, the refusal of a study that cannot be made, and a quiet stderr.

use crate::common;

use common::{ddirac, TempDir};

use std::process::Output;

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");
const PENDULUM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/double_spherical_pendulum.toml");

/// Paper, Table 1: ‖q(T) − q_N‖ for N = 10, 50, 100, 200, with the digits printed there.
const TABLE_1: [(u64, f64, f64); 4] =
    [(10, 1.6781, 5e-5), (50, 0.25971, 5e-6), (100, 0.06626, 5e-6), (200, 0.01664, 5e-6)];

fn convergence(spec: &str, steps: &str, extra: &[&str], dir: &TempDir) -> Output {
    let out = dir.out();
    let mut args = vec!["convergence", spec, "--steps", steps, "--out", out.to_str().unwrap()];
    args.extend(extra);
    ddirac(&args, &dir.0)
}

/// The rows of convergence.csv: (N, h, error, order).
fn table(dir: &TempDir) -> Vec<(u64, f64, Option<f64>, Option<f64>)> {
    let text = std::fs::read_to_string(dir.out().join("convergence.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("steps,step,error,order,wall_seconds,reference"));
    let number = |s: &str| (!s.is_empty()).then(|| s.parse::<f64>().unwrap());
    lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            (f[0].parse().unwrap(), f[1].parse().unwrap(), number(f[2]), number(f[3]))
        })
        .collect()
}

#[test]
fn charged_particle_reproduces_table_1_of_the_paper() {
    let dir = TempDir::new("table1");
    let output = convergence(CHARGED_PARTICLE, "200,10,100,50", &[], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let rows = table(&dir);
    assert_eq!(rows.len(), 4);
    for ((n, h, error, _), (paper_n, paper, digits)) in rows.iter().zip(TABLE_1) {
        assert_eq!(*n, paper_n, "rows are sorted by N");
        assert!((h - 20.0 / paper_n as f64).abs() < 1e-15, "h = {h} for N = {n}");
        let error = error.unwrap();
        assert!((error - paper).abs() <= digits, "N = {n}: error {error}, paper {paper}");
    }
    // Second order: the slopes between the finer rows approach 2.
    for (n, _, _, order) in &rows[2..] {
        let order = order.unwrap();
        assert!((order - 2.0).abs() < 0.05, "N = {n}: order {order}");
    }
    assert_eq!(rows[0].3, None, "the first row has no order");

    // The printed table: N, h, error (five significant digits), order.
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("against the exact solution"), "{stdout}");
    let printed: Vec<Vec<&str>> = stdout
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|f| f.first().is_some_and(|n| n.parse::<u64>().is_ok()))
        .collect();
    assert_eq!(printed.len(), 4, "{stdout}");
    for (row, (n, paper, digits)) in printed.iter().zip(TABLE_1) {
        assert_eq!(row[0], n.to_string());
        let error: f64 = row[2].parse().unwrap();
        assert!((error - paper).abs() <= digits, "printed {error} for N = {n}, paper {paper}\n{stdout}");
    }
    assert_eq!((printed[2][3], printed[3][3]), ("1.97", "1.99"), "{stdout}");
    for file in ["convergence.png", "convergence.svg"] {
        assert!(std::fs::metadata(dir.out().join(file)).unwrap().len() > 1000, "{file}");
    }
    let svg = std::fs::read_to_string(dir.out().join("convergence.svg")).unwrap();
    assert!(svg.contains("step h") && svg.contains("‖q_N − q(T)‖"), "axis names missing");
}

/// The final configuration (of the pendulum's four coordinates) of one `ddirac run` with N steps.
fn final_q(spec: &str, steps: u64, sets: &[&str], dir: &TempDir) -> Vec<f64> {
    let out = dir.0.join(format!("run{steps}"));
    let n = format!("time.steps={steps}");
    let mut args = vec!["run", spec, "--out", out.to_str().unwrap(), "--quiet", "--set", &n];
    for s in sets {
        args.extend(["--set", s]);
    }
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    // The last row of the trajectory (numbers written to round-trip, read with Rust's exact parser).
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let last = csv.lines().last().unwrap();
    last.split(',').skip(1).take(4).map(|v| v.parse().unwrap()).collect()
}

#[test]
fn without_an_exact_solution_the_errors_are_against_a_finer_reference_run() {
    let dir = TempDir::new("reference");
    let sets = ["--set", "time.duration=2"];
    let output = convergence(PENDULUM, "100,200,400,800", &sets, &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let rows = table(&dir);
    assert_eq!(rows.iter().map(|r| r.0).collect::<Vec<_>>(), [100, 200, 400, 800]);
    // Every error is the distance between the final configurations of two ordinary runs: the row's
    // and the reference run's, 8 × 800 steps.
    let reference = final_q(PENDULUM, 6400, &["time.duration=2"], &dir);
    for &(n, _, error, _) in &rows {
        let q = final_q(PENDULUM, n, &["time.duration=2"], &dir);
        let distance = q.iter().zip(&reference).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
        let error = error.unwrap();
        assert!((error - distance).abs() <= 1e-9 * distance, "N = {n}: table {error}, runs {distance}");
    }
    // The midpoint rule is second order, and every row shows it.
    for (n, _, _, order) in &rows[1..] {
        let order = order.unwrap();
        assert!((order - 2.0).abs() < 0.05, "N = {n}: order {order}");
    }
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("against a reference run") && stdout.contains("N = 6400"), "{stdout}");
    assert!(stdout.contains("its own error"), "{stdout}");
}

#[test]
fn one_step_count_without_an_exact_solution_is_refused() {
    let dir = TempDir::new("single");
    let output = convergence(PENDULUM, "100", &["--set", "time.duration=1"], &dir);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("no exact solution") && stderr.contains("at least two"), "{stderr}");
    assert!(!dir.out().join("convergence.csv").exists());
}

#[test]
fn a_step_count_of_zero_is_refused_by_the_command_line() {
    let dir = TempDir::new("zero");
    let output = convergence(CHARGED_PARTICLE, "0,10", &[], &dir);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--steps"));
}

#[test]
fn no_progress_bar_when_stderr_is_not_a_terminal() {
    let dir = TempDir::new("quiet");
    // Long enough (600 000 steps, over a second) for a bar to appear on a terminal.
    let steps = "40000,80000,160000,320000";
    let output = convergence(CHARGED_PARTICLE, steps, &["--quiet"], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.stdout.is_empty() && output.stderr.is_empty(), "--quiet printed something");
    let output = convergence(CHARGED_PARTICLE, steps, &[], &dir);
    assert!(output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    for mark in ["\r", "\x1b[", "steps/s", "█", "░"] {
        assert!(!stderr.contains(mark), "progress output on a pipe: {stderr:?}");
    }
    assert!(!String::from_utf8_lossy(&output.stdout).contains("steps/s"));
}

/// `method.order` = 4, 6, 8 on the charged particle (midpoint rule): the observed orders of the
/// table are those of the compositions, as Table 1 shows order 2 for the basic step. The rows are
/// chosen in the asymptotic range and above round-off (order 8 reaches 1e-11 at N = 100).
#[test]
fn charged_particle_shows_the_orders_of_the_compositions() {
    for (order, steps) in [(4, "50,100,200,400"), (6, "50,100,200,400"), (8, "28,40,56,80")] {
        let dir = TempDir::new(&format!("composition{order}"));
        let set_order = format!("method.order={order}");
        let output =
            convergence(CHARGED_PARTICLE, steps, &["--set", "method.rule=midpoint", "--set", &set_order], &dir);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let stdout = String::from_utf8(output.stdout).unwrap();
        assert!(stdout.contains(&format!("order {order} (")), "the header names the composition: {stdout}");
        let rows = table(&dir);
        for (n, _, _, observed) in &rows[1..] {
            let observed = observed.unwrap();
            assert!(
                (observed - f64::from(order)).abs() < 0.15,
                "order {order}, N = {n}: observed {observed}\n{stdout}"
            );
        }
    }
}

//! The exact motion beside a run: `exact.csv` at the times of the trajectory's rows, and the figures
//! that draw it under the computed lines (the paper's §7.1 figure: exact against computed
//! charged-particle trajectory at h = 0.2).

use crate::common;

use common::{ddirac, example, run, TempDir};

/// The rows of a CSV file as numbers (empty fields as NaN), after its header.
fn table(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows = lines.map(|l| l.split(',').map(|f| f.parse().unwrap_or(f64::NAN)).collect()).collect();
    (header, rows)
}

/// The texts of an SVG: what plotters writes between `<text …>` and `</text>`.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.trim().to_owned()))
        .collect()
}

#[test]
fn a_run_of_the_charged_particle_writes_the_exact_gyration_at_the_rows_of_its_trajectory() {
    let dir = TempDir::new("exact");
    let output = run(&example("charged_particle.toml"), &["output.every=7"], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let (header, exact) = table(&dir.out().join("exact.csv"));
    assert_eq!(header, ["t", "q1", "q2", "q3"]);
    let (_, trajectory) = table(&dir.out().join("trajectory.csv"));
    assert_eq!(exact.len(), trajectory.len());
    // B = e₃, q0 = 0, v0 = (1, 0, 1): the gyration q1 = sin t, q2 = cos t − 1, q3 = t (paper §7.1).
    for (row, traj) in exact.iter().zip(&trajectory) {
        let t = row[0];
        assert_eq!(t, traj[0]);
        let expected = [t.sin(), t.cos() - 1.0, t];
        for (got, want) in row[1..].iter().zip(expected) {
            assert!((got - want).abs() < 1e-14, "t = {t}: {got} against {want}");
        }
    }
    // The computed trajectory is first order here (left rule, h = 0.2): near, not equal.
    let last = (exact.last().unwrap(), trajectory.last().unwrap());
    let error = (1..4).map(|i| (last.0[i] - last.1[i]).abs()).fold(0.0, f64::max);
    assert!(error > 1e-3 && error < 0.2, "error at T: {error}");
}

#[test]
fn plot_draws_the_exact_motion_under_the_computed_one() {
    let dir = TempDir::new("exact-figures");
    let output = run(&example("charged_particle.toml"), &["output.plots=true"], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let coordinates = std::fs::read_to_string(dir.out().join("coordinates.svg")).unwrap();
    let legend = texts(&coordinates);
    assert_eq!(legend.iter().filter(|t| *t == "exact").count(), 3, "one entry per q1, q2, q3: {legend:?}");
    assert_eq!(legend.iter().filter(|t| *t == "computed").count(), 3, "{legend:?}");
    let path = texts(&std::fs::read_to_string(dir.out().join("exact_path.svg")).unwrap());
    assert!(path.iter().any(|t| t.ends_with("path in the (q1, q2) plane, computed and exact")), "{path:?}");
    assert!(dir.out().join("exact_path.png").exists());
}

#[test]
fn a_system_without_an_exact_solution_writes_no_exact_file_and_no_exact_figure() {
    let dir = TempDir::new("no-exact");
    let output = run(
        &example("double_spherical_pendulum.toml"),
        &["time.steps=100", "time.duration=1", "output.plots=true"],
        &dir,
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(!dir.out().join("exact.csv").exists());
    assert!(!dir.out().join("exact_path.svg").exists());
    let out = dir.out();
    let listed = ddirac(&["plot", out.to_str().unwrap()], &dir.0);
    assert!(String::from_utf8_lossy(&listed.stdout).contains("6 figures"));
}

//! A rerun into a directory kept the earlier run's files (CSV, `npy/`, figures), and `ddirac plot`
//! then drew the old CSV under the new run's title. On success a directory now holds exactly the
//! files of its last run: the earlier run's files are replaced as a set; a failed rerun leaves the
//! earlier set as it was; files that ddirac did not write are never touched.

use crate::common;

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Output;

use common::{ddirac, example, files_under, TempDir};

/// Every file under `dir`, as paths relative to it.
fn files(dir: &Path) -> BTreeSet<String> {
    files_under(dir)
}

fn run(dir: &TempDir, args: &[&str]) -> Output {
    let out = dir.out();
    let spec = example("charged_particle.toml");
    ddirac(&[&["run", &spec, "--out", out.to_str().unwrap(), "--quiet"][..], args].concat(), &dir.0)
}

fn succeed(dir: &TempDir, args: &[&str]) {
    let output = run(dir, args);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}

const FIGURES: [&str; 8] = [
    "coordinates.png",
    "coordinates.svg",
    "energy_error.png",
    "energy_error.svg",
    "momentum_map.png",
    "momentum_map.svg",
    "discrete_energy.png",
    "discrete_energy.svg",
];

#[test]
fn a_rerun_with_fewer_formats_leaves_no_npy_and_no_figures_of_the_earlier_run() {
    let dir = TempDir::new("rerun");
    let out = dir.out();
    succeed(&dir, &["--format", "csv,npy", "--set", "output.plots=true"]);
    let first = files(&out);
    assert!(first.contains("npy/q1.npy") && first.contains("coordinates.png"), "{first:?}");
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    std::fs::write(out.join("npy/mine.npy"), "mine").unwrap();

    succeed(&dir, &["--format", "csv", "--set", "time.steps=50"]);
    let second = files(&out);
    let expected: BTreeSet<String> =
        [".ddirac-files", "summary.json", "trajectory.csv", "exact.csv", "notes.txt", "npy/mine.npy"]
            .map(String::from)
            .into();
    assert_eq!(second, expected, "the earlier run's files are left beside the new ones");
    assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
    let rows = std::fs::read_to_string(out.join("trajectory.csv")).unwrap().lines().count();
    assert_eq!(rows, 51 + 1, "the CSV is the new run's");

    // Without the file of its own, `npy/` goes with the earlier run's columns.
    std::fs::remove_file(out.join("npy/mine.npy")).unwrap();
    succeed(&dir, &["--format", "npy"]);
    succeed(&dir, &["--format", "csv"]);
    assert!(!out.join("npy").exists());
}

#[test]
fn a_rerun_without_csv_leaves_no_csv_for_plot_to_read() {
    let dir = TempDir::new("no-csv");
    let out = dir.out();
    succeed(&dir, &["--set", "time.steps=100"]);
    succeed(&dir, &["--format", "npy", "--set", "time.steps=30"]);
    assert!(!out.join("trajectory.csv").exists(), "plot would read the earlier run's CSV");
    // `ddirac plot` draws the new run, and its figures belong to the run: the next run removes them.
    let output = ddirac(&["plot", out.to_str().unwrap(), "--quiet"], &dir.0);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(out.join("coordinates.png").exists());
    succeed(&dir, &["--format", "csv"]);
    let left = files(&out);
    assert!(FIGURES.iter().all(|f| !left.contains(*f)), "figures of the earlier run are left: {left:?}");
}

#[test]
fn a_failed_rerun_leaves_the_earlier_set_as_it_was() {
    let dir = TempDir::new("failed");
    let out = dir.out();
    succeed(&dir, &["--format", "csv,npy", "--set", "output.plots=true"]);
    let before: Vec<(String, Vec<u8>)> =
        files(&out).into_iter().map(|f| (f.clone(), std::fs::read(out.join(&f)).unwrap())).collect();
    assert!(before.iter().any(|(f, _)| f == "coordinates.svg"));
    let output = run(&dir, &["--format", "csv", "--set", "method.max_iterations=1", "--set", "method.tolerance=1e-16"]);
    assert_eq!(output.status.code(), Some(3), "{}", String::from_utf8_lossy(&output.stderr));
    let after: Vec<(String, Vec<u8>)> =
        files(&out).into_iter().map(|f| (f.clone(), std::fs::read(out.join(&f)).unwrap())).collect();
    assert_eq!(after.len(), before.len());
    for ((a, a_bytes), (b, b_bytes)) in after.iter().zip(&before) {
        assert_eq!(a, b);
        assert!(a_bytes == b_bytes, "{a} changed");
    }
}

//! Two runs into one directory (a sweep without `--out`) wrote the same temporary file: one exited 0
//! with NUL bytes and the rows of both runs in trajectory.csv, the other failed with "No such file
//! or directory". A run now owns its directory while it lasts: the second fails at once with a
//! message naming the first, and the first writes an intact CSV.

use crate::common;

use std::process::{Command, Stdio};

use common::{example, TempDir};

const STEPS: usize = 60_000;
const EVERY: usize = 3;

#[test]
fn of_two_runs_into_one_directory_one_succeeds_intact_and_the_other_names_it() {
    let dir = TempDir::new("two-runs");
    let out = dir.out();
    let spawn = |step: f64| {
        Command::new(env!("CARGO_BIN_EXE_ddirac"))
            .args(["run", &example("pendulum_chain.toml"), "--out", out.to_str().unwrap(), "--quiet"])
            .args(["--set", &format!("time.step={step}"), "--set", &format!("time.duration={}", step * STEPS as f64)])
            .args(["--set", &format!("output.every={EVERY}")])
            .current_dir(&dir.0)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    // Two different step sizes: the rows of one run cannot pass for those of the other.
    let (a, b) = (spawn(0.005), spawn(0.004));
    let (a_pid, b_pid) = (a.id(), b.id());
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    let (winner, loser, winner_step, winner_pid) = match (a.status.success(), b.status.success()) {
        (true, false) => (a, b, 0.005, a_pid),
        (false, true) => (b, a, 0.004, b_pid),
        _ => panic!(
            "exactly one run must succeed: {:?} / {:?}\n{}\n{}",
            a.status,
            b.status,
            String::from_utf8_lossy(&a.stderr),
            String::from_utf8_lossy(&b.stderr)
        ),
    };
    assert!(winner.stderr.is_empty(), "{}", String::from_utf8_lossy(&winner.stderr));
    let stderr = String::from_utf8_lossy(&loser.stderr);
    assert!(
        stderr.contains(&format!("the output directory `{}` is in use by another ddirac run", out.display())),
        "{stderr}"
    );
    assert!(stderr.contains(&format!("pid {winner_pid}")), "the message does not name the other run: {stderr}");
    assert!(stderr.contains("pendulum_chain.toml"), "the message does not name the other spec: {stderr}");
    assert_eq!(loser.status.code(), Some(4), "{stderr}");

    // The CSV is the winner's, whole: a header, one row every EVERY steps and the last, t = k h.
    let bytes = std::fs::read(out.join("trajectory.csv")).unwrap();
    assert!(!bytes.contains(&0), "NUL bytes in trajectory.csv");
    let text = String::from_utf8(bytes).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "t");
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|f| f.parse::<f64>().unwrap_or(f64::NAN)).collect()).collect();
    assert_eq!(rows.len(), STEPS / EVERY + 1);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len(), "row {i}");
        let expected = (i * EVERY) as f64 * winner_step;
        assert!((row[0] - expected).abs() <= 1e-9 * expected.max(1.0), "row {i}: t = {} ≠ {expected}", row[0]);
        let last = i == rows.len() - 1;
        for (name, value) in header.iter().zip(row) {
            assert!(value.is_finite() || (last && *name == "discrete_energy"), "row {i}: {name} = {value}");
        }
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["step"], winner_step);

    // Nothing else stays behind: no temporary, no lock.
    let mut left: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    left.sort();
    assert_eq!(left, [".ddirac-files", "summary.json", "trajectory.csv"]);
}

#[test]
fn the_lock_and_the_temporaries_of_a_killed_run_are_taken_over() {
    // What a run killed with SIGKILL leaves: its lock file (the lock itself died with it) and its
    // staging directory.
    let dir = TempDir::new("stale");
    let out = dir.out();
    std::fs::create_dir_all(out.join(".ddirac-999999-0.partial/npy")).unwrap();
    std::fs::write(out.join(".ddirac-999999-0.partial/trajectory.csv"), "t,x\n0,").unwrap();
    std::fs::write(out.join(".ddirac.lock"), "pid = 999999\ncommand = \"ddirac run old.toml\"\nstarted = 1\n").unwrap();
    std::fs::write(out.join(".ddirac-files.999999-3.partial"), "trajectory.csv\n").unwrap();
    std::fs::write(out.join(".ddirac-notes.partial"), "not ddirac's").unwrap();
    let finished = common::succeed(&example("charged_particle.toml"), &[], &dir);
    assert_eq!(finished.column("t").len(), 101);
    let mut left: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    left.sort();
    assert_eq!(left, [".ddirac-files", ".ddirac-notes.partial", "exact.csv", "summary.json", "trajectory.csv"]);
}

//! SIGINT, SIGTERM and SIGHUP killed a run silently and left its hidden `.partial` files (10–14 MB)
//! behind. A run now stops, removes its temporary files and its lock, says so, and exits with
//! 128 + the signal's number — promptly even when it writes a row only every 10⁹ steps.
#![cfg(unix)]

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{example, TempDir};

/// Names under `dir` (recursively) that a run leaves only while it lasts.
fn temporaries(dir: &Path) -> Vec<String> {
    let mut found = vec![];
    let Ok(entries) = std::fs::read_dir(dir) else { return found };
    for entry in entries {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.contains(".partial") || name.contains(".lock") {
            found.push(name);
        }
        if path.is_dir() {
            found.extend(temporaries(&path));
        }
    }
    found
}

/// Starts a long run of the pendulum chain (10⁷ steps) into `dir.out()`, waits until its temporary
/// files exist, sends `signal` and returns the exit code, stderr and the seconds to exit.
fn interrupt(dir: &TempDir, signal: i32, every: u64) -> (Option<i32>, String, f64) {
    let out = dir.out();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["run", &example("pendulum_chain.toml"), "--out", out.to_str().unwrap(), "--quiet"])
        .args(["--set", "time.duration=50000", "--set", &format!("output.every={every}")])
        .current_dir(&dir.0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while temporaries(&out).iter().all(|n| !n.contains(".partial")) {
        assert!(started.elapsed() < Duration::from_secs(60), "no temporary file appeared");
        assert!(child.try_wait().unwrap().is_none(), "the run ended before it was interrupted");
        std::thread::sleep(Duration::from_millis(20));
    }
    // Well into the steps.
    std::thread::sleep(Duration::from_millis(300));
    // SAFETY: kill(2) on the id of a child process this test started and has not reaped yet.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
    let sent = Instant::now();
    let output = child.wait_with_output().unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned(), sent.elapsed().as_secs_f64())
}

#[test]
fn sigint_stops_the_run_removes_its_temporaries_and_exits_130() {
    let dir = TempDir::new("sigint");
    let (code, stderr, _) = interrupt(&dir, libc::SIGINT, 5);
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("interrupted by SIGINT"), "{stderr}");
    assert!(stderr.contains("no output written"), "{stderr}");
    assert!(!dir.out().exists(), "the directory made for the run stays: {:?}", temporaries(&dir.out()));
}

#[test]
fn sigterm_stops_a_run_that_reports_no_row_promptly_and_keeps_the_earlier_files() {
    let dir = TempDir::new("sigterm");
    let finished = common::succeed(&example("pendulum_chain.toml"), &[], &dir);
    let csv = std::fs::read(dir.out().join("trajectory.csv")).unwrap();
    assert_eq!(finished.column("t").len(), 1201);

    // One row at the start, the next one 10⁹ steps later: no row to stop at.
    let (code, stderr, seconds) = interrupt(&dir, libc::SIGTERM, 1_000_000_000);
    assert_eq!(code, Some(143), "{stderr}");
    assert!(stderr.contains("interrupted by SIGTERM"), "{stderr}");
    assert!(seconds < 3.0, "the run took {seconds:.1} s to stop");
    assert_eq!(temporaries(&dir.out()), Vec::<String>::new());
    assert_eq!(std::fs::read(dir.out().join("trajectory.csv")).unwrap(), csv, "the earlier run's CSV changed");
}

#[test]
fn sighup_exits_129() {
    let dir = TempDir::new("sighup");
    let (code, stderr, _) = interrupt(&dir, libc::SIGHUP, 5);
    assert_eq!(code, Some(129), "{stderr}");
    assert!(stderr.contains("interrupted by SIGHUP"), "{stderr}");
    assert!(!dir.out().exists());
}

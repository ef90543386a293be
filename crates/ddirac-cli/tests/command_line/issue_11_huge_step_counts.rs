//! `time.step = 1e-300` saturated the step count silently (the run started, writing gigabytes), and
//! `time.steps = 10¹²` started without a word about the ~240 TB it would write. A step count beyond
//! 2⁵³ is now a spec error at the `[time]` keys; a run whose output would not fit in the free space
//! is refused at `[time]` unless `output.every` thins it; a large run says how large it is first.

use crate::common;

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{underlined, TempDir};

fn oscillator(dir: &TempDir, time: &str) -> String {
    dir.file(
        "spec.toml",
        &format!(
            "[system]\nshape = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\n[time]\n{time}\n[initial]\nq = [1.0]\np = [0.0]\n"
        ),
    )
}

fn spawn(spec: &str, args: &[&str], dir: &TempDir) -> Child {
    Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["run", spec, "--out", dir.out().to_str().unwrap()])
        .args(args)
        .current_dir(&dir.0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits at most 10 s for `child` (a run that would write for hours is killed) and returns its exit
/// code, or None if it had to be killed, with its stderr.
fn finish(mut child: Child) -> (Option<i32>, String) {
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > Duration::from_secs(10) {
            child.kill().unwrap();
            let output = child.wait_with_output().unwrap();
            return (None, String::from_utf8_lossy(&output.stderr).into_owned());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = child.wait_with_output().unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn a_step_count_beyond_2_53_is_refused_at_the_time_keys() {
    let dir = TempDir::new("tiny-step");
    let spec = oscillator(&dir, "step = 1e-300\nduration = 20.0");
    let (code, stderr) = finish(spawn(&spec, &["--quiet"], &dir));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("`[time]` asks for 2.000e301 steps, more than the 9007199254740992 (2^53)"), "{stderr}");
    assert_eq!(underlined(&stderr, "step = 1e-300"), ["1e-300"]);
    assert_eq!(underlined(&stderr, "duration = 20.0"), ["20.0"]);
    assert!(!stderr.contains("0.0000000000"), "a number is written with all its zeros:\n{stderr}");
    assert!(!dir.out().exists());

    let spec = oscillator(&dir, "steps = 9007199254740993\nduration = 1.0");
    let (code, stderr) = finish(spawn(&spec, &["--quiet"], &dir));
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(underlined(&stderr, "steps = "), ["9007199254740993"]);
}

#[test]
fn an_output_larger_than_the_free_space_is_refused_unless_thinned() {
    // 10¹² rows of 5 columns: about 100 TB of CSV.
    let dir = TempDir::new("huge");
    let spec = oscillator(&dir, "steps = 1000000000000\nduration = 1000000.0");
    let (code, stderr) = finish(spawn(&spec, &["--quiet"], &dir));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains(
            "the output of this run would not fit: about 100 TB (1.0e12 rows of 5 columns: trajectory.csv ≈ 100 TB)"
        ),
        "{stderr}"
    );
    assert!(stderr.contains("are free where"), "{stderr}");
    assert!(stderr.contains("output.every = "), "no way out is suggested:\n{stderr}");
    assert_eq!(underlined(&stderr, "steps = "), ["1000000000000"]);
    assert_eq!(underlined(&stderr, "duration = "), ["1000000.0"]);
    assert!(!dir.out().exists());

    // A row every 10¹¹ steps: 11 rows, accepted (and interrupted: it would take days).
    let child = spawn(&spec, &["--quiet", "--set", "output.every=100000000000"], &dir);
    std::thread::sleep(Duration::from_millis(1500));
    assert!(dir.out().exists(), "the thinned run did not start");
    // SAFETY: kill(2) on the id of a child process this test started and has not reaped yet.
    #[cfg(unix)]
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
    let (code, stderr) = finish(child);
    #[cfg(unix)]
    assert_eq!(code, Some(130), "{stderr}");
}

#[test]
fn a_run_of_more_than_a_gigabyte_says_so_before_it_starts() {
    // The estimate is printed before the first step.
    let dir = TempDir::new("notice");
    let spec = oscillator(&dir, "steps = 100000000000\nduration = 100000.0");
    let mut child = spawn(&spec, &["--format", "csv,npy", "--set", "output.every=10000"], &dir);
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let reader = std::thread::spawn(move || {
        let mut line = String::new();
        stderr.read_line(&mut line).unwrap();
        line
    });
    let started = Instant::now();
    while !reader.is_finished() && started.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    let line = if reader.is_finished() { reader.join().unwrap() } else { String::new() };
    // 10⁷ + 1 rows × 5 columns × (20 B of CSV + 8 B of npy) = 1.4 GB; refused instead where the
    // disk has less room than that.
    if line.contains("are free where") {
        eprintln!("a_run_of_more_than_a_gigabyte_says_so_before_it_starts: less than 1.4 GB free, refused");
        return;
    }
    assert!(
        line.starts_with("ddirac: this run writes about 1.4 GB to")
            && line.contains("1.0e7 rows of 5 columns: trajectory.csv ≈ 1.0 GB, npy/ ≈ 400 MB"),
        "{line}"
    );
}

//! Two commands into one directory must not mix their files: `ddirac convergence` owns its output
//! directory while it lasts, as `ddirac run` does, and writes its table and figures as one set.

use crate::common;

use std::process::{Command, Stdio};

use common::{example, TempDir};

#[test]
fn a_convergence_study_into_a_directory_in_use_is_refused_and_writes_nothing() {
    let dir = TempDir::new("convergence-lock");
    let out = dir.out();
    // A run long enough to hold the directory while the study starts.
    let mut long = Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["run", &example("pendulum_chain.toml"), "--out", out.to_str().unwrap(), "--quiet"])
        .args(["--set", "time.step=0.001", "--set", "time.duration=2000.0", "--set", "output.every=1000"])
        .current_dir(&dir.0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while !out.join(".ddirac.lock").exists() {
        assert!(started.elapsed().as_secs() < 60, "the run never locked its directory");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let study = Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["convergence", &example("kepler.toml"), "--steps", "50,100", "--out", out.to_str().unwrap(), "--quiet"])
        .current_dir(&dir.0)
        .output()
        .unwrap();
    long.kill().unwrap();
    let _ = long.wait();
    let stderr = String::from_utf8_lossy(&study.stderr);
    assert_eq!(study.status.code(), Some(4), "{stderr}");
    assert!(stderr.contains("is in use by another ddirac run"), "{stderr}");
    assert!(!out.join("convergence.csv").exists());

    // Once the directory is free, the study writes its table and figures, and nothing else stays.
    let study = Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["convergence", &example("kepler.toml"), "--steps", "50,100", "--out", out.to_str().unwrap(), "--quiet"])
        .current_dir(&dir.0)
        .output()
        .unwrap();
    assert!(study.status.success(), "{}", String::from_utf8_lossy(&study.stderr));
    let mut listed: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    listed.sort();
    assert_eq!(listed, [".ddirac-files", "convergence.csv", "convergence.png", "convergence.svg"]);
}

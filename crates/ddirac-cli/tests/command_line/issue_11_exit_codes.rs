//! Every failure exited 1, and `--help` said only "Command-line front end of ddirac". The exit
//! status now tells the kind of failure — 2 a wrong spec or command line, 3 a failed integration,
//! 4 a file that cannot be read or written or a directory in use, 128 + n a signal (see
//! issue_11_signal_leaves_no_partial_files.rs) — and the help describes every command with
//! examples and the statuses.

use crate::common;

use common::{check, ddirac, example, run, TempDir};

fn code(output: &std::process::Output) -> Option<i32> {
    output.status.code()
}

#[test]
fn a_wrong_spec_or_command_line_exits_2() {
    let dir = TempDir::new("spec");
    let cp = example("charged_particle.toml");
    for output in [
        run(&cp, &["method.rule=\"sideways\""], &dir),
        run(&cp, &["time.steps=0"], &dir),
        run(&cp, &["method.reduced"], &dir),
        check(&example("point_vortices.toml"), &["method.reduced=true"], &dir),
        ddirac(&["run"], &dir.0),
        ddirac(&["run", &cp, "--format", "xls"], &dir.0),
    ] {
        assert_eq!(code(&output), Some(2), "{}", String::from_utf8_lossy(&output.stderr));
    }
}

#[test]
fn a_failed_integration_exits_3() {
    let dir = TempDir::new("numerical");
    let output = run(&example("charged_particle.toml"), &["method.max_iterations=1", "method.tolerance=1e-16"], &dir);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("Newton's method failed"), "{stderr}");
    assert_eq!(code(&output), Some(3), "{stderr}");
}

#[test]
fn a_file_that_cannot_be_read_or_written_exits_4() {
    let dir = TempDir::new("io");
    let missing = ddirac(&["run", "no-such-spec.toml"], &dir.0);
    assert_eq!(code(&missing), Some(4), "{}", String::from_utf8_lossy(&missing.stderr));

    let file = dir.file("occupied", "a file, not a directory");
    let output = ddirac(&["run", &example("charged_particle.toml"), "--out", &file, "--quiet"], &dir.0);
    assert_eq!(code(&output), Some(4), "{}", String::from_utf8_lossy(&output.stderr));

    let plot = ddirac(&["plot", dir.0.to_str().unwrap()], &dir.0);
    assert_eq!(code(&plot), Some(4), "{}", String::from_utf8_lossy(&plot.stderr));
}

#[test]
fn success_exits_0() {
    let dir = TempDir::new("success");
    assert_eq!(code(&run(&example("charged_particle.toml"), &[], &dir)), Some(0));
    assert_eq!(code(&check(&example("charged_particle.toml"), &[], &dir)), Some(0));
}

#[test]
fn the_help_describes_every_command_with_examples_and_the_exit_statuses() {
    let dir = TempDir::new("help");
    let output = ddirac(&["--help"], &dir.0);
    assert_eq!(code(&output), Some(0));
    let help = String::from_utf8_lossy(&output.stdout);
    assert!(!help.contains("Command-line front end of ddirac"), "{help}");
    assert!(help.contains("Discrete Dirac reduction of implicit Lagrangian systems"), "{help}");
    for command in ["run", "convergence", "plot", "check", "systems", "bench"] {
        assert!(help.contains(&format!("\n  {command} ")), "`{command}` is not listed:\n{help}");
        let output = ddirac(&[command, "--help"], &dir.0);
        assert_eq!(code(&output), Some(0));
        let text = String::from_utf8_lossy(&output.stdout);
        assert!(text.contains("Example"), "`ddirac {command} --help` has no example:\n{text}");
        assert!(text.contains(&format!("ddirac {command}")), "`ddirac {command} --help`:\n{text}");
    }
    for status in ["Exit status:", "  2 ", "  3 ", "  4 ", "130 SIGINT", "143 SIGTERM", "129 SIGHUP"] {
        assert!(help.contains(status), "the help lacks `{status}`:\n{help}");
    }
    let version = ddirac(&["--version"], &dir.0);
    assert_eq!(code(&version), Some(0));
    assert_eq!(String::from_utf8_lossy(&version.stdout).trim(), format!("ddirac {}", env!("CARGO_PKG_VERSION")));
}

//! Finding 3: `check_invariance = false` reduced a non-invariant Lagrangian without a word and
//! reported zero momentum drift, while `check` with the same override said the run would be refused.
//! The run must warn (in summary.json and on stderr), and check and run must agree.

use crate::common;

use common::{check, line, run, stderr, stdout, summary, TempDir};

const TILTED: &str = r#"
[system]
shape = ["phi"]
group = ["theta"]
angles = ["phi", "theta"]
lagrangian = "0.5*(phi_dot^2 + sin(phi)^2*theta_dot^2) - g*(cos(eps)*cos(phi) + sin(eps)*sin(phi)*cos(theta))"

[parameters]
g = 9.81
eps = 0.01

[method]
reduced = true
check_invariance = false

[time]
step = 0.01
steps = 100

[initial]
q = [1.0, 0.0]
v = [0.0, 1.0]
"#;

#[test]
fn reducing_without_the_check_warns_and_check_agrees_with_run() {
    let dir = TempDir::new("unchecked");
    let spec = dir.file("tilted.toml", TILTED);
    let output = run(&spec, &[], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let warning = "warning [not_invariant]";
    assert_eq!(stderr(&output).matches(warning).count(), 1, "{}", stderr(&output));
    let warnings = summary(&dir)["warnings"].as_array().expect("a warnings list").clone();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0]["kind"], "not_invariant");
    assert!(warnings[0]["step"].is_null() && warnings[0]["t"].is_null());
    let message = warnings[0]["message"].as_str().unwrap();
    assert!(message.contains("`theta`") && message.contains("momentum"), "{message}");

    let output = check(&spec, &[], &dir);
    assert!(output.status.success(), "check refuses what run accepts:\n{}", stdout(&output));
    assert!(line(&stdout(&output), "verdict").contains("accepted (reduced equations) with 1 warning"));
    assert!(stderr(&output).contains(warning));

    // With the check on, both refuse with the same message.
    let (checked, ran) =
        (check(&spec, &["method.check_invariance=true"], &dir), run(&spec, &["method.check_invariance=true"], &dir));
    assert!(!checked.status.success() && !ran.status.success());
    let first = |o: &std::process::Output| stderr(o).lines().find(|l| l.contains('×')).unwrap_or_default().to_owned();
    assert_eq!(first(&checked), first(&ran));
}

#[test]
fn an_invariant_reduction_has_no_warnings() {
    let dir = TempDir::new("no-warnings");
    let spec = dir.file("upright.toml", TILTED);
    let output = run(&spec, &["parameters.eps=0.0"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!stderr(&output).contains("warning"), "{}", stderr(&output));
    assert_eq!(summary(&dir)["warnings"].as_array().map(Vec::len), Some(0));
}

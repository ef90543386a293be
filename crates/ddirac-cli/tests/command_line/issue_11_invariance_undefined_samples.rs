//! Finding 2: invariance samples where L is undefined counted as invariant. With
//! `c*sqrt(1e-4 - x^2)*cos(y)` in L every sample (drawn far from the initial data) fell outside the
//! domain of the square root, the check printed "deviation 0" and the reduced run was wrong. Samples
//! must be taken where L is defined, and a check without enough of them must refuse, not pass.

use crate::common;

use common::{check, line, run, stderr, stdout, TempDir};

fn spec(lagrangian: &str, q0: &str) -> String {
    format!(
        r#"
[system]
shape = ["x"]
group = ["y"]
lagrangian = "{lagrangian}"

[parameters]
c = 1.0

[method]
reduced = true

[time]
step = 0.01
steps = 100

[initial]
q = {q0}
v = [0.0, 0.1]
"#
    )
}

#[test]
fn a_lagrangian_defined_only_near_the_initial_data_is_tested_there() {
    let dir = TempDir::new("undefined-samples");
    let path = dir.file("narrow.toml", &spec("0.5*(x_dot^2 + y_dot^2) + c*sqrt(1e-4 - x^2)*cos(y)", "[0.001, 0.0]"));
    let output = check(&path, &[], &dir);
    let report = stdout(&output);
    assert!(!output.status.success(), "{report}");
    let invariance = line(&report, "invariance");
    assert!(invariance.contains("NOT invariant"), "{report}");
    let samples: usize = invariance.split(", ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!(samples >= 4, "{report}");
    assert!(!run(&path, &[], &dir).status.success(), "the reduced run was accepted");

    // The same domain without the dependence on y is invariant, and runs.
    let path = dir.file("narrow-invariant.toml", &spec("0.5*(x_dot^2 + y_dot^2) + c*sqrt(1e-4 - x^2)", "[0.001, 0.0]"));
    let output = check(&path, &[], &dir);
    assert!(output.status.success(), "{}", stdout(&output));
    assert!(line(&stdout(&output), "invariance").ends_with(": invariant"));
}

#[test]
fn a_check_without_enough_defined_samples_refuses_to_decide() {
    let dir = TempDir::new("undecided");
    // sqrt(1e-14 - x^2) is defined for |x| < 1e-7 only: the first step (x = 0) and few other pairs.
    let lagrangian = "0.5*(x_dot^2 + y_dot^2) + c*sqrt(1e-14 - x^2)*cos(y)";
    let path = dir.file("thin.toml", &spec(lagrangian, "[0.0, 0.0]"));
    let output = check(&path, &[], &dir);
    let report = stdout(&output);
    assert!(!output.status.success(), "{report}");
    assert!(line(&report, "invariance").contains("UNDECIDED"), "{report}");
    assert!(stderr(&output).contains("could not be tested"), "{}", stderr(&output));
    // An explicit override reduces anyway, with a warning.
    let output = check(&path, &["method.check_invariance=false"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("warning [invariance_undecided]"), "{}", stderr(&output));
}

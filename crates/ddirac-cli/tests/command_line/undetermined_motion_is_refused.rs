//! A spec whose Lagrangian leaves the motion undetermined (`0*x_dot`, or a built-in system with a
//! parameter that makes it vanish) used to run with "warnings none" and exit code 0, reporting a
//! constant q. It is a spec error now (exit 2) pointing at the system, and nothing is written.

use crate::common;

use common::{assert_fails, example, run, TempDir};

const VANISHING: &str = r#"
[system]
shape = ["x"]
lagrangian = "0*x_dot"

[time]
step = 0.1
steps = 10

[initial]
q = [1.0]
v = [2.0]
"#;

#[test]
fn a_vanishing_lagrangian_is_a_spec_error_at_the_system() {
    let dir = TempDir::new("undetermined");
    let spec = dir.file("vanishing.toml", VANISHING);
    let output = run(&spec, &[], &dir);
    assert_eq!(output.status.code(), Some(2));
    let stderr = assert_fails(&output, &dir, &["do not determine the motion", "rank 0 of 1", "this system"]);
    assert!(stderr.contains("every velocity must enter the Lagrangian"), "{stderr}");
}

#[test]
fn a_pendulum_of_length_zero_is_refused() {
    let dir = TempDir::new("undetermined-builtin");
    let output = run(&example("spherical_pendulum.toml"), &["parameters.l=0.0"], &dir);
    assert_eq!(output.status.code(), Some(2));
    assert_fails(&output, &dir, &["do not determine the motion", "rank 0 of 2"]);
}

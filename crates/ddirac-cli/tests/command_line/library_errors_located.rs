//! Errors of the library point at the spec value they are about, found from the error's typed fields
//! (which input, which hypothesis, which coordinate) rather than from its message text: a parameter a
//! built-in system refuses, and a hypothesis that could not be tested on an angle (before, the latter
//! pointed at `reduced`, or nowhere when the spec did not set it).

use crate::common;

use common::{assert_fails, run, underlined, TempDir};

#[test]
fn a_parameter_the_system_refuses_is_underlined() {
    let dir = TempDir::new("parameter-located");
    let spec = dir.file(
        "negative-mass.toml",
        r#"
system = "charged_particle"

[parameters]
m = -1.0

[time]
step = 0.1
steps = 10

[initial]
q = [0.0, 0.0, 0.0, 0.0]
p = [1.0, 0.0, 1.0, 1.0]
"#,
    );
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["invalid parameter `m`: must be positive, got -1"]);
    assert_eq!(underlined(&stderr, "m = "), ["-1.0"]);
    assert!(stderr.contains("this parameter"), "{stderr}");
}

#[test]
fn an_untestable_periodicity_points_at_the_angle() {
    let dir = TempDir::new("periodicity-undecided");
    // sqrt(1e-14 - x^2) is defined for |x| < 1e-7 only: too few pairs near q0 to test x as an angle.
    let spec = dir.file(
        "thin-angle.toml",
        r#"
[system]
shape = ["x", "y"]
angles = ["x"]
lagrangian = "0.5*(x_dot^2 + y_dot^2) + c*sqrt(1e-14 - x^2)"

[parameters]
c = 1.0

[time]
step = 0.01
steps = 100

[initial]
q = [0.0, 0.0]
v = [0.0, 0.1]
"#,
    );
    let stderr = assert_fails(
        &run(&spec, &[], &dir),
        &dir,
        &["the 2π-periodicity of L in the angle `x` could not be tested", "remove the coordinate from `angles`"],
    );
    assert_eq!(underlined(&stderr, "angles = "), ["\"x\""]);
    assert!(!stderr.contains("check_invariance"), "{stderr}");
}

//! Finding 4: an `angles` coordinate was never checked for 2π-periodicity: a spring pendulum's radius
//! listed as an angle was accepted, the chart wrapped r to r − 2π and the answer was silently wrong.

use crate::common;

use common::{assert_fails, check, run, stdout, underlined, TempDir};

const SPRING: &str = r#"
[system]
shape = ["r", "phi"]
angles = ["r", "phi"]
lagrangian = "0.5*(r_dot^2 + r^2*phi_dot^2) - 0.5*k*(r - 1)^2 + g*r*cos(phi)"

[parameters]
k = 10.0
g = 1.0

[time]
step = 0.01
steps = 100

[initial]
q = [3.5, 0.3]
v = [0.0, 0.0]
"#;

#[test]
fn a_radius_listed_as_an_angle_is_refused_at_its_name() {
    let dir = TempDir::new("not-periodic");
    let spec = dir.file("spring.toml", SPRING);
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["not 2π-periodic in the angle `r`"]);
    assert_eq!(underlined(&stderr, "angles = "), ["\"r\""]);
    let output = check(&spec, &[], &dir);
    assert!(!output.status.success());
    assert!(stdout(&output).contains("r: deviation") && stdout(&output).contains("NOT 2π-periodic"));

    // phi alone is an angle: accepted.
    let fixed = dir.file("spring-fixed.toml", &SPRING.replace(r#"angles = ["r", "phi"]"#, r#"angles = ["phi"]"#));
    let output = run(&fixed, &[], &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}

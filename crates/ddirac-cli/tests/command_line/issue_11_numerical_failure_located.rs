//! Smaller finding: Newton failures were not located in the spec and printed times such as
//! `t = 72.10000000000001`. A numerical failure points at the `[time]` table (and the Newton
//! tolerance, when the spec sets it), and times are printed rounded.

use crate::common;

use common::{assert_fails, example, run, TempDir};

#[test]
fn a_newton_failure_points_at_the_time_grid_and_the_tolerance() {
    let dir = TempDir::new("newton-located");
    // One iteration cannot meet a tolerance of 1e-15 on the Kepler orbit's first step.
    let stderr = assert_fails(
        &run(&example("kepler.toml"), &["method.max_iterations=1", "method.tolerance=1e-15"], &dir),
        &dir,
        &["Newton's method failed", "step 0 (t = 0, h = 0.002)"],
    );
    assert!(stderr.contains("this time grid"), "{stderr}");
    assert!(stderr.contains("Newton tolerance"), "{stderr}");
}

#[test]
fn times_are_printed_rounded() {
    // 721 steps of 0.1 is 72.10000000000001 in floating point.
    assert_eq!(721.0 * 0.1, 72.10000000000001);
    assert_eq!(ddirac::Time(721.0 * 0.1).to_string(), "72.1");
    assert_eq!(ddirac::Time(3.0 * 0.1).to_string(), "0.3");
    assert_eq!(ddirac::Time(1e-300).to_string(), "1e-300");
    assert_eq!(ddirac::Time(0.0).to_string(), "0");
}

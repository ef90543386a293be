//! `ddirac check`: the report (invariance, connection, Legendre rank, primary constraint) and the
//! exit status, which is non-zero exactly when a run of the spec's method would be refused.

use crate::common;

use std::process::Output;

use common::{check, example, TempDir};

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The report line that starts with `key` (after the indentation).
fn line<'a>(report: &'a str, key: &str) -> &'a str {
    report.lines().find(|l| l.trim_start().starts_with(key)).unwrap_or_else(|| panic!("no `{key}` line:\n{report}"))
}

#[test]
fn an_invariant_regular_system_is_accepted_for_a_reduced_run() {
    let dir = TempDir::new("check-cp");
    for spec in ["charged_particle.toml", "charged_particle_expression.toml"] {
        let output = check(&example(spec), &[], &dir);
        let report = stdout(&output);
        assert!(output.status.success(), "{spec}: {report}{}", stderr(&output));
        assert!(line(&report, "invariance").contains("theta: deviation"), "{report}");
        assert!(line(&report, "invariance").ends_with("(tolerance 1e-9, 16 samples): invariant"), "{report}");
        assert!(line(&report, "angles").contains("theta: deviation 0.00e0"), "{report}");
        assert_eq!(line(&report, "connection").trim(), "connection        K = 0 (1 × 3): axioms hold");
        assert!(line(&report, "Legendre").contains("regular (rank 4 of 4)"), "{report}");
        assert!(line(&report, "initial momentum").contains("consistent with the primary constraint"), "{report}");
        assert!(line(&report, "verdict").contains("a run would be accepted (reduced equations)"), "{report}");
    }
    assert!(!dir.out().exists(), "check wrote output");
}

#[test]
fn point_vortices_are_degenerate_and_not_invariant_but_run_unreduced() {
    let dir = TempDir::new("check-vortices");
    let output = check(&example("point_vortices.toml"), &[], &dir);
    let report = stdout(&output);
    assert!(output.status.success(), "{report}{}", stderr(&output));
    let invariance = line(&report, "invariance");
    assert!(invariance.contains("X: deviation"), "{report}");
    assert!(invariance.ends_with("NOT invariant: the unreduced equations do not need it"), "{report}");
    // The deviation is the boundary term ½ a (G1 Δy1 + G2 Δy2), relative to the slope of L_d.
    let deviation: f64 = invariance.split("deviation ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!(deviation > 1e-3, "{deviation}");
    assert!(line(&report, "Legendre").contains("degenerate (rank 0 of 4)"), "{report}");
    assert!(line(&report, "initial momentum").contains("consistent with the primary constraint"), "{report}");
    assert!(line(&report, "verdict").contains("accepted (unreduced equations)"), "{report}");
}

#[test]
fn a_reduced_run_of_a_non_invariant_lagrangian_would_be_refused() {
    let dir = TempDir::new("check-vortices-reduced");
    let output = check(&example("point_vortices.toml"), &["method.reduced=true"], &dir);
    let report = stdout(&output);
    assert!(!output.status.success(), "{report}");
    assert!(line(&report, "verdict").contains("a run would be refused"), "{report}");
    let diagnostic = stderr(&output);
    for needle in
        ["not invariant under translation of the group coordinate `X`", "tolerance 1e-9", "reduction asked here"]
    {
        assert!(diagnostic.contains(needle), "stderr lacks `{needle}`:\n{diagnostic}");
    }
    // Skipping the library's invariance check does not make the reduced equations valid: the run
    // goes on, as `ddirac run` would, with a warning that says so.
    let output =
        check(&example("point_vortices.toml"), &["method.reduced=true", "method.check_invariance=false"], &dir);
    assert!(output.status.success(), "{}", stdout(&output));
    assert!(line(&stdout(&output), "invariance").contains("reduced anyway (check_invariance = false)"));
    assert!(stderr(&output).contains("warning [not_invariant]"), "{}", stderr(&output));
}

#[test]
fn a_degenerate_lagrangian_with_p0_off_the_primary_constraint_would_be_refused() {
    let dir = TempDir::new("check-constraint");
    // p_X = −½ G1 y1 − ½ G2 y2 = −1.6 on the constraint; 0 is off it by 1.6.
    let output = check(&example("point_vortices.toml"), &["initial.p.X=0.0"], &dir);
    let report = stdout(&output);
    assert!(!output.status.success(), "{report}");
    let momentum = line(&report, "initial momentum");
    assert!(momentum.contains("NOT consistent with the primary constraint p = ∂L/∂v (mismatch 1.60e0)"), "{report}");
    let diagnostic = stderr(&output);
    assert!(diagnostic.contains("the Lagrangian is degenerate (rank 0 of 4)"), "{diagnostic}");
    assert!(diagnostic.contains("off the primary constraint"), "{diagnostic}");

    // A regular Lagrangian has a velocity for every p0: any p0 is accepted.
    let output = check(&example("kepler.toml"), &["initial.p.r=0.3"], &dir);
    assert!(output.status.success(), "{}{}", stdout(&output), stderr(&output));
}

#[test]
fn velocities_are_on_the_constraint_by_construction() {
    let dir = TempDir::new("check-velocity");
    let output = check(&example("heavy_top.toml"), &[], &dir);
    let report = stdout(&output);
    assert!(output.status.success(), "{report}");
    assert!(line(&report, "initial momentum").contains("given as a velocity"), "{report}");
    assert_eq!(report.matches("invariant").count(), 2, "one line per group coordinate:\n{report}");
    assert!(report.contains("phi: deviation") && report.contains("psi: deviation"), "{report}");
    assert!(line(&report, "connection").contains("(2 × 1)"), "{report}");
}

#[test]
fn reduction_without_a_group_coordinate_would_be_refused() {
    let dir = TempDir::new("check-no-group");
    let spec = dir.file(
        "spec.toml",
        "[system]\nshape = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\n[method]\nreduced = true\n\
         [time]\nstep = 0.1\nsteps = 10\n[initial]\nq = [1.0]\np = [0.0]\n",
    );
    let output = check(&spec, &[], &dir);
    assert!(!output.status.success(), "{}", stdout(&output));
    assert!(line(&stdout(&output), "invariance").contains("no group coordinates"));
    assert!(stderr(&output).contains("reduction needs at least one group coordinate"), "{}", stderr(&output));
    let output = check(&spec, &["method.reduced=false"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn spec_errors_fail_before_any_report() {
    let dir = TempDir::new("check-error");
    let output = check(&example("kepler_expression.toml"), &["system.lagrangian=\"0.5*m*r_dot^2 + k/q\""], &dir);
    assert!(!output.status.success());
    assert!(stdout(&output).is_empty(), "{}", stdout(&output));
    assert!(stderr(&output).contains("unknown name `q`"), "{}", stderr(&output));
}

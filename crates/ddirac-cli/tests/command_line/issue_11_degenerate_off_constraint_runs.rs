//! Finding 5: a degenerate Lagrangian with p0 off the primary constraint ran (exit 0, a meaningless
//! trajectory), although `check` and the README said it is refused.

use crate::common;

use common::{assert_fails, check, example, run, stderr, underlined, TempDir};

#[test]
fn point_vortices_with_p0_off_the_constraint_are_refused_by_run_as_by_check() {
    let dir = TempDir::new("off-constraint");
    let spec = example("point_vortices.toml");
    // p_X = −½ Γ1 y1 − ½ Γ2 y2 = −1.6 on the constraint; 0 is off it by 1.6.
    let ran = assert_fails(
        &run(&spec, &["initial.p.X=0.0"], &dir),
        &dir,
        &["the Lagrangian is degenerate (rank 0 of 4)", "mismatch 1.600e0"],
    );
    assert!(underlined(&ran, "p = ").len() == 1, "{ran}");
    let checked = check(&spec, &["initial.p.X=0.0"], &dir);
    assert!(!checked.status.success());
    let first = |s: &str| s.lines().find(|l| l.contains('×')).unwrap_or_default().to_owned();
    assert_eq!(first(&ran), first(&stderr(&checked)));
    // On the constraint, the example runs.
    assert!(run(&spec, &[], &dir).status.success());
}

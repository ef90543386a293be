//! `ddirac run SPEC --compare` runs the spec reduced and unreduced whatever its `reduced` says. When
//! the reduced run was refused, the report pointed at the user's `reduced = false` with the label
//! "reduction asked here": the spec asked for no such thing. The report must say what the spec says
//! and that the other run is the one `--compare` adds.

use crate::common;

use common::{ddirac, example, TempDir};

fn compare(sets: &[&str], dir: &TempDir) -> String {
    let out = dir.out();
    let spec = example("point_vortices.toml");
    let mut args = vec!["run", spec.as_str(), "--compare", "--out", out.to_str().unwrap()];
    for s in sets {
        args.extend(["--set", s]);
    }
    let output = ddirac(&args, &dir.0);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(!output.status.success(), "the vortices' L_d is not invariant: the reduced run must be refused");
    assert!(stderr.contains("not invariant under translation of the group coordinate `X`"), "{stderr}");
    stderr
}

#[test]
fn a_spec_with_reduced_false_is_not_labelled_as_asking_for_reduction() {
    // examples/point_vortices.toml says `reduced = false`.
    let dir = TempDir::new("unreduced");
    let stderr = compare(&[], &dir);
    assert!(!stderr.contains("reduction asked here"), "the spec asks for `reduced = false`:\n{stderr}");
    assert!(
        stderr.contains("the spec asks for `reduced = false`, and --compare runs the reduced equations as well"),
        "{stderr}"
    );
    // The group coordinate whose translation changes L_d is still pointed at.
    assert!(stderr.contains("L_d is not invariant under translations of `X`"), "{stderr}");
}

#[test]
fn a_spec_that_asks_for_reduction_is_labelled_so() {
    let dir = TempDir::new("reduced");
    let stderr = compare(&["method.reduced=true"], &dir);
    assert!(stderr.contains("reduction asked here"), "{stderr}");
    assert!(stderr.contains("the reduced run failed"), "{stderr}");
    assert!(!stderr.contains("--compare runs"), "the reduced run is the spec's own:\n{stderr}");
}

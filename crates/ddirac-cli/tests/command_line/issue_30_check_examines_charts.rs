//! `ddirac check` never examined an atlas's charts: a spec whose `to_main` swaps the arguments of
//! `atan2` (so that its maps are not inverse) passed the check, and its run silently never entered
//! the charts ("0 switches among 3 charts"). The check now prints a line per chart and refuses such a
//! chart with exit status 2, and the run refuses it with the same message.

use crate::common;

use common::{check, example, run, stderr, stdout, TempDir};

/// The spherical pendulum example with `to_main`'s `atan2(y, x)` written `atan2(x, y)` in both caps.
fn swapped(dir: &TempDir) -> String {
    let text = std::fs::read_to_string(example("spherical_pendulum.toml")).unwrap();
    let text = text.replace("phi = \"atan2(y, x)\"", "phi = \"atan2(x, y)\"");
    assert!(text.contains("atan2(x, y)"));
    dir.file("swapped.toml", &text)
}

#[test]
fn check_reports_every_chart_of_the_shipped_atlas() {
    let dir = TempDir::new("check-charts");
    let output = check(&example("spherical_pendulum.toml"), &[], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("`lower cap`: maps inverse on"), "{text}");
    assert!(text.contains("`upper cap`: maps inverse on"), "{text}");
}

#[test]
fn check_and_run_refuse_a_chart_whose_maps_are_not_inverse() {
    let dir = TempDir::new("check-swapped");
    let spec = swapped(&dir);
    let checked = check(&spec, &[], &dir);
    assert_eq!(checked.status.code(), Some(2), "{}", stdout(&checked));
    assert!(stdout(&checked).contains("maps NOT inverse"), "{}", stdout(&checked));
    let ran = run(&spec, &[], &dir);
    assert_eq!(ran.status.code(), Some(2));
    let (from_check, from_run) = (stderr(&checked), stderr(&ran));
    let message = "chart `lower cap` of the atlas: its maps are not inverse";
    assert!(from_check.contains(message) && from_run.contains(message), "{from_check}\n{from_run}");
    assert!(!dir.out().join("summary.json").exists(), "a refused run leaves no output");
    // Without the atlas the charts are not relied on.
    assert!(check(&spec, &["method.atlas=false"], &dir).status.success());
}

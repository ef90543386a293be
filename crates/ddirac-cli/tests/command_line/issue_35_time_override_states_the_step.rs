//! Finding: `--set time.duration=100000` on the main example kept its `steps = 10⁴`, so the step
//! became h = 10 without a word; the run then died at step 8 with a NaN and a message that did not
//! state h. An override of a `[time]` key that changes h is now noted with the resulting h, and
//! every numerical failure states the step it was taken with.

use crate::common;

use common::{assert_fails, example, run, stderr, TempDir};

#[test]
fn overriding_the_duration_notes_the_step_that_results_and_the_failure_states_it() {
    let dir = TempDir::new("time-override");
    let output = run(&example("double_spherical_pendulum.toml"), &["time.duration=100000"], &dir);
    // The spec gives steps = 10⁴ and duration = 100: the override keeps N, so h = 10⁵ / 10⁴.
    let (steps, duration, spec_h) = (10_000.0, 100_000.0, 100.0 / 10_000.0);
    let h = duration / steps;
    let text = assert_fails(&output, &dir, &[&format!("h = {h}")]);
    let note = text.lines().find(|l| l.starts_with("note: ")).unwrap_or_else(|| panic!("no note:\n{text}"));
    assert!(note.contains("`time.duration`"), "{note}");
    assert!(note.contains(&format!("the step h = {h} ")), "{note}");
    assert!(note.contains(&format!("the spec's own step is h = {spec_h} ")), "{note}");
    // Keeping h = 0.01 over 10⁵ time units takes 10⁷ steps.
    assert!(note.contains(&format!("set `time.steps={}`", duration / spec_h)), "{note}");
    // The failure itself names h, not only the step and the time.
    assert!(text.lines().any(|l| l.contains("step ") && l.contains(&format!(", h = {h})"))), "{text}");
}

#[test]
fn an_override_that_keeps_the_step_or_sets_it_is_not_noted() {
    let dir = TempDir::new("time-override-quiet");
    // steps and duration scaled together: h stays 0.01.
    let output = run(&example("double_spherical_pendulum.toml"), &["time.duration=1", "time.steps=100"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!stderr(&output).contains("note:"), "{}", stderr(&output));

    // A spec that gives step and duration: overriding the step is what the user asked for.
    let dir = TempDir::new("time-override-step");
    let output = run(&example("kepler.toml"), &["time.step=0.004"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!stderr(&output).contains("note:"), "{}", stderr(&output));

    // Overriding the duration of that spec keeps its step: nothing to note either.
    let dir = TempDir::new("time-override-step-kept");
    let output = run(&example("kepler.toml"), &["time.duration=4"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!stderr(&output).contains("note:"), "{}", stderr(&output));
}

#[test]
fn more_steps_over_the_same_duration_are_what_was_asked_and_the_summary_states_h() {
    // Halving h by doubling the steps is what `time.steps` means (a convergence study does it at
    // every row): no note, and the printed summary states the new h.
    let dir = TempDir::new("time-override-steps");
    let out = dir.out();
    let spec = example("double_spherical_pendulum.toml");
    let output = common::ddirac(&["run", &spec, "--out", out.to_str().unwrap(), "--set", "time.steps=20"], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!stderr(&output).contains("note:"), "{}", stderr(&output));
    let report = common::stdout(&output);
    assert!(report.contains(&format!("20 steps of h = {} ", 100.0 / 20.0)), "{report}");
}

//! `[time]`: the time grid of [`crate::keys::time`] read from the spec, and what overriding its keys
//! did to the step.

use std::ops::Range;

use toml::Spanned;

use super::TimeSpec;
use crate::diagnostics::{SpecError, SpecSource};
use crate::keys::time::{TimeKey, TimeKeys, INTEGER_TOLERANCE, MAX_STEPS};
use crate::keys::Spelling;
use crate::output::number;

/// The step h and the number of steps N of `[time]` ([`crate::keys::time::grid`]), a refusal pointing
/// at the keys it concerns.
pub fn grid(source: &SpecSource, time: &Spanned<TimeSpec>) -> Result<(f64, usize), Box<SpecError>> {
    let t = time.get_ref();
    let keys = TimeKeys {
        step: t.step.as_ref().map(|s| *s.get_ref()),
        steps: t.steps.as_ref().map(|n| *n.get_ref()),
        duration: t.duration.as_ref().map(|d| *d.get_ref()),
    };
    crate::keys::time::grid(&keys, Spelling::Spec).map_err(|error| {
        source.refusal(error, |key| -> Option<Range<usize>> {
            match key {
                TimeKey::Step => t.step.as_ref().map(|s| s.span()),
                TimeKey::Steps => t.steps.as_ref().map(|n| n.span()),
                TimeKey::Duration => t.duration.as_ref().map(|d| d.span()),
                TimeKey::Grid => Some(time.span()),
            }
        })
    })
}

/// What overriding keys of `[time]` did to the step: a note when the step h of the spec `edited`
/// differs from that of the spec `original` although neither `time.step` nor `time.steps` was among
/// the overridden `keys` — `time.duration` of a spec that gives `steps` and `duration` keeps N, and so
/// scales h. (Overriding the steps over a fixed duration changes h as asked.) `None` when h is
/// unchanged, or either spec has no valid grid.
pub fn changed_step(original: &SpecSource, edited: &SpecSource, keys: &[&str]) -> Option<String> {
    if keys.is_empty() || keys.contains(&"step") || keys.contains(&"steps") {
        return None;
    }
    let (h0, n0) = grid(original, &super::parse(original).ok()?.time).ok()?;
    let (h, n) = grid(edited, &super::parse(edited).ok()?.time).ok()?;
    if (h - h0).abs() <= 1e-12 * h0 {
        return None;
    }
    let set: Vec<String> = keys.iter().map(|k| format!("`time.{k}`")).collect();
    let duration = h * n as f64;
    let mut note = format!(
        "overriding {} makes the step h = {} ({n} steps over a duration of {}); the spec's own step is h = {} \
         ({n0} steps)",
        set.join(" and "),
        number(h),
        number(duration),
        number(h0)
    );
    let keep = (duration / h0).round();
    if keep >= 1.0 && keep <= MAX_STEPS as f64 && ((keep * h0 - duration) / duration).abs() <= INTEGER_TOLERANCE {
        note.push_str(&format!("; to keep h = {}, set `time.steps={keep}` as well", number(h0)));
    }
    Some(note)
}

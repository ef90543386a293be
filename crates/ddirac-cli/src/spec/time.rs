//! The time grid from any two of step h, steps N and duration T = N h.
//!
//! N is at most [`MAX_STEPS`] = 2⁵³, the largest count for which every t_k = k h has an exact k;
//! a grid with more steps (`step = 1e-300` over a duration of 20), or whose step or duration is not
//! a positive normal number, is refused at its keys.

use miette::LabeledSpan;
use toml::Spanned;

use super::TimeSpec;
use crate::diagnostics::{SpecError, SpecSource};
use crate::output::number;

/// Relative tolerance on T / h being an integer, and on N h = T when all three are given.
const INTEGER_TOLERANCE: f64 = 1e-9;

/// The largest number of steps: 2⁵³.
pub const MAX_STEPS: u64 = 1 << 53;

/// The step h and the number of steps N of `[time]`.
pub fn grid(source: &SpecSource, time: &Spanned<TimeSpec>) -> Result<(f64, usize), Box<SpecError>> {
    let t = time.get_ref();
    let positive = |value: &Spanned<f64>, key: &str| {
        let v = *value.get_ref();
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(source.error(Some(value.span()), format!("`time.{key}` must be positive and finite"), number(v)))
        }
    };
    let step = t.step.as_ref().map(|s| positive(s, "step")).transpose()?;
    let duration = t.duration.as_ref().map(|s| positive(s, "duration")).transpose()?;
    let steps = match &t.steps {
        Some(n) if (1..=MAX_STEPS as i64).contains(n.get_ref()) => Some(*n.get_ref() as usize),
        Some(n) if *n.get_ref() >= 1 => {
            let labels = vec![label(&t.steps, format!("steps = {}", n.get_ref()))];
            return Err(too_many(source, labels, n.get_ref().to_string()));
        }
        Some(n) => {
            return Err(source.error(Some(n.span()), "`time.steps` must be at least 1", format!("{}", n.get_ref())))
        }
        None => None,
    };
    match (step, steps, duration) {
        (Some(h), Some(n), None) => {
            let d = h * n as f64;
            if d.is_finite() {
                Ok((h, n))
            } else {
                let labels =
                    vec![label(&t.step, format!("step = {}", number(h))), label(&t.steps, format!("steps = {n}"))];
                Err(source.error_with(
                    format!("`[time]`: the duration step × steps = {} × {n} is not a finite number", number(h)),
                    labels.into_iter().flatten().collect(),
                ))
            }
        }
        (None, Some(n), Some(d)) => {
            let h = d / n as f64;
            if h.is_normal() {
                Ok((h, n))
            } else {
                let labels = vec![
                    label(&t.duration, format!("duration = {}", number(d))),
                    label(&t.steps, format!("steps = {n}")),
                ];
                Err(source
                    .error_with(
                        format!(
                            "`[time]`: the step duration / steps = {} / {n} = {h:e} is too small to compute with",
                            number(d)
                        ),
                        labels.into_iter().flatten().collect(),
                    )
                    .with_help("choose fewer steps or a longer duration"))
            }
        }
        (Some(h), None, Some(d)) => {
            let ratio = d / h;
            let n = ratio.round();
            if n > MAX_STEPS as f64 {
                let labels = vec![
                    label(&t.duration, format!("duration = {}", number(d))),
                    label(&t.step, format!("step = {}", number(h))),
                ];
                return Err(too_many(source, labels, format!("{ratio:.3e}")));
            }
            if n >= 1.0 && (ratio - n).abs() <= INTEGER_TOLERANCE * n {
                Ok((h, n as usize))
            } else {
                let labels = vec![
                    label(&t.duration, format!("duration = {}", number(d))),
                    label(&t.step, format!("step = {}", number(h))),
                ];
                Err(source
                    .error_with(
                        format!("`time.duration / time.step` = {} is not a whole number of steps", number(ratio)),
                        labels.into_iter().flatten().collect(),
                    )
                    .with_help("choose a step that divides the duration, or give `steps` instead of `step`"))
            }
        }
        (Some(h), Some(n), Some(d)) => {
            let product = h * n as f64;
            if (product - d).abs() <= INTEGER_TOLERANCE * d {
                Ok((h, n))
            } else {
                let labels = vec![
                    label(&t.step, format!("step = {}", number(h))),
                    label(&t.steps, format!("steps = {n}")),
                    label(&t.duration, format!("but duration = {}", number(d))),
                ];
                Err(source
                    .error_with(
                        format!(
                            "inconsistent `[time]`: step × steps = {}, but duration = {}",
                            number(product),
                            number(d)
                        ),
                        labels.into_iter().flatten().collect(),
                    )
                    .with_help("give only two of `step`, `steps`, `duration`, or make step × steps equal the duration"))
            }
        }
        _ => {
            let given: Vec<&str> =
                [("step", step.is_some()), ("steps", steps.is_some()), ("duration", duration.is_some())]
                    .into_iter()
                    .filter_map(|(k, present)| present.then_some(k))
                    .collect();
            let found = if given.is_empty() { "none".to_owned() } else { format!("only `{}`", given.join("`, `")) };
            Err(source
                .error(
                    Some(time.span()),
                    format!("`[time]` needs two of `step`, `steps`, `duration`; found {found}"),
                    "this table",
                )
                .with_help("e.g. `steps = 100` and `duration = 20.0`"))
        }
    }
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

/// The error of a grid of `count` steps, more than [`MAX_STEPS`].
fn too_many(source: &SpecSource, labels: Vec<Option<LabeledSpan>>, count: String) -> Box<SpecError> {
    source
        .error_with(
            format!("`[time]` asks for {count} steps, more than the {MAX_STEPS} (2^53) a run can count"),
            labels.into_iter().flatten().collect(),
        )
        .with_help("choose a larger step, a shorter duration or fewer steps")
}

fn label<T>(value: &Option<Spanned<T>>, text: String) -> Option<LabeledSpan> {
    value.as_ref().map(|v| LabeledSpan::new_with_span(Some(text), v.span()))
}

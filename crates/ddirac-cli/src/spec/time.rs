//! The time grid from any two of step h, steps N and duration T = N h.

use miette::LabeledSpan;
use toml::Spanned;

use super::TimeSpec;
use crate::diagnostics::{SpecError, SpecSource};

/// Relative tolerance on T / h being an integer, and on N h = T when all three are given.
const INTEGER_TOLERANCE: f64 = 1e-9;

/// The step h and the number of steps N of `[time]`.
pub fn grid(source: &SpecSource, time: &Spanned<TimeSpec>) -> Result<(f64, usize), Box<SpecError>> {
    let t = time.get_ref();
    let positive = |value: &Spanned<f64>, key: &str| {
        let v = *value.get_ref();
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(source.error(Some(value.span()), format!("`time.{key}` must be positive and finite"), format!("{v}")))
        }
    };
    let step = t.step.as_ref().map(|s| positive(s, "step")).transpose()?;
    let duration = t.duration.as_ref().map(|s| positive(s, "duration")).transpose()?;
    let steps = match &t.steps {
        Some(n) if *n.get_ref() >= 1 => Some(*n.get_ref() as usize),
        Some(n) => {
            return Err(source.error(Some(n.span()), "`time.steps` must be at least 1", format!("{}", n.get_ref())))
        }
        None => None,
    };
    match (step, steps, duration) {
        (Some(h), Some(n), None) => Ok((h, n)),
        (None, Some(n), Some(d)) => Ok((d / n as f64, n)),
        (Some(h), None, Some(d)) => {
            let ratio = d / h;
            let n = ratio.round();
            if n >= 1.0 && (ratio - n).abs() <= INTEGER_TOLERANCE * n {
                Ok((h, n as usize))
            } else {
                let labels = vec![label(&t.duration, format!("duration = {d}")), label(&t.step, format!("step = {h}"))];
                Err(source
                    .error_with(
                        format!("`time.duration / time.step` = {ratio} is not a whole number of steps"),
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
                    label(&t.step, format!("step = {h}")),
                    label(&t.steps, format!("steps = {n}")),
                    label(&t.duration, format!("but duration = {d}")),
                ];
                Err(source
                    .error_with(
                        format!("inconsistent `[time]`: step × steps = {product}, but duration = {d}"),
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

fn label<T>(value: &Option<Spanned<T>>, text: String) -> Option<LabeledSpan> {
    value.as_ref().map(|v| LabeledSpan::new_with_span(Some(text), v.span()))
}

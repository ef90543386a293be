//! The time grid from any two of step h, steps N and duration T = N h (all three when they agree),
//! for a spec's `[time]` table and the Python package's `step`, `steps`, `duration`.
//!
//! N is at most [`MAX_STEPS`] = 2⁵³, the largest count for which every t_k = k h has an exact k; a
//! grid with more steps (`step = 1e-300` over a duration of 20), or whose step or duration is not a
//! positive normal number, is refused at its keys.

use super::{KeyError, Spelling};
use crate::output::number;

/// Relative tolerance on T / h being an integer, and on N h = T when all three are given.
pub const INTEGER_TOLERANCE: f64 = 1e-9;

/// The largest number of steps: 2⁵³.
pub const MAX_STEPS: u64 = 1 << 53;

/// The time keys as a front end read them; `None` for a key not given.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TimeKeys {
    /// `step`: h.
    pub step: Option<f64>,
    /// `steps`: N.
    pub steps: Option<i64>,
    /// `duration`: T.
    pub duration: Option<f64>,
}

/// A time key, or the grid as a whole.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeKey {
    /// `step`.
    Step,
    /// `steps`.
    Steps,
    /// `duration`.
    Duration,
    /// The grid (`[time]`).
    Grid,
}

impl TimeKey {
    /// The key's name (`step`); the grid is `time`.
    pub fn name(self) -> &'static str {
        match self {
            TimeKey::Step => "step",
            TimeKey::Steps => "steps",
            TimeKey::Duration => "duration",
            TimeKey::Grid => "time",
        }
    }
}

/// How `spelling` writes the grid and its keys.
struct Words {
    grid: &'static str,
    prefix: &'static str,
}

impl Words {
    fn of(spelling: Spelling) -> Self {
        match spelling {
            Spelling::Spec => Words { grid: "`[time]`", prefix: "time." },
            Spelling::Argument => Words { grid: "the time grid", prefix: "" },
        }
    }

    fn key(&self, key: TimeKey) -> String {
        format!("`{}{}`", self.prefix, key.name())
    }
}

/// The step h and the number of steps N of `keys`.
pub fn grid(keys: &TimeKeys, spelling: Spelling) -> Result<(f64, usize), KeyError<TimeKey>> {
    let words = Words::of(spelling);
    let positive = |value: Option<f64>, key: TimeKey| match value {
        Some(v) if v.is_finite() && v > 0.0 => Ok(Some(v)),
        Some(v) => Err(KeyError::at(key, format!("{} must be positive and finite", words.key(key)), number(v))),
        None => Ok(None),
    };
    let step = positive(keys.step, TimeKey::Step)?;
    let duration = positive(keys.duration, TimeKey::Duration)?;
    let steps = match keys.steps {
        Some(n) if (1..=MAX_STEPS as i64).contains(&n) => Some(n as usize),
        Some(n) if n >= 1 => {
            return Err(too_many(&words, vec![(TimeKey::Steps, format!("steps = {n}"))], n.to_string()))
        }
        Some(n) => {
            return Err(KeyError::at(
                TimeKey::Steps,
                format!("{} must be at least 1", words.key(TimeKey::Steps)),
                n.to_string(),
            ))
        }
        None => None,
    };
    let grid = words.grid;
    match (step, steps, duration) {
        (Some(h), Some(n), None) => {
            if (h * n as f64).is_finite() {
                Ok((h, n))
            } else {
                Err(KeyError::of(
                    format!("{grid}: the duration step × steps = {} × {n} is not a finite number", number(h)),
                    vec![(TimeKey::Step, format!("step = {}", number(h))), (TimeKey::Steps, format!("steps = {n}"))],
                ))
            }
        }
        (None, Some(n), Some(d)) => {
            let h = d / n as f64;
            if h.is_normal() {
                Ok((h, n))
            } else {
                Err(KeyError::of(
                    format!(
                        "{grid}: the step duration / steps = {} / {n} = {h:e} is too small to compute with",
                        number(d)
                    ),
                    vec![
                        (TimeKey::Duration, format!("duration = {}", number(d))),
                        (TimeKey::Steps, format!("steps = {n}")),
                    ],
                )
                .with_help("choose fewer steps or a longer duration"))
            }
        }
        (Some(h), None, Some(d)) => {
            let ratio = d / h;
            let n = ratio.round();
            let labels = vec![
                (TimeKey::Duration, format!("duration = {}", number(d))),
                (TimeKey::Step, format!("step = {}", number(h))),
            ];
            if n > MAX_STEPS as f64 {
                return Err(too_many(&words, labels, format!("{ratio:.3e}")));
            }
            if n >= 1.0 && (ratio - n).abs() <= INTEGER_TOLERANCE * n {
                Ok((h, n as usize))
            } else {
                Err(KeyError::of(
                    format!(
                        "`{p}duration / {p}step` = {} is not a whole number of steps",
                        number(ratio),
                        p = words.prefix
                    ),
                    labels,
                )
                .with_help("choose a step that divides the duration, or give `steps` instead of `step`"))
            }
        }
        (Some(h), Some(n), Some(d)) => {
            let product = h * n as f64;
            if (product - d).abs() <= INTEGER_TOLERANCE * d {
                Ok((h, n))
            } else {
                let grid = grid.trim_start_matches("the ");
                Err(KeyError::of(
                    format!("inconsistent {grid}: step × steps = {}, but duration = {}", number(product), number(d)),
                    vec![
                        (TimeKey::Step, format!("step = {}", number(h))),
                        (TimeKey::Steps, format!("steps = {n}")),
                        (TimeKey::Duration, format!("but duration = {}", number(d))),
                    ],
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
            Err(KeyError::at(
                TimeKey::Grid,
                format!("{grid} needs two of `step`, `steps`, `duration`; found {found}"),
                "this table",
            )
            .with_help("e.g. `steps = 100` and `duration = 20.0`"))
        }
    }
}

/// The refusal of a grid of `count` steps, more than [`MAX_STEPS`].
fn too_many(words: &Words, labels: Vec<(TimeKey, String)>, count: String) -> KeyError<TimeKey> {
    KeyError::of(
        format!("{} asks for {count} steps, more than the {MAX_STEPS} (2^53) a run can count", words.grid),
        labels,
    )
    .with_help("choose a larger step, a shorter duration or fewer steps")
}

//! The keys of a run that every front end takes, each defined, defaulted and checked here once: the
//! method ([`method`]: a spec's `[method]` table and the Python package's keyword arguments of the same
//! names), the time grid ([`time`]: any two of step, steps and duration) and the initial data, in the
//! coordinate order or by coordinate name ([`initial`]).
//!
//! A front end hands over plain values and turns a refusal, a [`KeyError`] naming the keys it
//! concerns, into its own diagnostic: the command line points at each key's text in the spec file,
//! Python raises the message ([`KeyError::text`]). [`Spelling`] says how the messages write a key.

pub mod initial;
pub mod method;
pub mod time;

/// How the messages write a key: as a spec file does (`method.tolerance`, `time.step`, `initial.q`)
/// or as the Python package's arguments (`tolerance`, `step`, `q0`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spelling {
    /// The spec file's dotted keys and tables.
    Spec,
    /// The Python package's keyword arguments.
    Argument,
}

/// A refused value: what is wrong, the keys it concerns with a label for each (what the command line
/// writes under the key's text), and what to do about it.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyError<K> {
    /// The sentence saying what is wrong.
    pub message: String,
    /// The keys concerned, each with its label.
    pub labels: Vec<(K, String)>,
    /// What to do about it.
    pub help: Option<String>,
}

impl<K> KeyError<K> {
    /// A refusal of the value of one key.
    pub(crate) fn at(key: K, message: impl Into<String>, label: impl Into<String>) -> Self {
        Self { message: message.into(), labels: vec![(key, label.into())], help: None }
    }

    /// A refusal concerning several keys.
    pub(crate) fn of(message: impl Into<String>, labels: Vec<(K, String)>) -> Self {
        Self { message: message.into(), labels, help: None }
    }

    /// With what to do about it.
    pub(crate) fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// The message and the help as one text, for a front end that cannot point at the keys.
    pub fn text(&self) -> String {
        match &self.help {
            Some(help) => format!("{}; {help}", self.message),
            None => self.message.clone(),
        }
    }
}

/// `value`, if it is finite; `what` names it in the refusal.
pub(crate) fn finite<K>(key: K, value: f64, what: &str) -> Result<f64, KeyError<K>> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(KeyError::at(key, format!("{what} is not finite ({value})"), "not a finite number"))
    }
}

#[cfg(test)]
mod tests;

//! The run spec: a TOML file naming a system, its parameters, the method, the time grid, the
//! initial data and the output options.
//!
//! ```text
//! system = "charged_particle"
//! [parameters]  m = 1.0                       # overrides of the system's defaults
//! [method]      rule = "left"  variant = "plus"  reduced = true  connection = [[0, 0, 0]]
//!               tolerance = 1e-12  max_iterations = 50  check_invariance = true
//! [time]        step = 0.2  steps = 100  duration = 20.0   # any two, or all three if consistent
//! [initial]     q = [0, 0, 0, 0]  p = [1, 0, 1, 1]         # or v = [...] instead of p
//! [output]      directory = "out/cp"  every = 1  wrap_angles = false
//! ```
//!
//! The schema keeps every value [`Spanned`], so that [`validate`] can point at the text of any value
//! it rejects; unknown keys are refused by the parser itself, with the key's span.

mod time;
mod validate;

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

pub use validate::{validate, Plan};

use crate::diagnostics::{SpecError, SpecSource};

/// A number as written in the spec.
pub type Number = Spanned<f64>;
/// A list of numbers as written in the spec.
pub type Numbers = Spanned<Vec<Number>>;

/// The whole spec file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Which system to integrate.
    pub system: Spanned<SystemRef>,
    /// Overrides of the system's default parameters, by name.
    #[serde(default)]
    pub parameters: BTreeMap<Spanned<String>, Number>,
    /// The discretization and the choice of equations.
    #[serde(default)]
    pub method: MethodSpec,
    /// The time grid.
    pub time: Spanned<TimeSpec>,
    /// The initial data.
    pub initial: Spanned<InitialSpec>,
    /// Where and what to write.
    #[serde(default)]
    pub output: OutputSpec,
}

/// How a spec names its system.
///
/// Only built-in systems exist so far (`system = "name"`); a `[system]` table defining a Lagrangian
/// by expressions is meant to become a second variant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SystemRef {
    /// A system of `ddirac::systems::BUILT_IN`, by name.
    BuiltIn(String),
}

impl<'de> Deserialize<'de> for SystemRef {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = SystemRef;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(
                    "the name of a built-in system (see `ddirac systems`); `[system]` tables are not supported yet",
                )
            }
            fn visit_str<E: serde::de::Error>(self, name: &str) -> Result<SystemRef, E> {
                Ok(SystemRef::BuiltIn(name.to_owned()))
            }
        }
        deserializer.deserialize_str(Visitor)
    }
}

/// `[method]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MethodSpec {
    /// `left`, `right`, `midpoint` (default) or `trapezoid`.
    pub rule: Option<Spanned<String>>,
    /// `plus` (default) or `minus`.
    pub variant: Option<Spanned<String>>,
    /// Reduced equations (default false).
    pub reduced: Option<Spanned<bool>>,
    /// K = h_{d,Σ}: n_g rows of n_x entries (default zeros).
    pub connection: Option<Spanned<Vec<Numbers>>>,
    /// Newton tolerance.
    pub tolerance: Option<Number>,
    /// Newton iteration limit.
    pub max_iterations: Option<Spanned<i64>>,
    /// Check the invariance of L_d before a reduced run (default true).
    pub check_invariance: Option<Spanned<bool>>,
}

/// `[time]`: any two of step, steps, duration (all three if consistent).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Step size h.
    pub step: Option<Number>,
    /// Number of steps N.
    pub steps: Option<Spanned<i64>>,
    /// Final time T = N h.
    pub duration: Option<Number>,
}

/// `[initial]`: q and exactly one of p, v, in the system's coordinate order.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Initial configuration.
    pub q: Numbers,
    /// Initial momenta.
    pub p: Option<Numbers>,
    /// Initial velocities.
    pub v: Option<Numbers>,
}

/// `[output]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output directory (relative to the current directory).
    pub directory: Option<Spanned<String>>,
    /// Report every `every`-th step (and the last).
    pub every: Option<Spanned<i64>>,
    /// Wrap angles to (−π, π] in the output.
    pub wrap_angles: Option<Spanned<bool>>,
}

/// Parses the spec text, reporting syntax errors, unknown keys and wrong types at their span.
pub fn parse(source: &SpecSource) -> Result<Spec, Box<SpecError>> {
    toml::from_str(source.text()).map_err(|e| {
        let message = e.message().trim_end().to_owned();
        let label = if message.starts_with("unknown field") { "unknown key" } else { "here" };
        let error = source.error(e.span(), format!("invalid spec: {message}"), label);
        if message.starts_with("unknown field") {
            error.with_help("remove the key or fix its spelling; the accepted keys are listed above")
        } else {
            error
        }
    })
}

/// Checks only that the text is TOML, reporting a syntax error at its span.
pub fn syntax(source: &SpecSource) -> Result<(), Box<SpecError>> {
    toml::from_str::<toml::Table>(source.text())
        .map(drop)
        .map_err(|e| source.error(e.span(), format!("invalid TOML: {}", e.message().trim_end()), "here"))
}

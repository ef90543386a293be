//! The run spec: a TOML file naming a system (or defining one by its Lagrangian), its parameters,
//! the method, the time grid, the initial data and the output options.
//!
//! ```text
//! system = "charged_particle"                 # a built-in system, or a [system] table:
//! [system]      name = "charged particle"  shape = ["x", "y", "z"]  group = ["theta"]
//!               angles = ["theta"]  order = [...]  lagrangian = "0.5*m*x_dot^2 + ..."
//!               attitude = "SO(3)"  symmetry = "SO(3)"   # a rigid system: L in R11..R33, Omega1..3
//! [system.definitions]  Ax = "-B0/2*y"        # named sub-expressions
//! [system.exact]        x = "sin(t)"          # exact solution, in `t` and the parameters
//! [[system.charts]]     name = "cap"  shape = ["u", "v"]  quality = "..."   # an atlas (with
//!                       to_main = { x = "..." }  from_main = { u = "..." }  # system.quality)
//! [parameters]  m = 1.0                       # overrides of the defaults, or the constants of L
//! [method]      rule = "left"  variant = "plus"  reduced = true  connection = [[0, 0, 0]]
//!               tolerance = 1e-12  max_iterations = 50  jacobian = "reuse"  check_invariance = true
//!               derivatives = "auto"  on_energy_jump = "warn"  energy_jump_threshold = 1e-3
//!               order = 2  composition = "suzuki"  atlas = true
//! [time]        step = 0.2  steps = 100  duration = 20.0   # any two, or all three if consistent
//! [initial]     q = [0, 0, 0, 0]  p = { x = 1, y = 0, z = 1, theta = 1 }   # or v = ...
//!               R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]  Pi = [0, 1, 0]   # rigid_body: or Omega = ...
//! [output]      directory = "out/cp"  every = 1  wrap_angles = false  plots = false  format = ["csv", "npy"]
//! ```
//!
//! The schema keeps every value [`Spanned`], so that [`validate`] can point at the text of any value
//! it rejects; unknown keys are refused by the parser itself, with the key's span.

pub(crate) mod expression;
pub(crate) mod initial;
mod lists;
mod spans;
mod strings;
mod time;
mod validate;

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

pub use time::changed_step;
pub(crate) use time::grid;
pub(crate) use validate::method as method_of;
pub use validate::{validate, Plan, Spans};

use crate::diagnostics::{SpecError, SpecSource};

/// The name of the built-in rigid body in specs (`system = "rigid_body"`), which `ddirac run` and
/// `ddirac check` take through [`crate::rigid`].
pub const RIGID_BODY: &str = "rigid_body";

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
    /// Members generated for `ddirac ensemble` (the other commands ignore it).
    pub ensemble: Option<Spanned<EnsembleSpec>>,
}

/// `[ensemble]`: the members of `ddirac ensemble` from grids and seeded random samples, and whether
/// their trajectories are written.
///
/// ```text
/// [ensemble]
/// trajectories = true            # q, p, energy of every member at the rows of output.every
/// samples = 100                  # random draws per grid point (with [[ensemble.random]])
/// seed = 7
/// [[ensemble.grid]]              # members: the Cartesian product of the axes, the first slowest,
/// key = "initial.q.phi1"         #   each grid point repeated for `samples` draws
/// from = 1.0                     # `count` equally spaced values from `from` to `to`, or
/// to = 2.5                       #   `values = [...]`
/// count = 16
/// [[ensemble.random]]
/// key = "parameters.B0"
/// normal = [1.0, 0.1]            # mean, standard deviation; or uniform = [low, high]
/// ```
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnsembleSpec {
    /// Write each member's rows (every `output.every`-th step) as NPY arrays (default false).
    pub trajectories: Option<Spanned<bool>>,
    /// Grid axes; the members are their Cartesian product, the first axis varying slowest.
    #[serde(default)]
    pub grid: Vec<Spanned<GridAxis>>,
    /// Random draws per grid point.
    pub samples: Option<Spanned<i64>>,
    /// Seed of the random draws (default 0).
    pub seed: Option<Spanned<i64>>,
    /// Keys drawn at random, in the order written.
    #[serde(default)]
    pub random: Vec<Spanned<RandomAxis>>,
}

/// `[[ensemble.grid]]`: one key's values, listed or equally spaced.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridAxis {
    /// The spec key, as `--set` names it.
    pub key: Spanned<String>,
    /// Listed values.
    pub values: Option<Numbers>,
    /// First of `count` equally spaced values.
    pub from: Option<Number>,
    /// Last of them.
    pub to: Option<Number>,
    /// How many.
    pub count: Option<Spanned<i64>>,
}

/// `[[ensemble.random]]`: one key drawn from a distribution.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomAxis {
    /// The spec key, as `--set` names it.
    pub key: Spanned<String>,
    /// `[low, high]`: uniform on [low, high).
    pub uniform: Option<Numbers>,
    /// `[mean, standard deviation]`: normal.
    pub normal: Option<Numbers>,
}

/// How a spec names its system.
#[derive(Debug)]
pub enum SystemRef {
    /// A system of `ddirac::systems::BUILT_IN`, by name: `system = "name"`.
    BuiltIn(String),
    /// A system defined by its Lagrangian: a `[system]` table.
    Expression(Box<SystemTable>),
}

impl<'de> Deserialize<'de> for SystemRef {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = SystemRef;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("the name of a built-in system (see `ddirac systems`) or a `[system]` table")
            }
            fn visit_str<E: serde::de::Error>(self, name: &str) -> Result<SystemRef, E> {
                Ok(SystemRef::BuiltIn(name.to_owned()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<SystemRef, A::Error> {
                let table = SystemTable::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(SystemRef::Expression(Box::new(table)))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// A list of names as written in the spec.
pub type Names = Spanned<Vec<Spanned<String>>>;
/// A table of expressions by name, as written in the spec.
pub type Sources = Spanned<BTreeMap<Spanned<String>, Spanned<String>>>;

/// `[system]`: a system defined by its Lagrangian.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SystemTable {
    /// A name for reports (default `custom`).
    pub name: Option<Spanned<String>>,
    /// The coordinates x of the shape space Σ.
    pub shape: Option<Names>,
    /// The coordinates g translated by the symmetry group G.
    pub group: Option<Names>,
    /// The coordinates (of either list) that live on S¹.
    pub angles: Option<Names>,
    /// The order of all coordinates (default: shape, then group).
    pub order: Option<Names>,
    /// L(q, q̇) in the coordinates, their velocities `<name>_dot`, the parameters and definitions.
    pub lagrangian: Spanned<String>,
    /// Named sub-expressions.
    pub definitions: Option<Sources>,
    /// An exact solution, coordinate name → expression in `t` and the parameters.
    pub exact: Option<Sources>,
    /// With an atlas: where the main chart is good (an expression in the coordinates and the
    /// parameters, about 1 where regular, falling to 0 at its singular set).
    pub quality: Option<Spanned<String>>,
    /// The other charts of the atlas, `[[system.charts]]`.
    pub charts: Option<Vec<Spanned<ChartTable>>>,
    /// `"SO(3)"`: the configuration holds an attitude R (body to space) besides the `shape`
    /// coordinates, and the Lagrangian is written in `R11` … `R33` and the body angular velocity
    /// `Omega1` … `Omega3` (a rigid system, [`crate::rigid`]).
    pub attitude: Option<Spanned<String>>,
    /// A rigid system's symmetry: the rotations of space leaving the Lagrangian invariant, `"SO(3)"`,
    /// `"vertical"` (about e3) or `"none"`.
    pub symmetry: Option<Spanned<String>>,
}

/// `[[system.charts]]`: a chart of the system's atlas (paper §6), with its coordinates, the maps to
/// and from the main chart and where it is good.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChartTable {
    /// A name for messages (default `chart <i>`).
    pub name: Option<Spanned<String>>,
    /// The chart's shape coordinates.
    pub shape: Option<Names>,
    /// The chart's group coordinates (translated by the same symmetry as the main chart's).
    pub group: Option<Names>,
    /// The chart's coordinates that live on S¹.
    pub angles: Option<Names>,
    /// The order of the chart's coordinates (default: shape, then group).
    pub order: Option<Names>,
    /// Each main-chart coordinate as an expression in the chart's coordinates and the parameters.
    pub to_main: Sources,
    /// Each of the chart's coordinates as an expression in the main chart's and the parameters.
    pub from_main: Sources,
    /// Where the chart is good, an expression in its coordinates and the parameters.
    pub quality: Spanned<String>,
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
    /// `reuse` (default: chord Newton, one Jacobian per step while it contracts) or `fresh`
    /// (classical Newton, a new Jacobian at every iterate).
    pub jacobian: Option<Spanned<String>>,
    /// Check the invariance of L_d before a reduced run (default true).
    pub check_invariance: Option<Spanned<bool>>,
    /// `auto` (default: compiled when possible), `compiled` (required) or `dual` (dual numbers).
    pub derivatives: Option<Spanned<String>>,
    /// What a jump of the energy between steps does: `warn` (default), `error` or `ignore`.
    pub on_energy_jump: Option<Spanned<String>>,
    /// Smallest change of the energy in one step, relative to its scale, that may count as a jump.
    pub energy_jump_threshold: Option<Number>,
    /// The order of the method: 2 (default: the basic step), 4, 6 or 8 (a symmetric composition of
    /// the basic step; midpoint and trapezoid rules only).
    pub order: Option<Spanned<i64>>,
    /// The coefficient set of a composition: `suzuki` (order 4's default), `kahan-li` (order 6's and
    /// 8's default) or `triple-jump` (orders 4, 6, 8).
    pub composition: Option<Spanned<String>>,
    /// Switch between the charts of the system's atlas where the current one degrades (default
    /// true; without an atlas there is nothing to switch).
    pub atlas: Option<Spanned<bool>>,
    /// Propagate the tangent map d(q_N, p_N)/d(q_0, p_0) through every step (default false):
    /// summary.json's `sensitivity.state`.
    pub sensitivities: Option<Spanned<bool>>,
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

/// `[initial]`: q and exactly one of p, v, each in the coordinate order or by coordinate name; for
/// a rigid body (`system = "rigid_body"`), the attitude R and exactly one of Π, Ω instead.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Initial configuration.
    pub q: Option<Spanned<Vector>>,
    /// Initial momenta.
    pub p: Option<Spanned<Vector>>,
    /// Initial velocities.
    pub v: Option<Spanned<Vector>>,
    /// A rigid body's initial attitude R (body to space): three rows of three numbers.
    #[serde(rename = "R")]
    pub r: Option<Spanned<Vec<Numbers>>>,
    /// A rigid body's initial body angular momentum Π.
    #[serde(rename = "Pi")]
    pub pi: Option<Numbers>,
    /// A rigid body's initial body angular velocity Ω.
    #[serde(rename = "Omega")]
    pub omega: Option<Numbers>,
}

/// One number per coordinate: an array in the coordinate order, or a table by coordinate name.
#[derive(Debug)]
pub enum Vector {
    /// `[1.0, 0.0]`.
    InOrder(Vec<Number>),
    /// `{ x = 1.0, theta = 0.0 }`, in the order written.
    ByName(Vec<(Spanned<String>, Number)>),
}

impl<'de> Deserialize<'de> for Vector {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Vector;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("an array of numbers in coordinate order, or a table of numbers by coordinate name")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vector, A::Error> {
                let mut values = vec![];
                while let Some(value) = seq.next_element()? {
                    values.push(value);
                }
                Ok(Vector::InOrder(values))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Vector, A::Error> {
                let mut values = vec![];
                while let Some(entry) = map.next_entry()? {
                    values.push(entry);
                }
                Ok(Vector::ByName(values))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
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
    /// Trajectory formats: `["csv"]` (default), `["npy"]` or both.
    pub format: Option<Spanned<Vec<crate::output::Format>>>,
    /// Draw the run's figures (PNG and SVG) into the output directory (default false).
    pub plots: Option<Spanned<bool>>,
}

/// Parses the spec text, reporting syntax errors, unknown keys and wrong types at their span.
pub fn parse(source: &SpecSource) -> Result<Spec, Box<SpecError>> {
    toml::from_str(source.text()).map_err(|e| {
        let message = e.message().trim_end().to_owned();
        let label = if message.starts_with("unknown field") { "unknown key" } else { "here" };
        let error = source.error(e.span(), format!("invalid spec: {message}"), label);
        if message.starts_with("unknown field") {
            error.with_help("remove the key or fix its spelling; the accepted keys are listed above")
        } else if let Some(help) = integer_help(&message) {
            error.with_help(help)
        } else {
            error
        }
    })
}

/// The help for a float where the key takes an integer (`invalid type: floating point `1000.0`,
/// expected i64`): the integer it equals, if it is one TOML takes, else the range of TOML integers.
fn integer_help(message: &str) -> Option<String> {
    let value = message.strip_prefix("invalid type: floating point `")?.split('`').next()?;
    if !message.ends_with("expected i64") {
        return None;
    }
    let value: f64 = value.parse().ok()?;
    Some(match integral(value) {
        Some(n) => format!("this key takes an integer: write `{n}`, without a decimal point or exponent"),
        None => format!(
            "this key takes an integer, in {}..={}: write one without a decimal point or exponent",
            i64::MIN,
            i64::MAX
        ),
    })
}

/// `v` as an i64, if it is one exactly.
pub fn integral(v: f64) -> Option<i64> {
    // 2⁶³ is the first f64 above i64::MAX; −2⁶³ is i64::MIN.
    let bound = 2f64.powi(63);
    (v.fract() == 0.0 && (-bound..bound).contains(&v)).then_some(v as i64)
}

/// Checks only that the text is TOML, reporting a syntax error at its span.
pub fn syntax(source: &SpecSource) -> Result<(), Box<SpecError>> {
    toml::from_str::<toml::Table>(source.text())
        .map(drop)
        .map_err(|e| source.error(e.span(), format!("invalid TOML: {}", e.message().trim_end()), "here"))
}

/// `value`, if it is finite; `what` names it in the error.
pub(crate) fn finite(source: &SpecSource, value: &Number, what: &str) -> Result<f64, Box<SpecError>> {
    let v = *value.get_ref();
    if v.is_finite() {
        Ok(v)
    } else {
        Err(source.error(Some(value.span()), format!("{what} is not finite ({v})"), "not a finite number"))
    }
}

//! # ddirac — discrete Dirac reduction
//!
//! Structure-preserving integrators for (possibly degenerate) Lagrangian systems with an abelian
//! symmetry, after *Discrete Dirac reduction of implicit Lagrangian systems with abelian symmetry
//! groups* (Rodríguez Abella & Leok). Equation labels in the docs refer to that paper.
//!
//! A [`System`] knows its Lagrangian, coordinates and symmetry; a [`Problem`] adds the step, the
//! number of steps and initial data; a [`Method`] chooses the quadrature [`Rule`], the (+)/(−)
//! [`Variant`], reduced or unreduced equations and the [`Connection`]; [`integrate`] (streaming rows)
//! or [`solve`] (keeping them) joins the three, and a [`Stepper`] takes their run one step at a time,
//! with a [`State`] to save and restart from. [`DynSystem`] erases the system's type and dimension for
//! the command line and bindings.
//!
//! ```
//! use ddirac::{solve, Method, OutputOptions, Rule, systems::ChargedParticle};
//! let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
//! let solution = solve(&ChargedParticle::default(), &ChargedParticle::paper_problem(200), &method,
//!                      &OutputOptions::default()).unwrap();
//! // Paper, Table 1: N = 200 → 0.01664
//! assert!((solution.summary.reference_error.unwrap() - 0.01664).abs() < 5e-6);
//! ```
#![warn(missing_docs)]
//!
//! The API is the crate root (with [`prelude`] for one import), the modules a system's author
//! reaches for ([`systems`], [`expression`], [`atlas`], [`chart`], [`ensemble`], [`diagnostics`],
//! [`mechanics`], [`reduction`], [`composition`], [`dim`], [`ad`], [`interrupt`]). The modules hidden
//! from the documentation ([`baselines`]: the benchmarks' peers; [`compiled`]: the compiler's
//! programs; [`newton`], [`sampling`], [`stack`]) are public for the command line, the bindings, the
//! benchmarks and the tests, and may change without notice.

pub mod ad;
pub mod atlas;
#[doc(hidden)]
pub mod baselines;
pub mod blend;
pub mod chart;
mod check;
#[doc(hidden)]
pub mod compiled;
pub mod composition;
mod coordinate;
pub mod diagnostics;
pub mod dim;
mod energy_jump;
pub mod ensemble;
mod erased;
mod error;
pub mod expression;
mod integrator;
pub mod interrupt;
mod linalg;
pub mod mechanics;
#[doc(hidden)]
pub mod newton;
mod padding;
mod periodicity;
pub mod prelude;
mod problem;
pub mod reduction;
pub mod relative_equilibrium;
pub mod rigid;
mod runtime_sized;
#[doc(hidden)]
pub mod sampling;
mod scalar;
mod scheme;
mod setup;
mod sizes;
#[doc(hidden)]
pub mod stack;
mod stepper;
mod system;
pub mod systems;
pub mod tangent_map;

pub use check::{check, ChartFinding, CheckReport, Finding, CONSTRAINT_TOLERANCE, ROUND_TRIP_TOLERANCE};
pub use composition::Composition;
pub use coordinate::{Coordinate, CoordinateKind, Role, Split};
pub use diagnostics::{DerivativePath, OutputError, Row, Solution, Stats, Summary, Warning, WarningKind};
pub use energy_jump::{EnergyJump, JumpAction, ENERGY_DRIFT};
pub use erased::{DynRow, DynState, DynStepper, DynSystem, Erased, ErasedDynamic, Holds};
pub use error::{ChartProblem, EnergyChange, Error, Hypothesis, Input, Reason, SingularLegendre, Time};
pub use integrator::{integrate, integrate_watched, solve};
pub use mechanics::discrete_lagrangian::{DiscreteLagrangian, Rule};
pub use newton::NewtonOptions;
/// The scalar trait user Lagrangians are written against (`DualNum<Primitive = f64>`), re-exported so that
/// a system and the engine always agree on its version.
pub use num_dual;
pub use problem::{Differentiation, InitialData, InitialMomentum, Method, OutputOptions, Problem, Variant};
pub use reduction::connection::Connection;
pub use scalar::{RuntimeInput, Scalar};
pub use sizes::{sizes_text, SIZES};
pub use stepper::{
    OwnedRow, OwnedRowIn, State, StateIn, StepReport, Stepper, StepperIn, IMPLAUSIBLE_ENERGY_CHANGE, KICK,
    LEGENDRE_DROP, LOOSE_TOLERANCE_MARGIN, MAX_ANGLE_STEP, MAX_SUBDIVISION, SOFT_KICK, WATCH_STEPS,
};
pub use system::{Chart, System};

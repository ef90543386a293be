//! Errors of the library.

use crate::newton::FailureReason;
use std::fmt;

/// Everything that can go wrong in setting up or running an integration.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A vector or matrix has the wrong number of entries.
    #[error("{what} has {found} entries, but the system has {expected} coordinates")]
    Size {
        /// What was given.
        what: Input,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{} is not finite ({value})", Entry(what, *entry))]
    NonFinite {
        /// Which input.
        what: Input,
        /// The position of the value in it (from 0), when it is a vector.
        entry: Option<usize>,
        /// The offending value.
        value: f64,
    },
    /// An input is out of range or inconsistent.
    #[error("invalid {what}: {why}")]
    Invalid {
        /// Which input.
        what: Input,
        /// Why it is rejected.
        why: Reason,
    },
    /// Newton's method failed on a step.
    #[error(
        "step {step} (t = {}, h = {}): Newton's method failed after {iterations} iteration(s): {reason} \
         (residual {residual:.3e}); {}", Time(*t), Time(*h), NewtonCause(*reason, singular.as_ref(), *sub_steps)
    )]
    Newton {
        /// Index k of the step q_k → q_{k+1}.
        step: usize,
        /// Time t_k.
        t: f64,
        /// The run's step h.
        h: f64,
        /// Corrections taken.
        iterations: usize,
        /// Last residual norm.
        residual: f64,
        /// Why it stopped.
        reason: FailureReason,
        /// What the chart watch saw at the predicted step, when it saw it: the Legendre map near-singular.
        singular: Option<SingularLegendre>,
        /// The most sub-steps the step was also tried as (2, 4, …, this), when it was subdivided.
        sub_steps: Option<usize>,
    },
    /// The search for a relative equilibrium stopped without one
    /// ([`crate::relative_equilibrium::find`]).
    #[error(
        "no relative equilibrium found after {iterations} Newton correction(s) (‖Φ_h(x) − x‖∞ = {residual:.3e}): \
         {cause}"
    )]
    RelativeEquilibrium {
        /// Newton corrections taken.
        iterations: usize,
        /// The last residual ‖Φ_h(x) − x‖∞.
        residual: f64,
        /// Why the search stopped.
        cause: SearchFailure,
    },
    /// The state became NaN or infinite.
    #[error("step {step} (t = {}, h = {}): the state became non-finite", Time(*t), Time(*h))]
    Diverged {
        /// Index k of the step.
        step: usize,
        /// Time t_k.
        t: f64,
        /// The run's step h.
        h: f64,
    },
    /// The discrete Lagrangian is not invariant under the symmetry, so it cannot be reduced.
    #[error(
        "the discrete Lagrangian is not invariant under translation of the group coordinate \
         `{coordinate}`: L_d changes by {deviation:.2e} (relative), more than the tolerance {tolerance:.0e}"
    )]
    NotInvariant {
        /// The group coordinate whose translation changes L_d.
        coordinate: String,
        /// Largest relative change observed.
        deviation: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// A hypothesis of the run could not be tested: L_d is finite at too few pairs near the initial
    /// data.
    #[error(
        "{hypothesis} `{coordinate}` could not be tested: L_d is finite at only {samples} of the {wanted} \
         pairs sought near the initial data"
    )]
    Undecided {
        /// The hypothesis.
        hypothesis: Hypothesis,
        /// The coordinate it concerns: a group coordinate for the invariance, an angle for the
        /// periodicity.
        coordinate: String,
        /// Pairs with a finite L_d.
        samples: usize,
        /// Pairs sought.
        wanted: usize,
    },
    /// The Lagrangian is not 2π-periodic in a coordinate declared an angle, so the chart may not wrap
    /// it.
    #[error(
        "the Lagrangian is not 2π-periodic in the angle `{coordinate}`: L_d changes by {deviation:.2e} \
         (relative) under a shift by 2π, more than the tolerance {tolerance:.0e}"
    )]
    NotPeriodic {
        /// The angle coordinate.
        coordinate: String,
        /// Largest relative change observed.
        deviation: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// A degenerate Lagrangian with an initial momentum off the primary constraint p = ∂L/∂v.
    #[error(
        "the Lagrangian is degenerate (rank {rank} of {coordinates}) and p0 does not satisfy the primary \
         constraint p = ∂L/∂v(q0, v): mismatch {mismatch:.3e}"
    )]
    OffPrimaryConstraint {
        /// Rank of ∂²L/∂v² at (q0, v0).
        rank: usize,
        /// Number of coordinates.
        coordinates: usize,
        /// ‖∂L/∂v(q0, v0) − p0‖∞ for the best velocity v0.
        mismatch: f64,
    },
    /// The energy of a step jumped (see [`crate::diagnostics::WarningKind::EnergyJump`]) and the
    /// method asks for this to be an error.
    #[error("step {step} (t = {}, h = {}): {change}{}", Time(*t), Time(*h), Cause(singular.as_ref()))]
    EnergyJump {
        /// Index k of the step.
        step: usize,
        /// Time t_k.
        t: f64,
        /// The run's step h.
        h: f64,
        /// How the energy moved.
        change: EnergyChange,
        /// What the chart watch saw there, when it saw it: the Legendre map near-singular.
        singular: Option<SingularLegendre>,
    },
    /// The run was asked to stop ([`crate::interrupt::request`]) and stopped before step `step`.
    #[error("interrupted before step {step} (t = {})", Time(*t))]
    Interrupted {
        /// Index k of the step that was not taken.
        step: usize,
        /// Time t_k.
        t: f64,
    },
    /// A reduced run of a system with no group coordinates.
    #[error("reduction needs at least one group coordinate; the system has none")]
    NoSymmetry,
    /// The step equations do not determine the next configuration: their Jacobian (D1D2 L_d, or the
    /// reduced l̂'s mixed block) is singular at the first step, as for a Lagrangian that vanishes or
    /// does not depend on the velocity of some coordinate.
    #[error(
        "the step equations do not determine the motion: their Jacobian D1D2 L_d has rank {rank} of {coordinates} \
         at the first step (a Lagrangian that vanishes, or on which some coordinate has no effect, or the reduction \
         of one that is not invariant leaves the motion undetermined)"
    )]
    Undetermined {
        /// The rank of the Jacobian at the first step.
        rank: usize,
        /// Number of coordinates.
        coordinates: usize,
    },
    /// A chart of the system's atlas fails a hypothesis a run through it relies on ([`crate::check`]).
    #[error("chart `{chart}` of the atlas: {problem}")]
    Chart {
        /// The chart's name.
        chart: String,
        /// What is wrong with it.
        problem: ChartProblem,
    },
    /// A reduced run of a rigid system whose Lagrangian is not declared invariant under every rotation
    /// of space: the reduction by SO(3) would be wrong.
    #[error(
        "reduction by SO(3) needs a Lagrangian invariant under every rotation of space; this system's symmetry \
         is `{symmetry}`{}: run it unreduced (`reduced = false`), which conserves {}",
        if *symmetry == "vertical" { " (rotations about the vertical e3 only, as gravity allows)" } else { "" },
        if *symmetry == "vertical" { "the vertical angular momentum e3 · R Π" } else { "what the system conserves" }
    )]
    NotReducible {
        /// The symmetry the system declares ([`crate::rigid::Symmetry::name`]).
        symmetry: &'static str,
    },
    /// A rigid system's Lagrangian is not invariant under the rotations it declares as its symmetry.
    #[error(
        "the Lagrangian is not invariant under its declared symmetry `{symmetry}`: ℓ(g R, Ω, s, ṡ) differs from \
         ℓ(R, Ω, s, ṡ) by {deviation:.2e} (relative) for a rotation g of that group, more than the tolerance \
         {tolerance:.0e}"
    )]
    NotInvariantUnderRotations {
        /// The declared symmetry ([`crate::rigid::Symmetry::name`]).
        symmetry: &'static str,
        /// Largest relative change observed.
        deviation: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// Compiled derivatives were required (`method.derivatives = "compiled"`) but could not be built.
    #[error("compiled derivatives are not available: {0}")]
    NotCompiled(#[source] crate::compiled::CompileError),
    /// The consumer of the output rows failed (e.g. a full disk).
    #[error("writing output failed: {0}")]
    Output(#[source] Box<dyn std::error::Error + Send + Sync>),
}

/// Why an input is rejected ([`Error::Invalid`]): the rule it breaks and the numbers that break it.
/// Its display is the sentence the error says after the input's name.
///
/// ```
/// use ddirac::{Error, Input, InitialMomentum, Method, OutputOptions, Problem, Reason, solve, systems::ChargedParticle};
/// let problem = Problem::new(-0.1, 10, vec![0.0; 4], InitialMomentum::Momentum(vec![0.0; 4]));
/// let error = solve(&ChargedParticle::default(), &problem, &Method::default(), &OutputOptions::default()).unwrap_err();
/// assert!(matches!(error, Error::Invalid { what: Input::Step, why: Reason::NotPositiveFinite { value } } if value == -0.1));
/// assert_eq!(error.to_string(), "invalid step: must be positive and finite, got -0.1");
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Reason {
    /// A value that must be positive.
    NotPositive {
        /// The value given.
        value: f64,
    },
    /// A value that must be positive and finite.
    NotPositiveFinite {
        /// The value given.
        value: f64,
    },
    /// A count that must be at least 1 was 0.
    Zero,
    /// A parameter the system does not have.
    UnknownParameter {
        /// The parameters it has.
        known: Vec<String>,
    },
    /// A number of links that is not a positive whole number.
    NotANumberOfLinks {
        /// The value given.
        value: f64,
    },
    /// A chain of a fixed number of links given another.
    OtherLinks {
        /// The chain's links.
        links: usize,
        /// The value given.
        value: f64,
    },
    /// More links than a chain may have (its Newton Jacobian is dense).
    TooManyLinks {
        /// The links asked for.
        links: f64,
        /// The most there may be.
        max: usize,
    },
    /// A step asked of a run that has taken all its steps.
    Finished {
        /// The run's number of steps.
        steps: usize,
    },
    /// A state beyond the problem's last step.
    BeyondLastStep {
        /// The state's step.
        step: usize,
        /// The problem's last step.
        last: usize,
    },
    /// A warm state from a stepper with another method or step.
    AnotherMethod,
    /// A state taken in a chart the system does not have.
    NoSuchChart {
        /// The state's chart.
        chart: usize,
    },
    /// A state whose point is outside the chart it was taken in.
    OutsideChart {
        /// The state's chart.
        chart: usize,
    },
    /// A composition of a basic rule that is not symmetric.
    NotSymmetric {
        /// The composition's order.
        order: u8,
        /// The rule's name.
        rule: &'static str,
    },
    /// A connection with which the reduced step equations are singular in floating point.
    SingularInFloatingPoint {
        /// K's largest entry.
        largest: f64,
        /// The rank of the step equations' Jacobian at the first step.
        rank: usize,
        /// The number of coordinates.
        coordinates: usize,
    },
    /// Rows of K of unequal lengths.
    UnequalRows {
        /// The row (from 1).
        row: usize,
        /// Its entries.
        found: usize,
        /// The entries of row 1.
        first: usize,
    },
    /// A non-finite entry of K.
    NonFiniteEntry {
        /// The row (from 1).
        row: usize,
        /// The entry.
        value: f64,
    },
    /// K with another number of rows than the group coordinates.
    Rows {
        /// The group coordinates.
        expected: usize,
        /// K's rows.
        found: usize,
    },
    /// K's rows of another length than the shape coordinates.
    Columns {
        /// The shape coordinates.
        expected: usize,
        /// K's entries per row.
        found: usize,
    },
    /// K of another shape than the system's group × shape coordinates.
    Shape {
        /// K's rows.
        rows: usize,
        /// K's columns.
        columns: usize,
        /// The group coordinates.
        group: usize,
        /// The shape coordinates.
        shape: usize,
    },
    /// K fails an axiom of the paper's Definition 2.1 of a discrete connection.
    Axiom {
        /// The axiom.
        axiom: &'static str,
        /// By how much it fails.
        deviation: f64,
    },
    /// A matrix that is not a rotation: RᵀR ≠ I or det R ≠ 1 beyond the tolerance.
    NotARotation {
        /// The largest entry of |RᵀR − I|.
        orthogonality: f64,
        /// det R.
        determinant: f64,
        /// The tolerance both are held to.
        tolerance: f64,
    },
    /// Initial data whose energy overflows f64.
    EnergyOverflow {
        /// The energy computed.
        energy: f64,
    },
    /// A reason given by a front end (the command line's thread pool, say).
    Other(String),
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Reason::NotPositive { value } => write!(f, "must be positive, got {value}"),
            Reason::NotPositiveFinite { value } => write!(f, "must be positive and finite, got {value}"),
            Reason::Zero => f.write_str("must be at least 1"),
            Reason::UnknownParameter { known } => write!(f, "unknown; known parameters: {}", known.join(", ")),
            Reason::NotANumberOfLinks { value } => {
                write!(f, "{value} is not a number of links: a positive whole number")
            }
            Reason::OtherLinks { links, value } => write!(f, "this chain has {links} links, got {value}"),
            Reason::TooManyLinks { links, max } => write!(
                f,
                "{links} links are more than {max}: a step's Newton Jacobian is dense, n² numbers ({} GB here)",
                8.0 * links * links / 1e9
            ),
            Reason::Finished { steps } => write!(f, "the run has taken all its {steps} steps"),
            Reason::BeyondLastStep { step, last } => write!(f, "step {step} is beyond the problem's last step {last}"),
            Reason::AnotherMethod => f.write_str(
                "it was taken from a stepper with another method or step; restart from its cold form (`State::cold`)",
            ),
            Reason::NoSuchChart { chart } => {
                write!(f, "it was taken in chart {chart}, which this system does not have")
            }
            Reason::OutsideChart { chart } => write!(f, "its point is outside chart {chart}"),
            Reason::NotSymmetric { order, rule } => write!(
                f,
                "a composition of order {order} needs a symmetric rule (`midpoint` or `trapezoid`); the `{rule}` rule \
                 is not symmetric, and its compositions keep order 1"
            ),
            Reason::SingularInFloatingPoint { largest, rank, coordinates } => write!(
                f,
                "with this K (largest entry {largest:e}) the reduced step equations are singular in floating point: \
                 their Jacobian has rank {rank} of {coordinates} at the first step, full rank with K = 0, and its \
                 condition grows as |K|⁴; reduce with a K of smaller entries or run the unreduced equations \
                 (`reduced = false`)"
            ),
            Reason::UnequalRows { row, found, first } => write!(
                f,
                "row {row} of K has {found} entries, but row 1 has {first}: K has one entry per shape coordinate in \
                 every row"
            ),
            Reason::NonFiniteEntry { row, value } => write!(f, "row {row} of K contains the non-finite value {value}"),
            Reason::Rows { expected, found } => {
                write!(f, "K must have one row per group coordinate ({expected}), found {found} rows")
            }
            Reason::Columns { expected, found } => {
                write!(f, "row 1 of K has {found} entries, expected one per shape coordinate ({expected})")
            }
            Reason::Shape { rows, columns, group, shape } => {
                write!(f, "K is {rows}×{columns}, the system has {group} group and {shape} shape coordinates")
            }
            Reason::Axiom { axiom, deviation } => write!(f, "axiom {axiom} of Definition 2.1 fails by {deviation:.2e}"),
            Reason::NotARotation { orthogonality, determinant, tolerance } => write!(
                f,
                "not a rotation: |RᵀR − I| is {orthogonality:.2e} and det R = {determinant} (both must hold to \
                 {tolerance:.0e}: R orthogonal with determinant 1)"
            ),
            Reason::EnergyOverflow { energy } => {
                write!(f, "the energy at the initial data is {energy}: it overflows the range of f64 (scale the units)")
            }
            Reason::Other(why) => f.write_str(why),
        }
    }
}

/// The Legendre map ∂²L/∂v² near-singular where a step failed or the energy jumped: the coordinates
/// are singular nearby (a pole of spherical coordinates, say). What the chart watch reports.
#[derive(Debug, Clone, PartialEq)]
pub struct SingularLegendre {
    /// The coordinate along which ∂²L/∂v² is nearest to singular.
    pub coordinate: String,
    /// Its smallest pivot over its largest here.
    pub ratio: f64,
    /// The same ratio at the start of the run.
    pub at_start: f64,
}

impl fmt::Display for SingularLegendre {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (ratio, at_start, name) = (self.ratio, self.at_start, &self.coordinate);
        write!(
            f,
            "the Legendre map ∂²L/∂v² is near-singular here (its smallest pivot is {ratio:.1e} of its largest, \
             against {at_start:.1e} at the start), along `{name}`: the coordinates are singular nearby (a pole \
             of spherical coordinates, say), so `{name}` and its momentum are ill-conditioned"
        )
    }
}

/// How the energy of a step moved when it failed the run ([`Error::EnergyJump`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EnergyChange {
    /// The energy jumped and did not come back (the energy watch, [`crate::diagnostics::WarningKind::EnergyJump`]).
    Jumped(crate::energy_jump::Jump),
    /// One step moved the discrete energy by `relative` of its scale, more than `limit`, which no
    /// step that resolves the motion does.
    Implausible {
        /// The change over the energy's scale.
        relative: f64,
        /// The largest change a resolved step makes, relative.
        limit: f64,
    },
}

impl fmt::Display for EnergyChange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EnergyChange::Jumped(jump) => f.write_str(&jump.describe()),
            EnergyChange::Implausible { relative, limit } => write!(
                f,
                "its discrete energy moved by {:.1} % from the last step's, more than the {} % a resolved step moves it",
                relative * 100.0,
                limit * 100.0
            ),
        }
    }
}

/// "; " and the cause, when there is one.
struct Cause<'a>(Option<&'a SingularLegendre>);

impl fmt::Display for Cause<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(cause) => write!(f, "; {cause}"),
            None => Ok(()),
        }
    }
}

/// What explains a failure of Newton's method: what the chart watch saw and the sub-steps tried, or
/// else what a user can try about the reason.
struct NewtonCause<'a>(FailureReason, Option<&'a SingularLegendre>, Option<usize>);

impl fmt::Display for NewtonCause<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let tried = self.2.map(|m| format!("nor as 2, 4, …, {m} sub-steps"));
        match (self.1, tried) {
            (Some(singular), Some(tried)) => write!(f, "{singular}; {tried}"),
            (Some(singular), None) => write!(f, "{singular}"),
            (None, Some(tried)) => f.write_str(&tried),
            (None, None) => f.write_str(hint(self.0)),
        }
    }
}

/// What a user can try about a failure of Newton's method on a step.
fn hint(reason: FailureReason) -> &'static str {
    match reason {
        FailureReason::NotConverged => "try a smaller step, a looser tolerance or more iterations",
        FailureReason::SingularJacobian => {
            "the step equations are degenerate here: for a reduced run check that the Lagrangian is \
             invariant (the check of the run's hypotheses); otherwise try a smaller step"
        }
        FailureReason::NonFinite => "try a smaller step; check the Lagrangian for singular points",
    }
}

/// The input an error is about: a field of [`crate::Problem`], [`crate::Method`] or
/// [`crate::OutputOptions`], a system's parameter, or the state a stepper restarts from. Its display
/// is the name error messages use.
///
/// ```
/// use ddirac::{Error, Input, InitialMomentum, Method, OutputOptions, Problem, solve, systems::ChargedParticle};
/// let problem = Problem::new(0.1, 10, vec![0.0; 3], InitialMomentum::Momentum(vec![0.0; 4]));
/// let error = solve(&ChargedParticle::default(), &problem, &Method::default(), &OutputOptions::default()).unwrap_err();
/// assert!(matches!(error, Error::Size { what: Input::InitialConfiguration, expected: 4, found: 3 }));
/// assert_eq!(error.to_string(), "initial configuration q has 3 entries, but the system has 4 coordinates");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Input {
    /// The step size h ([`crate::Problem::step`]).
    Step,
    /// The number of steps ([`crate::Problem::steps`]).
    Steps,
    /// How often rows are reported ([`crate::OutputOptions::every`]).
    Every,
    /// The initial configuration q0 ([`crate::Problem::q0`]).
    InitialConfiguration,
    /// The initial momentum p0 as given ([`crate::InitialMomentum::Momentum`]).
    InitialMomentum,
    /// The initial velocity v0 as given ([`crate::InitialMomentum::Velocity`]).
    InitialVelocity,
    /// The initial momentum p0 = ∂L/∂v(q0, v0) that the given velocity v0 maps to.
    MomentumFromVelocity,
    /// The connection K ([`crate::Method::connection`]).
    Connection,
    /// The composition of a step ([`crate::Method::composition`]).
    Composition,
    /// A parameter of a system, by name.
    Parameter(String),
    /// The state a stepper restarts from ([`crate::Stepper::restart`]); its entries are those of q,
    /// then those of p.
    State,
    /// An argument of a function of the library, by the name its documentation gives it.
    Argument(String),
    /// The initial attitude R0 of a rigid system ([`crate::rigid::RigidProblem::r0`]).
    InitialAttitude,
    /// The initial body angular momentum Π0 of a rigid system.
    InitialAngularMomentum,
    /// The initial body angular velocity Ω0 of a rigid system.
    InitialAngularVelocity,
}

impl std::fmt::Display for Input {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Input::Step => f.write_str("step"),
            Input::Steps => f.write_str("steps"),
            Input::Every => f.write_str("output.every"),
            Input::InitialConfiguration => f.write_str("initial configuration q"),
            Input::InitialMomentum => f.write_str("initial momentum p"),
            Input::InitialVelocity => f.write_str("initial velocity v"),
            Input::MomentumFromVelocity => f.write_str("initial momentum p = ∂L/∂v(q0, v0)"),
            Input::Connection => f.write_str("connection"),
            Input::Composition => f.write_str("composition"),
            Input::Parameter(name) => write!(f, "parameter `{name}`"),
            Input::State => f.write_str("state (q, p)"),
            Input::Argument(name) => f.write_str(name),
            Input::InitialAttitude => f.write_str("initial attitude R"),
            Input::InitialAngularMomentum => f.write_str("initial body angular momentum Π"),
            Input::InitialAngularVelocity => f.write_str("initial body angular velocity Ω"),
        }
    }
}

/// An input, or one entry of it: "entry 2 of the initial configuration q".
struct Entry<'a>(&'a Input, Option<usize>);

impl std::fmt::Display for Entry<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.1 {
            Some(i) => write!(f, "entry {} of the {}", i + 1, self.0),
            None => write!(f, "{}", self.0),
        }
    }
}

/// A hypothesis of a run that is tested before its first step ([`crate::check`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Hypothesis {
    /// The invariance of L_d under translations of a group coordinate (paper §4).
    Invariance,
    /// The 2π-periodicity of L in an angle coordinate (paper §6).
    Periodicity,
}

impl std::fmt::Display for Hypothesis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Hypothesis::Invariance => "the invariance of L_d under the group coordinate",
            Hypothesis::Periodicity => "the 2π-periodicity of L in the angle",
        })
    }
}

/// What is wrong with a chart of an atlas ([`Error::Chart`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ChartProblem {
    /// None of the points sampled over the main chart falls where the chart's quality is positive.
    NoDomain {
        /// Main-chart points sampled.
        points: usize,
    },
    /// Its maps are not inverse: ψ(φ(q')) ≠ q' at the chart point `at`.
    NotInverse {
        /// |ψ(φ(q')) − q'|∞ / (1 + |q'|∞) there (infinite where φ(q') is not finite).
        deviation: f64,
        /// The chart point.
        at: Vec<f64>,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// Its quality says it is good at the chart point `at`, where ∂²L/∂v² in the chart is singular.
    SingularWhereGood {
        /// The chart point.
        at: Vec<f64>,
        /// The chart's quality there.
        quality: f64,
    },
    /// The Lagrangian in the chart is not invariant under translation of its group coordinate.
    NotInvariant {
        /// The chart's group coordinate.
        coordinate: String,
        /// Largest relative change of L_d observed.
        deviation: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// The Lagrangian in the chart is not 2π-periodic in a coordinate of the chart declared an angle.
    NotPeriodic {
        /// The chart's angle.
        coordinate: String,
        /// Largest relative change of L_d observed.
        deviation: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// A hypothesis could not be tested in the chart: L_d is finite at too few pairs there.
    Undecided {
        /// The hypothesis.
        hypothesis: Hypothesis,
        /// The chart's coordinate it concerns.
        coordinate: String,
        /// Pairs with a finite L_d.
        samples: usize,
    },
}

impl std::fmt::Display for ChartProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let point = |at: &[f64]| at.iter().map(|x| format!("{x:.6}")).collect::<Vec<_>>().join(", ");
        match self {
            ChartProblem::NoDomain { points } => write!(
                f,
                "none of {points} points sampled over the main chart falls where its quality is positive, so its maps \
                 cannot be tested (check its `quality` and `from_main`)"
            ),
            ChartProblem::NotInverse { deviation, at, tolerance } => write!(
                f,
                "its maps are not inverse: from its point ({}) to the main chart and back lands {deviation:.2e} \
                 (relative) away, more than the tolerance {tolerance:.0e}; `to_main` must be the inverse of \
                 `from_main` wherever the chart's quality is positive",
                point(at)
            ),
            ChartProblem::SingularWhereGood { at, quality } => write!(
                f,
                "its quality is {quality:.3} at its point ({}), where the Lagrangian in the chart has a singular \
                 ∂²L/∂v²: the chart is not good where its quality says it is",
                point(at)
            ),
            ChartProblem::NotInvariant { coordinate, deviation, tolerance } => write!(
                f,
                "the discrete Lagrangian in the chart is not invariant under translation of its group coordinate \
                 `{coordinate}`: L_d changes by {deviation:.2e} (relative), more than the tolerance {tolerance:.0e}; \
                 a reduced run would reduce by a symmetry that is not one (declare `{coordinate}` a shape coordinate)"
            ),
            ChartProblem::NotPeriodic { coordinate, deviation, tolerance } => write!(
                f,
                "the Lagrangian in the chart is not 2π-periodic in its angle `{coordinate}`: L_d changes by \
                 {deviation:.2e} (relative) under a shift by 2π, more than the tolerance {tolerance:.0e}"
            ),
            ChartProblem::Undecided { hypothesis, coordinate, samples } => write!(
                f,
                "{hypothesis} `{coordinate}` could not be tested: L_d in the chart is finite at only {samples} pairs \
                 near its best sampled point"
            ),
        }
    }
}

/// A time t_k = k·h as people write it: at most 12 significant digits (72.1, not 72.10000000000001).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Time(pub f64);

impl std::fmt::Display for Time {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let t = self.0;
        if t == 0.0 || !t.is_finite() {
            return write!(f, "{t}");
        }
        let rounded: f64 = format!("{t:.11e}").parse().unwrap_or(t);
        if (1e-4..1e15).contains(&rounded.abs()) {
            write!(f, "{rounded}")
        } else {
            write!(f, "{rounded:e}")
        }
    }
}

/// Why the search for a relative equilibrium ([`crate::relative_equilibrium::find`]) stopped without one.
#[derive(Debug)]
pub enum SearchFailure {
    /// The iterates did not settle within the iteration limit.
    NoConvergence,
    /// The iterates ran off: an entry of the last one is over a thousand times the first guess's
    /// largest entry (or 1). A map whose step barely moves far out (a body far from the centre of a
    /// central field) has a residual that vanishes there without an equilibrium.
    RanOff {
        /// The entry: a shape coordinate, or `p_` and its name for its momentum.
        name: String,
        /// Its value at the last iterate.
        value: f64,
    },
    /// Φ_h − I is singular at an iterate: a multiplier 1.
    Singular,
    /// A step of the method failed at an iterate.
    Step(Box<Error>),
}

impl std::fmt::Display for SearchFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoConvergence => write!(
                f,
                "the iterates did not settle; start nearer to one (the spec's initial shape and shape momenta are the \
                 first guess)"
            ),
            Self::RanOff { name, value } => write!(
                f,
                "the iterates ran off to {name} = {value:.3e}, where the map's residual fades without an \
                 equilibrium; start nearer to one (the spec's initial shape and shape momenta are the first guess)"
            ),
            Self::Singular => write!(
                f,
                "the linearized map has a multiplier 1 there (Φ_h − I is singular): a fold of the family, a \
                 continuum of equilibria, or a symmetry the spec does not declare"
            ),
            Self::Step(error) => write!(f, "a step of the method failed at an iterate: {error}"),
        }
    }
}

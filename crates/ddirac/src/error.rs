//! Errors of the library.

use crate::newton::FailureReason;

/// Everything that can go wrong in setting up or running an integration.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A vector or matrix has the wrong number of entries.
    #[error("{what} has {found} entries, but the system has {expected} coordinates")]
    Size {
        /// What was given.
        what: String,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{what} is not finite ({value})")]
    NonFinite {
        /// Which input.
        what: String,
        /// The offending value.
        value: f64,
    },
    /// An input is out of range or inconsistent.
    #[error("invalid {what}: {why}")]
    Invalid {
        /// Which input.
        what: String,
        /// Why it is rejected.
        why: String,
    },
    /// Newton's method failed on a step.
    #[error(
        "step {step} (t = {}): Newton's method failed after {iterations} iteration(s): {reason} \
         (residual {residual:.3e}); {}", Time(*t), reason.hint()
    )]
    Newton {
        /// Index k of the step q_k → q_{k+1}.
        step: usize,
        /// Time t_k.
        t: f64,
        /// Corrections taken.
        iterations: usize,
        /// Last residual norm.
        residual: f64,
        /// Why it stopped.
        reason: FailureReason,
    },
    /// The state became NaN or infinite.
    #[error("step {step} (t = {}): the {what} became non-finite", Time(*t))]
    Diverged {
        /// Index k of the step.
        step: usize,
        /// Time t_k.
        t: f64,
        /// Which quantity.
        what: &'static str,
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
        "{what} could not be tested: L_d is finite at only {samples} of the {wanted} pairs sought near \
         the initial data"
    )]
    Undecided {
        /// The hypothesis.
        what: String,
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
    #[error("step {step} (t = {}): {message}", Time(*t))]
    EnergyJump {
        /// Index k of the step.
        step: usize,
        /// Time t_k.
        t: f64,
        /// What jumped, by how much.
        message: String,
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
    /// Compiled derivatives were required (`method.derivatives = "compiled"`) but could not be built.
    #[error("compiled derivatives are not available: {0}")]
    NotCompiled(#[source] crate::compiled::CompileError),
    /// The consumer of the output rows failed (e.g. a full disk).
    #[error("writing output failed: {0}")]
    Output(#[source] Box<dyn std::error::Error + Send + Sync>),
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

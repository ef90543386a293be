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
        "step {step} (t = {t}): Newton's method failed after {iterations} iteration(s): {reason} \
         (residual {residual:.3e}); {}", reason.hint()
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
    #[error("step {step} (t = {t}): the {what} became non-finite")]
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

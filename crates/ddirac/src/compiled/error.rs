//! Why derivatives could not be compiled.

#[cfg(feature = "jit")]
use super::JitError;
use super::{MalformedProgram, NotCompiled};

/// Why derivatives could not be compiled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CompileError {
    /// The function could not be traced into a graph.
    #[error(transparent)]
    Trace(#[from] NotCompiled),
    /// The graph could not be turned into native code.
    #[error("native code: {0}")]
    Native(String),
    /// A program reads a register, input or output it does not have.
    #[error(transparent)]
    Malformed(#[from] MalformedProgram),
    /// The compiled derivatives disagree with dual numbers at the first point.
    #[error("compiled derivatives disagree with dual numbers at the first step ({what}: {compiled} vs {dual})")]
    Disagrees {
        /// Which output.
        what: &'static str,
        /// The compiled value.
        compiled: f64,
        /// The dual-number value.
        dual: f64,
    },
}

#[cfg(feature = "jit")]
impl From<JitError> for CompileError {
    fn from(e: JitError) -> Self {
        CompileError::Native(e.to_string())
    }
}

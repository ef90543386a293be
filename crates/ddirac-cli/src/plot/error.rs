//! Errors of the commands that read run directories and write figures and tables.

use std::path::PathBuf;

use miette::Diagnostic;

/// Why `ddirac plot`, `ddirac run --compare` or `ddirac convergence` stopped.
#[derive(Debug, thiserror::Error, Diagnostic)]
pub enum ToolError {
    /// A file of a run directory cannot be read.
    #[error("cannot read `{}`", path.display())]
    #[diagnostic(code(ddirac::read))]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
        /// What to do about it.
        #[help]
        help: Option<String>,
    },
    /// A file of a run directory does not have the content `ddirac run` writes.
    #[error("`{}` is not what `ddirac run` writes: {why}", path.display())]
    #[diagnostic(code(ddirac::malformed))]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// A figure or table cannot be written.
    #[error("cannot write `{}`", path.display())]
    #[diagnostic(code(ddirac::output))]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The command line asks for something that cannot be done.
    #[error("{message}")]
    #[diagnostic(code(ddirac::usage))]
    Usage {
        /// What is wrong.
        message: String,
        /// What to do instead.
        #[help]
        help: Option<String>,
    },
}

impl ToolError {
    /// A [`ToolError::Malformed`] about `path`.
    pub fn malformed(path: impl Into<PathBuf>, why: impl Into<String>) -> Self {
        Self::Malformed { path: path.into(), why: why.into() }
    }

    /// A [`ToolError::Write`] about `path`, from any error.
    pub fn write(path: impl Into<PathBuf>, source: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        Self::Write { path: path.into(), source: std::io::Error::other(source) }
    }
}

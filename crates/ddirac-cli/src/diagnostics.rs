//! Error types of the command line, rendered by miette, and the exit status of each.
//!
//! Everything that concerns a value of the spec is a [`SpecError`]: it carries the spec text (after
//! `--set` overrides) and labelled spans, so the report quotes the offending lines.
//!
//! Each failure has an exit status ([`exit_code`]): the kinds are the constants of [`exit`].

use std::ops::Range;
use std::path::PathBuf;

use miette::{Diagnostic, LabeledSpan, NamedSource};

use crate::signals;

/// The spec text that diagnostics quote, with a display name.
#[derive(Debug, Clone)]
pub struct SpecSource {
    name: String,
    text: String,
}

impl SpecSource {
    /// The text `text` of the spec called `name`.
    pub fn new(name: String, text: String) -> Self {
        Self { name, text }
    }

    /// The spec text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// An error about one span of the spec.
    pub fn error(
        &self,
        span: Option<Range<usize>>,
        message: impl Into<String>,
        label: impl Into<String>,
    ) -> Box<SpecError> {
        let labels = span.map(|s| LabeledSpan::new_with_span(Some(label.into()), s)).into_iter().collect();
        self.error_with(message, labels)
    }

    /// The diagnostic of a refused key: each key it concerns labelled at its span (`span_of`; a key
    /// without a span in this spec goes unlabelled), with the refusal's help.
    pub fn refusal<K: Copy>(
        &self,
        error: crate::keys::KeyError<K>,
        span_of: impl Fn(K) -> Option<Range<usize>>,
    ) -> Box<SpecError> {
        let labels = error
            .labels
            .into_iter()
            .filter_map(|(key, label)| span_of(key).map(|s| LabeledSpan::new_with_span(Some(label), s)))
            .collect();
        let mut diagnostic = self.error_with(error.message, labels);
        diagnostic.help = error.help;
        diagnostic
    }

    /// An error with any number of labelled spans.
    pub fn error_with(&self, message: impl Into<String>, labels: Vec<LabeledSpan>) -> Box<SpecError> {
        Box::new(SpecError {
            message: message.into(),
            src: NamedSource::new(&self.name, self.text.clone()).with_language("TOML"),
            labels,
            help: None,
        })
    }
}

/// A problem with a value of the spec, pointing at where it is written.
#[derive(Debug, thiserror::Error, Diagnostic)]
#[error("{message}")]
#[diagnostic(code(ddirac::spec))]
pub struct SpecError {
    message: String,
    #[source_code]
    src: NamedSource<String>,
    #[label(collection)]
    labels: Vec<LabeledSpan>,
    #[help]
    help: Option<String>,
}

impl SpecError {
    /// Adds a hint on how to fix it.
    pub fn with_help(mut self: Box<Self>, help: impl Into<String>) -> Box<Self> {
        self.help = Some(help.into());
        self
    }
}

/// The exit statuses of `ddirac` besides 0 (success) and 128 + n (stopped by signal n, see
/// [`signals::Signal::exit_code`]); `ddirac --help` and the README list them too.
pub mod exit {
    /// Any failure not classified below.
    pub const OTHER: u8 = 1;
    /// The spec or the command line is wrong (clap's status for usage errors, too).
    pub const SPEC: u8 = 2;
    /// The integration failed.
    pub const NUMERICAL: u8 = 3;
    /// A file cannot be read or written, or the output directory is in use by another run.
    pub const IO: u8 = 4;
}

/// The exit status of a failure: that of the first error of a known kind in its chain.
pub fn exit_code(report: &miette::Report) -> u8 {
    use crate::plot::ToolError;
    for error in report.chain() {
        if let Some(e) = error.downcast_ref::<CliError>() {
            return e.exit_code();
        }
        if error.is::<SpecError>() {
            return exit::SPEC;
        }
        if let Some(e) = error.downcast_ref::<signals::Interrupted>() {
            return e.signal.exit_code();
        }
        if let Some(e) = error.downcast_ref::<ToolError>() {
            return match e {
                ToolError::Usage { .. } => exit::SPEC,
                _ => exit::IO,
            };
        }
    }
    exit::OTHER
}

/// Everything the command line reports as a failure.
#[derive(Debug, thiserror::Error, Diagnostic)]
pub enum CliError {
    /// A file cannot be read.
    #[error("cannot read {what} `{}`", path.display())]
    #[diagnostic(code(ddirac::read))]
    Read {
        /// What the file is: `the spec file`, `the members file`, ….
        what: &'static str,
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A `--set` argument is malformed.
    #[error("malformed `--set {arg}`: {why}")]
    #[diagnostic(
        code(ddirac::set),
        help("write `--set KEY=VALUE` with a dotted key, e.g. `--set method.reduced=false`")
    )]
    Set {
        /// The argument as given.
        arg: String,
        /// What is wrong with it.
        why: String,
    },
    /// The members of an ensemble are malformed.
    #[error("invalid members in {what}: {why}")]
    #[diagnostic(
        code(ddirac::members),
        help(
            "a members file has a header of spec keys (`initial.q.<coordinate>`, `initial.p.<coordinate>`, \
             `initial.v.<coordinate>`, `parameters.<name>`) and one row of numbers per member"
        )
    )]
    Members {
        /// The file, or the spec's `[ensemble]` table.
        what: String,
        /// What is wrong.
        why: String,
    },
    /// Shard directories that do not form one ensemble.
    #[error("cannot merge: {0}")]
    #[diagnostic(code(ddirac::merge))]
    Merge(String),
    /// A value of the spec is wrong.
    #[error(transparent)]
    #[diagnostic(transparent)]
    Spec(#[from] Box<SpecError>),
    /// The integration stopped (Newton failure, divergence, ...).
    #[error("the integration failed")]
    #[diagnostic(code(ddirac::integration))]
    Integration(#[source] ddirac::Error),
    /// The integration stopped, at a place the spec can point to.
    #[error(transparent)]
    #[diagnostic(transparent)]
    IntegrationAt(Box<SpecError>),
    /// Writing an output file failed.
    #[error("cannot write `{}`", path.display())]
    #[diagnostic(code(ddirac::output))]
    Output {
        /// The file or directory the failed operation concerned.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The output directory names a file.
    #[error("the output directory `{}` is not a directory: `{}` is a file", dir.display(), file.display())]
    #[diagnostic(
        code(ddirac::output),
        help("give a directory with `--out DIR` or `output.directory`; it is created if it does not exist")
    )]
    NotADirectory {
        /// The output directory asked for.
        dir: PathBuf,
        /// The file in its place (the directory itself or one above it).
        file: PathBuf,
    },
    /// Another run holds the output directory.
    #[error("the output directory `{}` is in use by another ddirac run ({holder})", dir.display())]
    #[diagnostic(
        code(ddirac::busy),
        help(
            "wait for that run to end, or give this one a directory of its own with `--out DIR`; the lock of a \
             run that no longer exists is taken over without asking"
        )
    )]
    Busy {
        /// The output directory.
        dir: PathBuf,
        /// The other run: process id, command, start.
        holder: String,
    },
    /// A signal stopped the run.
    #[error(transparent)]
    #[diagnostic(code(ddirac::interrupted))]
    Interrupted(#[from] signals::Interrupted),
}

impl CliError {
    /// The exit status of this failure (see [`exit`]).
    /// A figure that cannot be drawn in `dir`, as an output error naming the file.
    pub fn figure(dir: &std::path::Path, error: crate::plot::ToolError) -> Self {
        match error {
            crate::plot::ToolError::Write { path, source } => Self::Output { path, source },
            other => Self::Output { path: dir.to_owned(), source: std::io::Error::other(other) },
        }
    }

    pub fn exit_code(&self) -> u8 {
        match self {
            Self::Set { .. } | Self::Spec(_) | Self::Members { .. } | Self::Merge(_) => exit::SPEC,
            Self::Integration(_) | Self::IntegrationAt(_) => exit::NUMERICAL,
            Self::Read { .. } | Self::Output { .. } | Self::NotADirectory { .. } | Self::Busy { .. } => exit::IO,
            Self::Interrupted(e) => e.signal.exit_code(),
        }
    }
}

//! Error types of the command line, rendered by miette.
//!
//! Everything that concerns a value of the spec is a [`SpecError`]: it carries the spec text (after
//! `--set` overrides) and labelled spans, so the report quotes the offending lines.

use std::ops::Range;
use std::path::PathBuf;

use miette::{Diagnostic, LabeledSpan, NamedSource};

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

/// Everything the command line reports as a failure.
#[derive(Debug, thiserror::Error, Diagnostic)]
pub enum CliError {
    /// The spec file cannot be read.
    #[error("cannot read the spec file `{}`", path.display())]
    #[diagnostic(code(ddirac::read))]
    Read {
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
    /// A value of the spec is wrong.
    #[error(transparent)]
    #[diagnostic(transparent)]
    Spec(#[from] Box<SpecError>),
    /// The integration stopped (Newton failure, divergence, ...).
    #[error("the integration failed")]
    #[diagnostic(code(ddirac::integration))]
    Integration(#[source] ddirac::Error),
    /// Writing the output files failed.
    #[error("cannot write the output in `{}`", dir.display())]
    #[diagnostic(code(ddirac::output))]
    Output {
        /// The output directory.
        dir: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
}

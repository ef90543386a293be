//! Errors of the expression language: syntax errors of one source text ([`SyntaxError`]) and errors of
//! a compilation or a system definition ([`ExpressionError`]), which also say which source text they
//! belong to ([`Origin`]).

use std::fmt;

use super::Span;

/// The source text an error belongs to.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Origin {
    /// A standalone expression ([`Scope::compile_expression`](super::Scope::compile_expression)).
    Expression,
    /// The Lagrangian of an [`ExpressionSystem`](super::ExpressionSystem).
    Lagrangian,
    /// The definition with this name.
    Definition(String),
    /// The exact solution given for the coordinate with this name.
    ExactSolution(String),
    /// The declaration of the coordinate with this name (no source text).
    Coordinate(String),
    /// The declaration of the parameter with this name (no source text).
    Parameter(String),
    /// The main chart's measure, with an atlas ([`ExpressionSpec::quality`](super::ExpressionSpec::quality)).
    Quality,
    /// A part of chart `chart` (numbered from 1) of the atlas.
    Chart {
        /// The chart, numbered from 1 as in [`crate::System::charts`].
        chart: usize,
        /// Which of its expressions or declarations.
        part: super::ChartPart,
    },
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Expression => write!(f, "the expression"),
            Origin::Lagrangian => write!(f, "the Lagrangian"),
            Origin::Definition(name) => write!(f, "definition `{name}`"),
            Origin::ExactSolution(name) => write!(f, "the exact solution for `{name}`"),
            Origin::Coordinate(name) => write!(f, "coordinate `{name}`"),
            Origin::Parameter(name) => write!(f, "parameter `{name}`"),
            Origin::Quality => write!(f, "the main chart's `quality`"),
            Origin::Chart { chart, part } => write!(f, "{part} of chart {chart}"),
        }
    }
}

/// A syntax error in one source text, with the span it concerns and what was expected there.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SyntaxError {
    /// A character that starts no token.
    #[error("unexpected character `{found}`; expected a number, a name, an operator, a parenthesis or a comma")]
    UnexpectedCharacter {
        /// Where.
        span: Span,
        /// The character.
        found: char,
    },
    /// A number that does not parse as a finite f64.
    #[error("malformed number `{text}`: {why}")]
    MalformedNumber {
        /// Where.
        span: Span,
        /// Its text.
        text: String,
        /// What is wrong.
        why: &'static str,
    },
    /// A token where something else was expected.
    #[error("unexpected {found}; expected {expected}")]
    UnexpectedToken {
        /// Where.
        span: Span,
        /// What was found, e.g. "`)`" or "end of expression".
        found: String,
        /// What would have been accepted.
        expected: String,
    },
    /// `**`, which is a power in other languages.
    #[error("unexpected `**`; write `^` for powers (`x^2`), `**` is not an operator")]
    DoubleStar {
        /// The two stars.
        span: Span,
    },
    /// The input ended inside parentheses.
    #[error("missing `)` to close the `(` at {open}; expected `)` before the end of the expression")]
    MissingParen {
        /// The end of the input.
        span: Span,
        /// The unclosed `(`.
        open: Span,
    },
    /// A complete expression followed by more tokens.
    #[error("unexpected {found} after a complete expression; expected an operator or the end of the expression")]
    TrailingInput {
        /// The first extra token.
        span: Span,
        /// What it is.
        found: String,
    },
    /// Nothing but white space.
    #[error("empty expression; expected a number, a name, a function call or `(`")]
    Empty {
        /// The whole (blank) input.
        span: Span,
    },
    /// Nesting deeper than [`MAX_DEPTH`](super::MAX_DEPTH).
    #[error("expression nested too deeply (more than {limit} levels)")]
    TooDeep {
        /// The node that exceeds the limit.
        span: Span,
        /// The limit.
        limit: usize,
    },
}

impl SyntaxError {
    /// The span the error concerns.
    pub fn span(&self) -> Span {
        match self {
            SyntaxError::UnexpectedCharacter { span, .. }
            | SyntaxError::MalformedNumber { span, .. }
            | SyntaxError::UnexpectedToken { span, .. }
            | SyntaxError::DoubleStar { span }
            | SyntaxError::MissingParen { span, .. }
            | SyntaxError::TrailingInput { span, .. }
            | SyntaxError::Empty { span }
            | SyntaxError::TooDeep { span, .. } => *span,
        }
    }
}

/// One reference in a cycle of definitions: the source `origin` refers to `name` at `span`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CycleStep {
    /// The source containing the reference.
    pub origin: Origin,
    /// The definition referred to.
    pub name: String,
    /// The reference in that source.
    pub span: Span,
}

/// Why a set of expressions cannot be compiled, or a system cannot be built from them.
///
/// Errors in source text carry the [`Origin`] and the byte [`Span`] in that source
/// ([`ExpressionError::span`]); errors in declarations (names, values, sizes) carry no span.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExpressionError {
    /// The source does not parse.
    #[error("in {origin} at {}: {error}", error.span())]
    Syntax {
        /// Which source.
        origin: Origin,
        /// The syntax error, with its span.
        error: SyntaxError,
    },
    /// A name that is neither a variable, a constant nor a definition.
    #[error("in {origin} at {span}: unknown name `{name}`{}", did_you_mean(suggestion))]
    UnknownName {
        /// Which source.
        origin: Origin,
        /// The name.
        span: Span,
        /// The unknown name.
        name: String,
        /// The closest known name, if one is close.
        suggestion: Option<String>,
    },
    /// A known name that this source may not use (e.g. `t` in a Lagrangian).
    #[error("in {origin} at {span}: `{name}` is not available here: {reason}")]
    Unavailable {
        /// Which source.
        origin: Origin,
        /// The name.
        span: Span,
        /// The name.
        name: String,
        /// Why.
        reason: String,
    },
    /// A call of a name that is not a function.
    #[error("in {origin} at {span}: unknown function `{name}`{}", did_you_mean(suggestion))]
    UnknownFunction {
        /// Which source.
        origin: Origin,
        /// The function name.
        span: Span,
        /// The name.
        name: String,
        /// The closest function name, if one is close.
        suggestion: Option<String>,
    },
    /// A call of a variable, constant or definition.
    #[error("in {origin} at {span}: `{name}` is not a function and cannot be called")]
    NotAFunction {
        /// Which source.
        origin: Origin,
        /// The name.
        span: Span,
        /// The name.
        name: String,
    },
    /// A function name used without a call.
    #[error("in {origin} at {span}: `{name}` is a function; call it as `{name}(...)`")]
    FunctionWithoutCall {
        /// Which source.
        origin: Origin,
        /// The name.
        span: Span,
        /// The function name.
        name: String,
    },
    /// A function called with the wrong number of arguments.
    #[error(
        "in {origin} at {span}: `{function}` takes {expected} argument{}, but {found} {} given",
        if *expected == 1 { "" } else { "s" },
        if *found == 1 { "was" } else { "were" }
    )]
    Arity {
        /// Which source.
        origin: Origin,
        /// The whole call.
        span: Span,
        /// The function.
        function: String,
        /// Arguments it takes.
        expected: usize,
        /// Arguments given.
        found: usize,
    },
    /// Definitions that refer to one another in a cycle.
    #[error("in {origin} at {span}: definitions refer to each other in a cycle: {}", cycle_text(cycle))]
    Cycle {
        /// The source of the reference that closes the cycle.
        origin: Origin,
        /// That reference.
        span: Span,
        /// Every reference of the cycle, in order; the last is the one at `origin`/`span`.
        cycle: Vec<CycleStep>,
    },
    /// A declared name that cannot be used.
    #[error("{origin}: invalid name `{name}`: {reason}")]
    InvalidName {
        /// The declaration.
        origin: Origin,
        /// The name.
        name: String,
        /// Why.
        reason: String,
    },
    /// Two declarations of one name.
    #[error("the name `{name}` is declared twice: as {first} and as {second}")]
    DuplicateName {
        /// The second declaration.
        origin: Origin,
        /// The name.
        name: String,
        /// What the first declaration is.
        first: String,
        /// What the second declaration is.
        second: String,
    },
    /// A parameter that is NaN or infinite.
    #[error("{origin} is not finite ({value})")]
    NonFinite {
        /// The parameter.
        origin: Origin,
        /// Its value.
        value: f64,
    },
    /// An exact solution for a name that is not a coordinate.
    #[error("{origin}: `{name}` is not a coordinate{}", did_you_mean(suggestion))]
    UnknownCoordinate {
        /// The exact solution.
        origin: Origin,
        /// The name given.
        name: String,
        /// The closest coordinate name, if one is close.
        suggestion: Option<String>,
    },
    /// A system without coordinates.
    #[error("the system has no coordinates")]
    NoCoordinates,
    /// A part of a spec that this kind of system does not take.
    #[error("{what} are not taken")]
    Unsupported {
        /// What is not taken.
        what: String,
    },
    /// An atlas without the main chart's measure.
    #[error(
        "a system with charts says where its main chart is good: give `quality`, an expression in its coordinates"
    )]
    MissingQuality,
    /// A chart map without the expression of one coordinate.
    #[error("{origin} is missing: `to_main` gives each coordinate of the main chart, `from_main` each of the chart's")]
    MissingMap {
        /// The missing entry.
        origin: Origin,
        /// The coordinate without an expression.
        name: String,
    },
    /// A chart with another number of coordinates than the main chart.
    #[error("chart {chart} has {found} coordinates, the main chart {expected}")]
    ChartDimension {
        /// The chart, numbered from 1.
        chart: usize,
        /// The main chart's number of coordinates.
        expected: usize,
        /// The chart's.
        found: usize,
    },
    /// A system built for a number of coordinates it does not have.
    #[error("the system has {found} coordinates, but {expected} were expected")]
    Dimension {
        /// Coordinates expected (the `N` of `System<N>`).
        expected: usize,
        /// Coordinates declared.
        found: usize,
    },
    /// An engine size that is not one of [`crate::SIZES`], or smaller than the system
    /// ([`super::ExpressionSpec::into_dyn_in`]).
    #[error(
        "no engine of {size} coordinates for a system of {found}: the engine is built for {} coordinates",
        crate::sizes_text()
    )]
    EngineSize {
        /// The size asked for.
        size: usize,
        /// Coordinates declared.
        found: usize,
    },
}

impl ExpressionError {
    /// The source text the error belongs to.
    pub fn origin(&self) -> Option<&Origin> {
        match self {
            ExpressionError::Syntax { origin, .. }
            | ExpressionError::UnknownName { origin, .. }
            | ExpressionError::Unavailable { origin, .. }
            | ExpressionError::UnknownFunction { origin, .. }
            | ExpressionError::NotAFunction { origin, .. }
            | ExpressionError::FunctionWithoutCall { origin, .. }
            | ExpressionError::Arity { origin, .. }
            | ExpressionError::Cycle { origin, .. }
            | ExpressionError::InvalidName { origin, .. }
            | ExpressionError::DuplicateName { origin, .. }
            | ExpressionError::NonFinite { origin, .. }
            | ExpressionError::UnknownCoordinate { origin, .. }
            | ExpressionError::MissingMap { origin, .. } => Some(origin),
            ExpressionError::NoCoordinates
            | ExpressionError::Unsupported { .. }
            | ExpressionError::MissingQuality
            | ExpressionError::ChartDimension { .. }
            | ExpressionError::Dimension { .. }
            | ExpressionError::EngineSize { .. } => None,
        }
    }

    /// The byte span in the source named by [`ExpressionError::origin`], for errors in source text.
    pub fn span(&self) -> Option<Span> {
        match self {
            ExpressionError::Syntax { error, .. } => Some(error.span()),
            ExpressionError::UnknownName { span, .. }
            | ExpressionError::Unavailable { span, .. }
            | ExpressionError::UnknownFunction { span, .. }
            | ExpressionError::NotAFunction { span, .. }
            | ExpressionError::FunctionWithoutCall { span, .. }
            | ExpressionError::Arity { span, .. }
            | ExpressionError::Cycle { span, .. } => Some(*span),
            _ => None,
        }
    }
}

fn did_you_mean(suggestion: &Option<String>) -> String {
    suggestion.as_ref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default()
}

/// The names of a cycle, `a → b → a`; of a long cycle, the first and last eight.
fn cycle_text(cycle: &[CycleStep]) -> String {
    let mut names: Vec<&str> = Vec::with_capacity(cycle.len() + 1);
    if let Some(Origin::Definition(first)) = cycle.first().map(|s| &s.origin) {
        names.push(first);
    }
    names.extend(cycle.iter().map(|s| s.name.as_str()));
    const SHOWN: usize = 8;
    if names.len() > 2 * SHOWN + 1 {
        let hidden = format!("… ({} more)", names.len() - 2 * SHOWN);
        let (head, tail) = (names[..SHOWN].join(" → "), names[names.len() - SHOWN..].join(" → "));
        return format!("{head} → {hidden} → {tail}");
    }
    names.join(" → ")
}

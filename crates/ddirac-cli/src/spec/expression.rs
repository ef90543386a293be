//! A `[system]` table turned into a system: coordinates from the lists, the Lagrangian, definitions
//! and exact solution compiled by `ddirac::expression`, parameters from `[parameters]`.
//!
//! An [`ExpressionError`] names the source it belongs to (the Lagrangian, a definition, an exact
//! solution, a declaration) and a byte range in that source; it is reported at the corresponding
//! characters of the spec file (see [`super::strings`]).

use std::ops::Range;

use ddirac::expression::{ChartPart, ChartSpec, ExpressionError, ExpressionSpec, Origin};
use ddirac::DynSystem;
use miette::LabeledSpan;
use toml::Spanned;

use super::lists::{self, Declared, Lists};
use super::{strings, ChartTable, Number, Sources, Spec, SystemTable};
use crate::diagnostics::{SpecError, SpecSource};

/// The system a `[system]` table defines.
pub struct Built {
    /// The system.
    pub system: Box<dyn DynSystem>,
    /// `system.name`, or `custom`.
    pub name: String,
    /// The parameters, in the order written.
    pub parameters: Vec<(String, f64)>,
    /// The span of each coordinate's declaration, by name.
    pub coordinates: Vec<(String, Range<usize>)>,
}

/// The entries of a table of sources, in the order written.
fn sources(table: &Option<Sources>) -> Vec<(&Spanned<String>, &Spanned<String>)> {
    table.as_ref().map(entries).unwrap_or_default()
}

/// The entries of a table of sources that is given, in the order written.
fn entries(table: &Sources) -> Vec<(&Spanned<String>, &Spanned<String>)> {
    let mut entries: Vec<_> = table.get_ref().iter().collect();
    entries.sort_by_key(|(key, _)| key.span().start);
    entries
}

/// The charts of the atlas, each with its coordinates (`[[system.charts]]`).
fn charts<'t>(source: &SpecSource, table: &'t SystemTable) -> Result<Vec<(&'t ChartTable, Declared)>, Box<SpecError>> {
    let charts = table.charts.iter().flatten().enumerate();
    charts
        .map(|(i, chart)| {
            Ok((chart.get_ref(), lists::declare(source, &Lists::of_chart(chart.get_ref(), i + 1), chart.span())?))
        })
        .collect()
}

/// Builds the system of `table`, written at `span`, with the constants of `[parameters]`.
pub fn build(
    source: &SpecSource,
    spec: &Spec,
    table: &SystemTable,
    span: Range<usize>,
) -> Result<Built, Box<SpecError>> {
    let declared = lists::coordinates(source, table, span.clone())?;
    let mut parameters: Vec<(&Spanned<String>, &Number)> = spec.parameters.iter().collect();
    parameters.sort_by_key(|(key, _)| key.span().start);
    let values = parameters
        .iter()
        .map(|(name, value)| {
            let v = super::finite(source, value, &format!("parameter `{}`", name.get_ref()))?;
            Ok((name.get_ref().clone(), v))
        })
        .collect::<Result<Vec<_>, Box<SpecError>>>()?;
    let owned = |entries: Vec<(&Spanned<String>, &Spanned<String>)>| {
        entries.into_iter().map(|(k, v)| (k.get_ref().clone(), v.get_ref().clone())).collect::<Vec<_>>()
    };
    let charts = charts(source, table)?;
    let chart_specs = charts
        .iter()
        .enumerate()
        .map(|(i, (chart, declared))| ChartSpec {
            name: chart.name.as_ref().map_or_else(|| format!("chart {}", i + 1), |n| n.get_ref().clone()),
            coordinates: declared.coordinates.clone(),
            to_main: owned(entries(&chart.to_main)),
            from_main: owned(entries(&chart.from_main)),
            quality: chart.quality.get_ref().clone(),
        })
        .collect();
    let expression = ExpressionSpec {
        coordinates: declared.coordinates.clone(),
        lagrangian: table.lagrangian.get_ref().clone(),
        definitions: owned(sources(&table.definitions)),
        parameters: values.clone(),
        exact_solution: owned(sources(&table.exact)),
        quality: table.quality.as_ref().map(|q| q.get_ref().clone()),
        charts: chart_specs,
    };
    let context = Context { source, table, declared: &declared, charts: &charts, parameters: &parameters, span };
    let system = expression.into_dyn().map_err(|e| context.error(e))?;
    let name = table.name.as_ref().map_or_else(|| "custom".to_owned(), |n| n.get_ref().clone());
    let coordinates =
        declared.coordinates.iter().zip(&declared.spans).map(|(c, s)| (c.name.clone(), s.clone())).collect();
    Ok(Built { system, name, parameters: values, coordinates })
}

/// A rigid system of text with its parameters and their values, in the order written.
pub type BuiltRigid = (ddirac::rigid::RigidExpressionSystem, Vec<(String, f64)>);

/// The rigid system a `[system]` table with `attitude = "SO(3)"` defines (written at `span`), with the
/// constants of `[parameters]`: its shape coordinates (none when `shape` is not given), its
/// Lagrangian in `R11` … `R33`, `Omega1` … `Omega3`, the shape and its velocities, and `symmetry`.
pub fn build_rigid(
    source: &SpecSource,
    spec: &Spec,
    table: &SystemTable,
    span: Range<usize>,
    symmetry: ddirac::rigid::Symmetry,
) -> Result<BuiltRigid, Box<SpecError>> {
    let declared = match (&table.shape, &table.angles, &table.order) {
        (None, None, None) => Declared { coordinates: vec![], spans: vec![] },
        _ => lists::coordinates(source, table, span.clone())?,
    };
    let mut parameters: Vec<(&Spanned<String>, &Number)> = spec.parameters.iter().collect();
    parameters.sort_by_key(|(key, _)| key.span().start);
    let values = parameters
        .iter()
        .map(|(name, value)| {
            let v = super::finite(source, value, &format!("parameter `{}`", name.get_ref()))?;
            Ok((name.get_ref().clone(), v))
        })
        .collect::<Result<Vec<_>, Box<SpecError>>>()?;
    let definitions = sources(&table.definitions);
    let expression = ExpressionSpec {
        coordinates: declared.coordinates.clone(),
        lagrangian: table.lagrangian.get_ref().clone(),
        definitions: definitions.into_iter().map(|(k, v)| (k.get_ref().clone(), v.get_ref().clone())).collect(),
        parameters: values.clone(),
        ..ExpressionSpec::default()
    };
    let context = Context { source, table, declared: &declared, charts: &[], parameters: &parameters, span };
    let system = ddirac::rigid::RigidExpressionSystem::new(&expression, symmetry).map_err(|e| context.error(e))?;
    Ok((system, values))
}

/// Where the sources and declarations of a `[system]` table are written.
struct Context<'a> {
    source: &'a SpecSource,
    table: &'a SystemTable,
    declared: &'a Declared,
    charts: &'a [(&'a ChartTable, Declared)],
    parameters: &'a [(&'a Spanned<String>, &'a Number)],
    span: Range<usize>,
}

impl Context<'_> {
    /// The source text `origin` refers to (its value as written), and the span of its name.
    fn locate(&self, origin: &Origin) -> (Option<&Spanned<String>>, Option<Range<usize>>) {
        fn entry<'t>(table: &'t Option<Sources>, name: &str) -> (Option<&'t Spanned<String>>, Option<Range<usize>>) {
            match sources(table).into_iter().find(|(k, _)| k.get_ref() == name) {
                Some((key, value)) => (Some(value), Some(key.span())),
                None => (None, None),
            }
        }
        match origin {
            Origin::Lagrangian => (Some(&self.table.lagrangian), None),
            Origin::Definition(name) => entry(&self.table.definitions, name),
            Origin::ExactSolution(name) => entry(&self.table.exact, name),
            Origin::Coordinate(name) => (None, self.declared.span_of(name)),
            Origin::Parameter(name) => {
                (None, self.parameters.iter().find(|(k, _)| k.get_ref() == name).map(|(k, _)| k.span()))
            }
            Origin::Quality => (self.table.quality.as_ref(), None),
            Origin::Chart { chart, part } => {
                let Some((table, declared)) = chart.checked_sub(1).and_then(|i| self.charts.get(i)) else {
                    return (None, None);
                };
                // An entry of `to_main` or `from_main`, or the table itself where the entry is missing.
                fn map<'t>(sources: &'t Sources, name: &str) -> (Option<&'t Spanned<String>>, Option<Range<usize>>) {
                    match entries(sources).into_iter().find(|(k, _)| k.get_ref() == name) {
                        Some((key, value)) => (Some(value), Some(key.span())),
                        None => (None, Some(sources.span())),
                    }
                }
                match part {
                    ChartPart::Coordinate(name) => (None, declared.span_of(name)),
                    ChartPart::ToMain(name) => map(&table.to_main, name),
                    ChartPart::FromMain(name) => map(&table.from_main, name),
                    ChartPart::Quality => (Some(&table.quality), None),
                }
            }
            _ => (None, None),
        }
    }

    /// The label for the characters `inner` of the source `value`: exactly there when the string is
    /// written verbatim, else on the whole value.
    fn at(&self, value: &Spanned<String>, inner: Range<usize>, label: String) -> LabeledSpan {
        let text = self.source.text();
        match strings::inner_range(text, &value.span(), value.get_ref(), inner.clone()) {
            Some(range) => LabeledSpan::new_with_span(Some(label), range),
            None => LabeledSpan::new_with_span(
                Some(format!("{label} (bytes {}..{} of this string)", inner.start, inner.end)),
                value.span(),
            ),
        }
    }

    fn error(&self, error: ExpressionError) -> Box<SpecError> {
        let mut message = error.to_string();
        if let Some(span) = error.span() {
            message = message.replacen(&format!(" at {span}:"), ":", 1);
        }
        let mut labels = vec![];
        if let ExpressionError::Cycle { cycle, .. } = &error {
            for step in cycle.iter().take(LONG_LIST) {
                if let (Some(value), _) = self.locate(&step.origin) {
                    labels.push(self.at(value, step.span.into(), format!("uses `{}`", step.name)));
                }
            }
        } else if let Some(origin) = error.origin() {
            let (value, key) = self.locate(origin);
            match (error.span(), value, key) {
                (Some(inner), Some(value), _) => labels.push(self.at(value, inner.into(), label(&error))),
                (_, _, Some(key)) => labels.push(LabeledSpan::new_with_span(Some(label(&error)), key)),
                _ => {}
            }
        }
        if labels.is_empty() {
            labels.push(LabeledSpan::new_with_span(Some("in this system".into()), self.span.clone()));
        }
        // A label on a long line (a generated Lagrangian) would quote the whole line: it becomes an
        // excerpt of the line in the message instead.
        let text = self.source.text();
        labels.retain(|l| match excerpt(text, l.offset()..l.offset() + l.len(), l.label().unwrap_or("here")) {
            Some(excerpt) => {
                message.push_str(&excerpt);
                false
            }
            None => true,
        });
        let error_help = help(&error, self);
        let report = self.source.error_with(format!("invalid `[system]`: {message}"), labels);
        match error_help {
            Some(text) => report.with_help(text),
            None => report,
        }
    }
}

/// Names listed in a hint, at most (a generated system may have thousands of definitions).
const LONG_LIST: usize = 12;

/// Lines of the spec longer than this many characters are not quoted whole in a report.
const LONG_LINE: usize = 200;

/// Characters of a long line shown on each side of the start of what a report points at.
const EXCERPT_SIDE: usize = 40;

/// For `span` on a line of `text` longer than [`LONG_LINE`] characters: the place (line and column, in
/// characters from 1), `label`, and about 80 characters of the line around the start of `span` with
/// `^` under the span. `None` for a span on a shorter line.
///
/// ```text
///
///   at line 3, column 4522 of 92061 characters: here
///     … + x + x + x + x + x**2 + x + x + x + x + x + …
///                            ^^
/// ```
fn excerpt(text: &str, span: Range<usize>, label: &str) -> Option<String> {
    let start = span.start.min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = text[line_start..line_end].trim_end_matches('\r');
    let length = line.chars().count();
    if length <= LONG_LINE {
        return None;
    }
    let chars: Vec<char> = line.chars().collect();
    let column = text[line_start..start].chars().count();
    let width = text[start..span.end.clamp(start, line_start + line.len())].chars().count().max(1);
    let from = column.saturating_sub(EXCERPT_SIDE);
    let to = (column + width.max(EXCERPT_SIDE)).min(length);
    let before = if from > 0 { "…" } else { "" };
    let after = if to < length { "…" } else { "" };
    let shown: String = chars[from..to].iter().collect();
    let marks = "^".repeat(width.min(to - column).max(1));
    let number = text[..line_start].matches('\n').count() + 1;
    Some(format!(
        "\n\n  at line {number}, column {} of {length} characters: {label}\n    {before}{shown}{after}\n    {}{marks}",
        column + 1,
        " ".repeat(before.chars().count() + column - from),
    ))
}

fn label(error: &ExpressionError) -> String {
    match error {
        ExpressionError::Syntax { .. } => "here".into(),
        ExpressionError::UnknownName { .. } => "unknown name".into(),
        ExpressionError::Unavailable { .. } => "not available here".into(),
        ExpressionError::UnknownFunction { .. } => "unknown function".into(),
        ExpressionError::NotAFunction { .. } => "not a function".into(),
        ExpressionError::Arity { .. } => "this call".into(),
        ExpressionError::NonFinite { .. } => "not finite".into(),
        ExpressionError::UnknownCoordinate { .. } => "not a coordinate".into(),
        ExpressionError::MissingMap { name, .. } => format!("no expression for `{name}` here"),
        _ => "declared here".into(),
    }
}

fn help(error: &ExpressionError, context: &Context<'_>) -> Option<String> {
    let list = |names: Vec<String>| match names.len() {
        0 => "none".to_owned(),
        n if n > LONG_LIST => format!("{}, … and {} more", names[..LONG_LIST].join(", "), n - LONG_LIST),
        _ => names.join(", "),
    };
    let coordinates: Vec<String> = context.declared.coordinates.iter().map(|c| c.name.clone()).collect();
    let names_of = |declared: &Declared| list(declared.coordinates.iter().map(|c| c.name.clone()).collect());
    match error {
        ExpressionError::UnknownName { origin: Origin::Chart { chart, part }, .. }
        | ExpressionError::UnknownCoordinate { origin: Origin::Chart { chart, part }, .. } => {
            let (_, declared) = context.charts.get(chart.checked_sub(1)?)?;
            let parameters = list(parameter_names(context));
            Some(match part {
                ChartPart::FromMain(_) => format!(
                    "`from_main` gives each of the chart's coordinates ({}) in those of the main chart ({}) and the \
                     parameters ({parameters})",
                    names_of(declared),
                    list(coordinates)
                ),
                _ => format!(
                    "`to_main` gives each coordinate of the main chart ({}), and `quality` the chart's measure, in \
                     the chart's coordinates ({}) and the parameters ({parameters})",
                    list(coordinates),
                    names_of(declared)
                ),
            })
        }
        ExpressionError::UnknownName { origin: Origin::Quality, .. } => Some(format!(
            "the main chart's `quality` may use its coordinates ({}) and the parameters ({})",
            list(coordinates),
            list(parameter_names(context))
        )),
        ExpressionError::UnknownName { origin: Origin::ExactSolution(_), .. } => {
            Some(format!("an exact solution may use `t` and the parameters ({})", list(parameter_names(context))))
        }
        ExpressionError::UnknownName { .. } if context.table.attitude.is_some() => Some(format!(
            "the Lagrangian and the definitions of a rigid system may use the body angular velocity (Omega1, \
             Omega2, Omega3), the attitude's entries (R11, R12, …, R33), the shape coordinates ({}), their \
             velocities ({}), the parameters ({}) and the definitions ({}); give constants in `[parameters]`",
            list(coordinates.clone()),
            list(coordinates.iter().map(|c| format!("{c}_dot")).collect()),
            list(parameter_names(context)),
            list(sources(&context.table.definitions).iter().map(|(k, _)| k.get_ref().clone()).collect()),
        )),
        ExpressionError::UnknownName { .. } => Some(format!(
            "the Lagrangian and the definitions may use the coordinates ({}), their velocities ({}), the \
             parameters ({}) and the definitions ({}); give constants in `[parameters]`",
            list(coordinates.clone()),
            list(coordinates.iter().map(|c| format!("{c}_dot")).collect()),
            list(parameter_names(context)),
            list(sources(&context.table.definitions).iter().map(|(k, _)| k.get_ref().clone()).collect()),
        )),
        ExpressionError::UnknownCoordinate { .. } => {
            Some(format!("`[system.exact]` gives expressions for coordinates: {}", list(coordinates)))
        }
        ExpressionError::Cycle { .. } => Some("a definition may not depend on itself, directly or not".into()),
        _ => None,
    }
}

fn parameter_names(context: &Context<'_>) -> Vec<String> {
    context.parameters.iter().map(|(k, _)| k.get_ref().clone()).collect()
}

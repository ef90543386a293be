//! The atlas of a text system (paper §6; [`crate::atlas`]): its other charts, each with its
//! coordinates, the maps to and from the main chart and where it is good, as expressions in the
//! coordinates and the parameters (`[[system.charts]]` of a spec).
//!
//! The maps are expressions like the Lagrangian, evaluated by the same interpreter over any scalar,
//! so that the Lagrangian of a chart, L ∘ Tφ, is differentiated (and traced) as the Lagrangian is.

use super::compile::closest;
use super::spec::{ChartPart, ChartSpec};
use super::{CompiledExpression, ExpressionError, ExpressionSpec, Origin, Scope, CONSTANTS, FUNCTIONS};
use crate::Coordinate;

/// A compiled atlas: the main chart's measure and the other charts.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct TextAtlas {
    pub(super) quality: CompiledExpression,
    pub(super) charts: Vec<TextChart>,
}

/// A compiled chart: its maps in the order of the coordinates they give.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct TextChart {
    pub(super) name: String,
    pub(super) coordinates: Vec<Coordinate>,
    pub(super) to_main: Vec<CompiledExpression>,
    pub(super) from_main: Vec<CompiledExpression>,
    pub(super) quality: CompiledExpression,
}

impl TextAtlas {
    /// Entry `i` of a point `q` of chart `chart` in the main chart (`to_main`), or of a main-chart
    /// point in chart `chart`; entries beyond the spec's coordinates (padding) are kept.
    pub(super) fn map<D: crate::Scalar>(&self, chart: usize, to_main: bool, q: &[D], i: usize) -> D {
        let chart = &self.charts[chart - 1];
        let maps = if to_main { &chart.to_main } else { &chart.from_main };
        match maps.get(i) {
            Some(map) => map.eval_with(|j| q[j]),
            None => q[i],
        }
    }

    /// The measure of chart `chart` (0: the main chart) at its point `q` (the spec's coordinates).
    pub(super) fn quality<D: crate::Scalar>(&self, chart: usize, q: &[D]) -> D {
        match chart {
            0 => self.quality.eval(q),
            _ => self.charts[chart - 1].quality.eval(q),
        }
    }
}

/// The scope of expressions in `coordinates`: those as variables, the parameters as constants.
fn scope(coordinates: &[Coordinate], spec: &ExpressionSpec) -> Scope {
    let mut scope = Scope::new();
    for c in coordinates {
        scope = scope.variable(&c.name);
    }
    for &(name, value) in CONSTANTS {
        scope = scope.constant(name, value);
    }
    for (name, value) in &spec.parameters {
        scope = scope.constant(name, *value);
    }
    for (name, _) in &spec.definitions {
        scope = scope
            .unavailable(name, "definitions belong to the Lagrangian; a chart's maps use coordinates and parameters");
    }
    scope
}

/// Checks and compiles the atlas of `spec`, if it declares charts.
pub(super) fn compile(spec: &ExpressionSpec) -> Result<Option<TextAtlas>, ExpressionError> {
    if spec.charts.is_empty() {
        return Ok(None);
    }
    let Some(quality) = &spec.quality else {
        return Err(ExpressionError::MissingQuality);
    };
    let in_main = scope(&spec.coordinates, spec);
    let quality = in_main.compile(Origin::Quality, quality)?;
    let charts = spec
        .charts
        .iter()
        .enumerate()
        .map(|(i, chart)| {
            let index = i + 1;
            let origin = |part| Origin::Chart { chart: index, part };
            let (expected, found) = (spec.coordinates.len(), chart.coordinates.len());
            if found != expected {
                return Err(ExpressionError::ChartDimension { chart: index, expected, found });
            }
            check_names(chart, spec, &origin)?;
            let in_chart = scope(&chart.coordinates, spec);
            let to_main = ordered(&spec.coordinates, &chart.to_main, &|n| origin(ChartPart::ToMain(n)), &in_chart)?;
            let from_main =
                ordered(&chart.coordinates, &chart.from_main, &|n| origin(ChartPart::FromMain(n)), &in_main)?;
            let quality = in_chart.compile(origin(ChartPart::Quality), &chart.quality)?;
            let (name, coordinates) = (chart.name.clone(), chart.coordinates.clone());
            Ok(TextChart { name, coordinates, to_main, from_main, quality })
        })
        .collect::<Result<_, ExpressionError>>()?;
    Ok(Some(TextAtlas { quality, charts }))
}

/// The chart's coordinate names: identifiers, not functions or parameters, each once.
fn check_names(
    chart: &ChartSpec,
    spec: &ExpressionSpec,
    origin: &dyn Fn(ChartPart) -> Origin,
) -> Result<(), ExpressionError> {
    for (i, c) in chart.coordinates.iter().enumerate() {
        let origin = origin(ChartPart::Coordinate(c.name.clone()));
        let invalid = |reason: &str| ExpressionError::InvalidName {
            origin: origin.clone(),
            name: c.name.clone(),
            reason: reason.into(),
        };
        let mut chars = c.name.chars();
        let identifier = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !identifier {
            return Err(invalid("a name is a letter or `_` followed by letters, digits and `_`"));
        }
        if FUNCTIONS.contains(&c.name.as_str()) {
            return Err(invalid("it is the name of a function"));
        }
        if let Some(reason) = super::functions::constant(&c.name) {
            return Err(invalid(&reason));
        }
        let first = if spec.parameters.iter().any(|(p, _)| p == &c.name) {
            Some(format!("parameter `{}`", c.name))
        } else {
            chart.coordinates[..i]
                .iter()
                .any(|d| d.name == c.name)
                .then(|| format!("coordinate `{}` of this chart", c.name))
        };
        if let Some(first) = first {
            let second = format!("coordinate `{}` of this chart", c.name);
            return Err(ExpressionError::DuplicateName { origin, name: c.name.clone(), first, second });
        }
    }
    Ok(())
}

/// One expression per coordinate of `targets`, in their order, from `entries` (name → source).
fn ordered(
    targets: &[Coordinate],
    entries: &[(String, String)],
    origin: &dyn Fn(String) -> Origin,
    scope: &Scope,
) -> Result<Vec<CompiledExpression>, ExpressionError> {
    if let Some((name, _)) = entries.iter().find(|(name, _)| !targets.iter().any(|c| &c.name == name)) {
        let suggestion = closest(name, targets.iter().map(|c| c.name.as_str()));
        return Err(ExpressionError::UnknownCoordinate {
            origin: origin(name.clone()),
            name: name.clone(),
            suggestion,
        });
    }
    targets
        .iter()
        .map(|c| match entries.iter().find(|(name, _)| name == &c.name) {
            Some((_, source)) => scope.compile(origin(c.name.clone()), source),
            None => Err(ExpressionError::MissingMap { origin: origin(c.name.clone()), name: c.name.clone() }),
        })
        .collect()
}

//! The coordinates of a `[system]` table: `shape` (Σ), `group` (G), `angles` (S¹) and `order`,
//! checked against each other. The result lists the coordinates in order, each with the span of its
//! declaration, so that later errors about a coordinate can point at its name.

use std::ops::Range;

use ddirac::{Coordinate, Role};
use miette::LabeledSpan;
use toml::Spanned;

use super::{ChartTable, Names, SystemTable};
use crate::diagnostics::{SpecError, SpecSource};

/// The coordinates in order, with the span of each name in `shape` or `group`.
pub struct Declared {
    /// The coordinates.
    pub coordinates: Vec<Coordinate>,
    /// The span of each coordinate's name in the `shape` or `group` list.
    pub spans: Vec<Range<usize>>,
}

impl Declared {
    /// The span of the declaration of the coordinate `name`.
    pub fn span_of(&self, name: &str) -> Option<Range<usize>> {
        self.coordinates.iter().position(|c| c.name == name).map(|i| self.spans[i].clone())
    }
}

fn entries(list: &Option<Names>) -> &[Spanned<String>] {
    list.as_ref().map_or(&[], |l| l.get_ref().as_slice())
}

/// Two entries of `list` with the same name, if any.
fn duplicate(list: &[Spanned<String>]) -> Option<(&Spanned<String>, &Spanned<String>)> {
    list.iter().enumerate().find_map(|(i, a)| list[i + 1..].iter().find(|b| b.get_ref() == a.get_ref()).map(|b| (a, b)))
}

fn twice(source: &SpecSource, key: &str, (first, second): (&Spanned<String>, &Spanned<String>)) -> Box<SpecError> {
    let labels = vec![
        LabeledSpan::new_with_span(Some("first here".into()), first.span()),
        LabeledSpan::new_with_span(Some("and again here".into()), second.span()),
    ];
    source.error_with(format!("`{}` appears twice in `{key}`", first.get_ref()), labels)
}

/// The coordinate lists of the `[system]` table or of one of its charts, and where they are.
pub struct Lists<'a> {
    /// `system`, or `system.charts` with the chart's number.
    pub table: String,
    /// `shape`.
    pub shape: &'a Option<Names>,
    /// `group`.
    pub group: &'a Option<Names>,
    /// `angles`.
    pub angles: &'a Option<Names>,
    /// `order`.
    pub order: &'a Option<Names>,
}

impl<'a> Lists<'a> {
    /// The lists of the `[system]` table.
    pub fn of_system(table: &'a SystemTable) -> Self {
        let SystemTable { shape, group, angles, order, .. } = table;
        Self { table: "system".into(), shape, group, angles, order }
    }

    /// The lists of chart `index` (from 1).
    pub fn of_chart(chart: &'a ChartTable, index: usize) -> Self {
        let ChartTable { shape, group, angles, order, .. } = chart;
        Self { table: format!("system.charts (chart {index})"), shape, group, angles, order }
    }
}

/// Checks the coordinate lists of `table` (written at `span`) and puts the coordinates in order.
pub fn coordinates(source: &SpecSource, table: &SystemTable, span: Range<usize>) -> Result<Declared, Box<SpecError>> {
    declare(source, &Lists::of_system(table), span)
}

/// Checks coordinate lists (of a table written at `span`) and puts the coordinates in order.
pub fn declare(source: &SpecSource, table: &Lists<'_>, span: Range<usize>) -> Result<Declared, Box<SpecError>> {
    let (shape, group) = (entries(table.shape), entries(table.group));
    let key = |name: &str| format!("{}.{name}", table.table);
    for (name, list) in [("shape", shape), ("group", group), ("angles", entries(table.angles))] {
        if let Some(pair) = duplicate(list) {
            return Err(twice(source, &key(name), pair));
        }
    }
    if let Some((x, g)) = shape.iter().find_map(|x| group.iter().find(|g| g.get_ref() == x.get_ref()).map(|g| (x, g))) {
        let labels = vec![
            LabeledSpan::new_with_span(Some("a shape coordinate here".into()), x.span()),
            LabeledSpan::new_with_span(Some("and a group coordinate here".into()), g.span()),
        ];
        return Err(source
            .error_with(format!("coordinate `{}` is listed in both `shape` and `group`", x.get_ref()), labels)
            .with_help(
                "a coordinate belongs to the shape space Σ (`shape`) or is translated by the symmetry (`group`), \
                 not both",
            ));
    }
    let mut declared: Vec<(&Spanned<String>, Role)> =
        shape.iter().map(|x| (x, Role::Shape)).chain(group.iter().map(|g| (g, Role::Group))).collect();
    if declared.is_empty() {
        return Err(source
            .error(Some(span), format!("the `[{}]` table declares no coordinates", table.table), "this table")
            .with_help("list the coordinates in `shape = [...]` and the symmetry's coordinates in `group = [...]`"));
    }
    let names: Vec<&str> = declared.iter().map(|(n, _)| n.get_ref().as_str()).collect();
    let unknown = |entry: &Spanned<String>, name: &str| {
        source
            .error(
                Some(entry.span()),
                format!("`{}` in `{}` is not a coordinate", entry.get_ref(), key(name)),
                "not in `shape` or `group`",
            )
            .with_help(format!("the coordinates are: {}", names.join(", ")))
    };
    for angle in entries(table.angles) {
        if !names.contains(&angle.get_ref().as_str()) {
            return Err(unknown(angle, "angles"));
        }
    }
    if let Some(order) = table.order {
        let list = order.get_ref();
        if let Some(entry) = list.iter().find(|e| !names.contains(&e.get_ref().as_str())) {
            return Err(unknown(entry, "order"));
        }
        if let Some(pair) = duplicate(list) {
            return Err(twice(source, &key("order"), pair));
        }
        let missing: Vec<&str> = names.iter().copied().filter(|n| !list.iter().any(|e| e.get_ref() == n)).collect();
        if !missing.is_empty() {
            return Err(source
                .error(
                    Some(order.span()),
                    format!(
                        "`{}` is not a permutation of the coordinates: it misses {}",
                        key("order"),
                        missing.join(", ")
                    ),
                    "this order",
                )
                .with_help(format!("list every coordinate once: {}", names.join(", "))));
        }
        declared = list
            .iter()
            .map(|e| *declared.iter().find(|(n, _)| n.get_ref() == e.get_ref()).expect("checked above"))
            .collect();
    }
    let angles = entries(table.angles);
    let coordinates = declared
        .iter()
        .map(|(name, role)| {
            let c = match role {
                Role::Shape => Coordinate::shape(name.get_ref()),
                Role::Group => Coordinate::group(name.get_ref()),
            };
            if angles.iter().any(|a| a.get_ref() == name.get_ref()) {
                c.angle()
            } else {
                c
            }
        })
        .collect();
    Ok(Declared { coordinates, spans: declared.iter().map(|(n, _)| n.span()).collect() })
}

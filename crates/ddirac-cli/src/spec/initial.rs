//! `[initial]`: q0 and exactly one of p0, v0 ([`crate::keys::initial`]), each as an array in the
//! coordinate order or as a table by coordinate name (`q = { x = 0.0, theta = 0.0 }`), refusals
//! pointing at the values.

use std::ops::Range;

use ddirac::InitialMomentum;
use toml::Spanned;

use super::spans::Spans;
use super::{Spec, Vector};
use crate::diagnostics::{SpecError, SpecSource};
use crate::keys::initial::{InitialKey, Values, Which};
use crate::keys::Spelling;

/// The values of a vector as written.
fn values(vector: &Vector) -> Values {
    match vector {
        Vector::InOrder(list) => Values::InOrder(list.iter().map(|v| *v.get_ref()).collect()),
        Vector::ByName(entries) => {
            Values::ByName(entries.iter().map(|(n, v)| (n.get_ref().clone(), *v.get_ref())).collect())
        }
    }
}

/// q0 and exactly one of p0, v0 (of a rigid system's shape coordinates when `rigid`: the rigid
/// body's keys `R`, `Pi`, `Omega` are refused otherwise).
pub fn initial(
    source: &SpecSource,
    spec: &Spec,
    names: &[&str],
    spans: &mut Spans,
    rigid: bool,
) -> Result<(Vec<f64>, InitialMomentum), Box<SpecError>> {
    let initial = spec.initial.get_ref();
    let rigid_keys = [
        initial.r.as_ref().map(|v| (v.span(), "R")),
        initial.pi.as_ref().map(|v| (v.span(), "Pi")),
        initial.omega.as_ref().map(|v| (v.span(), "Omega")),
    ];
    if let Some((span, name)) = rigid_keys.into_iter().flatten().next().filter(|_| !rigid) {
        return Err(source
            .error(Some(span), format!("`initial.{name}` belongs to a rigid body"), "not a key of this system")
            .with_help(
                "`initial.R`, `initial.Pi` and `initial.Omega` are the initial data of `system = \"rigid_body\"`; \
                 this system has coordinates: give `initial.q` and one of `initial.p`, `initial.v`",
            ));
    }
    let Some(q) = &initial.q else {
        return Err(source
            .error(Some(spec.initial.span()), "`initial.q` is missing", "no `q` in this table")
            .with_help(
                "give the initial configuration: `q = [...]` in the coordinate order, or `q = { name = value }`",
            ));
    };
    let of = |which| match which {
        Which::Q => Some(q),
        Which::P => initial.p.as_ref(),
        Which::V => initial.v.as_ref(),
    };
    let span_of = |key| -> Option<Range<usize>> {
        match key {
            InitialKey::Table => Some(spec.initial.span()),
            InitialKey::Vector(which) => of(which).map(|v| v.span()),
            InitialKey::Entry(which, i) => match of(which)?.get_ref() {
                Vector::InOrder(list) => list.get(i).map(|v| v.span()),
                Vector::ByName(entries) => entries.get(i).map(|(_, v)| v.span()),
            },
            InitialKey::Name(which, i) => match of(which)?.get_ref() {
                Vector::ByName(entries) => entries.get(i).map(|(n, _)| n.span()),
                Vector::InOrder(_) => None,
            },
        }
    };
    let given = |v: Option<&Spanned<Vector>>| v.map(|v| values(v.get_ref()));
    let (p, v) = (given(initial.p.as_ref()), given(initial.v.as_ref()));
    let result = crate::keys::initial::initial(&values(q.get_ref()), p.as_ref(), v.as_ref(), names, Spelling::Spec)
        .map_err(|error| source.refusal(error, span_of))?;
    spans.q = Some(q.span());
    spans.momentum = initial.p.as_ref().or(initial.v.as_ref()).map(|x| x.span());
    Ok(result)
}

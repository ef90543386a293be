//! `[initial]`: q0 and exactly one of p0, v0, each as an array in the coordinate order or as a table
//! by coordinate name (`q = { x = 0.0, theta = 0.0 }`).

use ddirac::InitialMomentum;
use miette::LabeledSpan;
use toml::Spanned;

use super::validate::{finite, Spans};
use super::{Spec, Vector};
use crate::diagnostics::{SpecError, SpecSource};

/// A vector with one finite entry per coordinate, in the coordinate order.
pub fn vector(
    source: &SpecSource,
    values: &Spanned<Vector>,
    key: &str,
    names: &[&str],
) -> Result<Vec<f64>, Box<SpecError>> {
    match values.get_ref() {
        Vector::InOrder(list) => {
            if list.len() != names.len() {
                return Err(source
                    .error(
                        Some(values.span()),
                        format!("`{key}` has {} entries, but the system has {} coordinates", list.len(), names.len()),
                        format!("expected {} entries", names.len()),
                    )
                    .with_help(format!("give one entry per coordinate, in order: {}", names.join(", "))));
            }
            list.iter().zip(names).map(|(v, name)| finite(source, v, &format!("`{key}` entry for `{name}`"))).collect()
        }
        Vector::ByName(entries) => {
            if let Some((name, _)) = entries.iter().find(|(n, _)| !names.contains(&n.get_ref().as_str())) {
                return Err(source
                    .error(
                        Some(name.span()),
                        format!("`{key}` gives a value for `{}`, which is not a coordinate", name.get_ref()),
                        "not a coordinate",
                    )
                    .with_help(format!("the coordinates are: {}", names.join(", "))));
            }
            let missing: Vec<&str> =
                names.iter().copied().filter(|n| !entries.iter().any(|(e, _)| e.get_ref() == n)).collect();
            if !missing.is_empty() {
                return Err(source
                    .error(
                        Some(values.span()),
                        format!("`{key}` has no value for {}", quoted(&missing)),
                        format!("missing {}", quoted(&missing)),
                    )
                    .with_help(format!("give one value per coordinate: {}", names.join(", "))));
            }
            names
                .iter()
                .map(|name| {
                    let (_, value) = entries.iter().find(|(n, _)| n.get_ref() == name).expect("checked above");
                    finite(source, value, &format!("`{key}` entry for `{name}`"))
                })
                .collect()
        }
    }
}

fn quoted(names: &[&str]) -> String {
    names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}

/// q0 and exactly one of p0, v0.
pub fn initial(
    source: &SpecSource,
    spec: &Spec,
    names: &[&str],
    spans: &mut Spans,
) -> Result<(Vec<f64>, InitialMomentum), Box<SpecError>> {
    let initial = spec.initial.get_ref();
    let q0 = vector(source, &initial.q, "initial.q", names)?;
    spans.q = Some(initial.q.span());
    let momentum = match (&initial.p, &initial.v) {
        (Some(p), None) => InitialMomentum::Momentum(vector(source, p, "initial.p", names)?),
        (None, Some(v)) => InitialMomentum::Velocity(vector(source, v, "initial.v", names)?),
        (None, None) => {
            return Err(source
                .error(Some(spec.initial.span()), "`[initial]` needs `p` or `v`", "this table")
                .with_help("give the initial momenta as `p = [...]` or the initial velocities as `v = [...]`"))
        }
        (Some(p), Some(v)) => {
            let labels =
                [p, v].iter().map(|x| LabeledSpan::new_with_span(Some("given here".into()), x.span())).collect();
            return Err(source
                .error_with("`[initial]` takes `p` or `v`, not both", labels)
                .with_help("remove one of them: `p` are momenta, `v` velocities mapped to momenta by ∂L/∂v"));
        }
    };
    spans.momentum = initial.p.as_ref().or(initial.v.as_ref()).map(|x| x.span());
    Ok((q0, momentum))
}

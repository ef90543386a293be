//! Checks a parsed [`Spec`] against the system it names and turns it into the library's problem,
//! method and output options. Every rejection points at the value's span.

use std::ops::Range;

use ddirac::systems::BuiltIn;
use ddirac::{
    Coordinate, DynSystem, InitialMomentum, Method, NewtonOptions, OutputOptions, Problem, Role, Rule, Variant,
};
use miette::LabeledSpan;
use toml::Spanned;

use super::{time, Number, Numbers, Spec, SystemRef};
use crate::diagnostics::{SpecError, SpecSource};

/// A validated spec, ready to run.
pub struct Plan {
    /// The built-in system.
    pub built_in: &'static BuiltIn,
    /// The system with its parameters set.
    pub system: Box<dyn DynSystem>,
    /// All parameters with their effective values.
    pub parameters: Vec<(String, f64)>,
    /// Step, steps and initial data.
    pub problem: Problem,
    /// Rule, variant, reduction, connection, Newton options.
    pub method: Method,
    /// Reporting options.
    pub output: OutputOptions,
    /// `output.directory`, if given.
    pub directory: Option<String>,
    /// Where the values came from, to point library errors at them.
    pub spans: Spans,
}

/// Spans of the spec values that library errors can concern.
#[derive(Debug, Default)]
pub struct Spans {
    /// Each parameter override's value.
    pub parameters: Vec<(String, Range<usize>)>,
    /// `initial.q`.
    pub q: Option<Range<usize>>,
    /// `initial.p` or `initial.v`.
    pub momentum: Option<Range<usize>>,
    /// `method.connection`.
    pub connection: Option<Range<usize>>,
    /// `method.reduced`.
    pub reduced: Option<Range<usize>>,
    /// The `[time]` table.
    pub time: Option<Range<usize>>,
    /// `output.every`.
    pub every: Option<Range<usize>>,
}

impl Spans {
    /// The span and label of the spec value a library error is about, if any.
    pub fn locate(&self, error: &ddirac::Error) -> Option<(Range<usize>, &'static str)> {
        use ddirac::Error as E;
        let what = match error {
            E::Size { what, .. } | E::NonFinite { what, .. } | E::Invalid { what, .. } => what.as_str(),
            E::NotInvariant { .. } | E::NoSymmetry => return self.reduced.clone().map(|s| (s, "reduction asked here")),
            _ => return None,
        };
        if let Some((_, span)) = self.parameters.iter().find(|(n, _)| what.contains(&format!("`{n}`"))) {
            Some((span.clone(), "this parameter"))
        } else if what.contains("configuration q") {
            self.q.clone().map(|s| (s, "initial configuration"))
        } else if what.contains("momentum") || what.contains("velocity") {
            self.momentum.clone().map(|s| (s, "initial data"))
        } else if what.contains("connection") {
            self.connection.clone().map(|s| (s, "this connection"))
        } else if what.contains("every") {
            self.every.clone().map(|s| (s, "this value"))
        } else if what.contains("step") {
            self.time.clone().map(|s| (s, "this time grid"))
        } else {
            None
        }
    }
}

/// Validates `spec` and builds the system it names.
pub fn validate(source: &SpecSource, spec: &Spec) -> Result<Plan, Box<SpecError>> {
    let mut spans = Spans { time: Some(spec.time.span()), ..Spans::default() };
    let built_in = built_in(source, &spec.system)?;
    let (parameters, overrides) = parameters(source, spec, built_in, &mut spans)?;
    let system = (built_in.build)(&overrides).map_err(|e| {
        let (span, label) = spans.locate(&e).map_or((None, ""), |(s, l)| (Some(s), l));
        source.error(span, e.to_string(), label)
    })?;
    let coordinates = system.coordinates();
    let method = method(source, spec, &coordinates, &mut spans)?;
    let (step, steps) = time::grid(source, &spec.time)?;

    let names: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
    let (q0, momentum) = initial(source, spec, &names, &mut spans)?;

    let out = &spec.output;
    let every = match &out.every {
        Some(e) if *e.get_ref() >= 1 => *e.get_ref() as usize,
        Some(e) => {
            return Err(source.error(Some(e.span()), "`output.every` must be at least 1", format!("{}", e.get_ref())))
        }
        None => 1,
    };
    spans.every = out.every.as_ref().map(|e| e.span());
    let directory = match &out.directory {
        Some(d) if d.get_ref().trim().is_empty() => {
            return Err(source.error(Some(d.span()), "`output.directory` is empty", "empty"))
        }
        d => d.as_ref().map(|d| d.get_ref().clone()),
    };
    Ok(Plan {
        built_in,
        system,
        parameters,
        problem: Problem::new(step, steps, q0, momentum),
        method,
        output: OutputOptions { every, wrap_angles: out.wrap_angles.as_ref().is_some_and(|w| *w.get_ref()) },
        directory,
        spans,
    })
}

fn built_in(source: &SpecSource, system: &Spanned<SystemRef>) -> Result<&'static BuiltIn, Box<SpecError>> {
    let SystemRef::BuiltIn(name) = system.get_ref();
    ddirac::systems::find(name).ok_or_else(|| {
        let known: Vec<&str> = ddirac::systems::BUILT_IN.iter().map(|b| b.name).collect();
        source
            .error(Some(system.span()), format!("unknown system `{name}`"), "not a built-in system")
            .with_help(format!("built-in systems: {} (see `ddirac systems`)", known.join(", ")))
    })
}

type Parameters = (Vec<(String, f64)>, Vec<(String, f64)>);

/// The effective parameters and the overrides, checked by name and value.
fn parameters(
    source: &SpecSource,
    spec: &Spec,
    built_in: &BuiltIn,
    spans: &mut Spans,
) -> Result<Parameters, Box<SpecError>> {
    let mut all: Vec<(String, f64)> = (built_in.defaults)().into_iter().map(|(n, v)| (n.to_owned(), v)).collect();
    let mut overrides = vec![];
    for (name, value) in &spec.parameters {
        let Some(slot) = all.iter_mut().find(|(n, _)| n == name.get_ref()) else {
            let known: Vec<String> = (built_in.defaults)().iter().map(|(n, v)| format!("{n} (default {v})")).collect();
            return Err(source
                .error(
                    Some(name.span()),
                    format!("unknown parameter `{}` of system `{}`", name.get_ref(), built_in.name),
                    "unknown parameter",
                )
                .with_help(format!("known parameters: {}", known.join(", "))));
        };
        let v = finite(source, value, &format!("parameter `{}`", name.get_ref()))?;
        slot.1 = v;
        overrides.push((name.get_ref().clone(), v));
        spans.parameters.push((name.get_ref().clone(), value.span()));
    }
    Ok((all, overrides))
}

fn method(
    source: &SpecSource,
    spec: &Spec,
    coordinates: &[Coordinate],
    spans: &mut Spans,
) -> Result<Method, Box<SpecError>> {
    let m = &spec.method;
    let defaults = Method::default();
    let rule = match &m.rule {
        Some(r) => Rule::from_name(r.get_ref()).ok_or_else(|| {
            let names: Vec<&str> = Rule::ALL.iter().map(|r| r.name()).collect();
            source
                .error(Some(r.span()), format!("unknown rule `{}`", r.get_ref()), "not a quadrature rule")
                .with_help(format!("`method.rule` is one of: {}", names.join(", ")))
        })?,
        None => defaults.rule,
    };
    let variant = match &m.variant {
        Some(v) => match v.get_ref().as_str() {
            "plus" => Variant::Plus,
            "minus" => Variant::Minus,
            other => {
                return Err(source
                    .error(Some(v.span()), format!("unknown variant `{other}`"), "not a variant")
                    .with_help("`method.variant` is `plus` or `minus`"))
            }
        },
        None => defaults.variant,
    };
    let tolerance = match &m.tolerance {
        Some(t) => {
            let v = finite(source, t, "`method.tolerance`")?;
            if v <= 0.0 {
                return Err(source.error(Some(t.span()), "`method.tolerance` must be positive", format!("{v}")));
            }
            v
        }
        None => defaults.newton.tolerance,
    };
    let max_iterations = match &m.max_iterations {
        Some(n) if *n.get_ref() >= 1 => *n.get_ref() as usize,
        Some(n) => {
            return Err(source.error(
                Some(n.span()),
                "`method.max_iterations` must be at least 1",
                format!("{}", n.get_ref()),
            ))
        }
        None => defaults.newton.max_iterations,
    };
    spans.reduced = m.reduced.as_ref().map(|r| r.span());
    spans.connection = m.connection.as_ref().map(|c| c.span());
    let connection = m.connection.as_ref().map(|k| connection(source, k, coordinates)).transpose()?;
    Ok(Method {
        rule,
        variant,
        reduced: m.reduced.as_ref().is_some_and(|r| *r.get_ref()),
        connection,
        newton: NewtonOptions { tolerance, max_iterations },
        check_invariance: !matches!(&m.check_invariance, Some(c) if !*c.get_ref()),
    })
}

/// K: one row per group coordinate, one column per shape coordinate.
fn connection(
    source: &SpecSource,
    k: &Spanned<Vec<Numbers>>,
    coordinates: &[Coordinate],
) -> Result<Vec<Vec<f64>>, Box<SpecError>> {
    let of = |role| coordinates.iter().filter(|c| c.role == role).map(|c| c.name.as_str()).collect::<Vec<_>>();
    let (shape, group) = (of(Role::Shape), of(Role::Group));
    let expected = format!(
        "K = h_(d,Σ) has one row per group coordinate ({}) and one column per shape coordinate ({}): {} × {}",
        group.join(", "),
        shape.join(", "),
        group.len(),
        shape.len()
    );
    if k.get_ref().len() != group.len() {
        return Err(source
            .error(
                Some(k.span()),
                format!("`method.connection` has {} rows, expected {}", k.get_ref().len(), group.len()),
                "wrong number of rows",
            )
            .with_help(expected));
    }
    let mut rows = vec![];
    for (j, row) in k.get_ref().iter().enumerate() {
        if row.get_ref().len() != shape.len() {
            return Err(source
                .error(
                    Some(row.span()),
                    format!(
                        "row {} of `method.connection` has {} entries, expected {}",
                        j + 1,
                        row.get_ref().len(),
                        shape.len()
                    ),
                    format!("row for `{}`", group[j]),
                )
                .with_help(expected));
        }
        rows.push(
            row.get_ref()
                .iter()
                .map(|v| finite(source, v, "an entry of `method.connection`"))
                .collect::<Result<_, _>>()?,
        );
    }
    Ok(rows)
}

/// A vector with one finite entry per coordinate.
fn vector(source: &SpecSource, values: &Numbers, key: &str, names: &[&str]) -> Result<Vec<f64>, Box<SpecError>> {
    if values.get_ref().len() != names.len() {
        return Err(source
            .error(
                Some(values.span()),
                format!(
                    "`{key}` has {} entries, but the system has {} coordinates",
                    values.get_ref().len(),
                    names.len()
                ),
                format!("expected {} entries", names.len()),
            )
            .with_help(format!("give one entry per coordinate, in order: {}", names.join(", "))));
    }
    values
        .get_ref()
        .iter()
        .zip(names)
        .map(|(v, name)| finite(source, v, &format!("`{key}` entry for `{name}`")))
        .collect()
}

fn finite(source: &SpecSource, value: &Number, what: &str) -> Result<f64, Box<SpecError>> {
    let v = *value.get_ref();
    if v.is_finite() {
        Ok(v)
    } else {
        Err(source.error(Some(value.span()), format!("{what} is not finite ({v})"), "not a finite number"))
    }
}

/// q0 and exactly one of p0, v0.
fn initial(
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

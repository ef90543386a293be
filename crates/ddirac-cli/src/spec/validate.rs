//! Checks a parsed [`Spec`] against the system it names (or defines) and turns it into the library's
//! problem, method and output options. Every rejection points at the value's span.

use std::ops::Range;

use ddirac::systems::BuiltIn;
use ddirac::{Coordinate, DynSystem, Method, OutputOptions, Problem, Role};
use miette::LabeledSpan;
use toml::Spanned;

pub use super::spans::Spans;
use super::{expression, finite, initial, time, MethodSpec, Spec, SystemRef};
use crate::diagnostics::{SpecError, SpecSource};
use crate::keys::{self, method::MethodKey, method::MethodKeys, Spelling};

/// A validated spec, ready to run.
pub struct Plan {
    /// The system's name: the built-in's name, or `system.name` of a `[system]` table.
    pub name: String,
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

/// Validates `spec` and builds the system it names or defines.
pub fn validate(source: &SpecSource, spec: &Spec) -> Result<Plan, Box<SpecError>> {
    let mut spans = Spans {
        time: Some(spec.time.span()),
        system: Some(spec.system.span()),
        built_in: matches!(spec.system.get_ref(), SystemRef::BuiltIn(_)),
        ..Spans::default()
    };
    // The span of each coordinate's name in a `[system]` table.
    let mut declared: Vec<(String, Range<usize>)> = vec![];
    let (name, system, parameters) = match spec.system.get_ref() {
        SystemRef::BuiltIn(name) if name == super::RIGID_BODY => {
            return Err(source
                .error(Some(spec.system.span()), "this command does not take the rigid body yet", "a rigid body")
                .with_help(
                    "`ddirac run` runs `rigid_body` (also with `--compare`), `ddirac check` checks it, `ddirac \
                     convergence` studies it, `ddirac ensemble` runs its members, and Python's `ddirac.simulate` and \
                     `ddirac.ensemble` take it; `ddirac.load` takes the systems in coordinates (`ddirac systems`)",
                ))
        }
        SystemRef::BuiltIn(name) => {
            let built_in = built_in(source, name, spec.system.span())?;
            let (parameters, overrides) = parameters(source, spec, built_in, &mut spans)?;
            let system = (built_in.build)(&overrides).map_err(|e| {
                let (span, label) = spans.locate(&e).map_or((None, ""), |(s, l)| (Some(s), l));
                source.error(span, e.to_string(), label)
            })?;
            (built_in.name.to_owned(), system, parameters)
        }
        SystemRef::Expression(table) if table.attitude.is_some() => {
            return Err(source
                .error(Some(spec.system.span()), "this command does not take rigid systems yet", "a rigid system")
                .with_help(
                    "`ddirac run` (also with `--compare`), `ddirac check`, `ddirac convergence` and `ddirac \
                     ensemble` take a `[system]` with an `attitude`, and Python's `ddirac.RigidBody`, \
                     `ddirac.simulate` and `ddirac.ensemble`; `ddirac.load` takes the systems in coordinates",
                ))
        }
        SystemRef::Expression(table) => {
            if let Some(symmetry) = &table.symmetry {
                return Err(source
                    .error(Some(symmetry.span()), "`system.symmetry` belongs to rigid systems", "no attitude here")
                    .with_help(
                        "a system in coordinates lists the coordinates its symmetry translates in `group`; \
                        `symmetry` declares the rotations leaving a rigid system (`attitude = \"SO(3)\"`) invariant",
                    ));
            }
            let built = expression::build(source, spec, table, spec.system.span())?;
            spans.angles = table
                .angles
                .as_ref()
                .map(|list| list.get_ref().iter().map(|a| (a.get_ref().clone(), a.span())).collect())
                .unwrap_or_default();
            let coordinates = built.system.coordinates();
            declared.clone_from(&built.coordinates);
            spans.group = built
                .coordinates
                .into_iter()
                .filter(|(n, _)| coordinates.iter().any(|c| &c.name == n && c.role == Role::Group))
                .collect();
            (built.name, built.system, built.parameters)
        }
    };
    let coordinates = system.coordinates();
    distinct_columns(source, &coordinates, &declared, spec.system.span())?;
    let method = method(source, spec, &coordinates, &mut spans)?;
    let (step, steps) = time::grid(source, &spec.time)?;

    let names: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
    let (q0, momentum) = initial::initial(source, spec, &names, &mut spans, false)?;

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
        name,
        system,
        parameters,
        problem: Problem::new(step, steps, q0, momentum),
        method,
        output: OutputOptions { every, wrap_angles: out.wrap_angles.as_ref().is_some_and(|w| *w.get_ref()) },
        directory,
        spans,
    })
}

/// Refuses a coordinate whose name is that of another output column: `t`, `energy`,
/// `discrete_energy`, `p_<coordinate>` or `momentum_<group coordinate>`. The error points at the
/// coordinate's name in `shape`/`group` (at `system` for a built-in system), and at the coordinate
/// the other column belongs to.
fn distinct_columns(
    source: &SpecSource,
    coordinates: &[Coordinate],
    declared: &[(String, Range<usize>)],
    system: Range<usize>,
) -> Result<(), Box<SpecError>> {
    let names: Vec<String> = coordinates.iter().map(|c| c.name.clone()).collect();
    let group: Vec<String> = coordinates.iter().filter(|c| c.role == Role::Group).map(|c| c.name.clone()).collect();
    let columns = crate::output::columns(&names, &group, true);
    let n = names.len();
    let span_of = |name: &str| declared.iter().find(|(d, _)| d == name).map_or(system.clone(), |(_, s)| s.clone());
    for (i, name) in names.iter().enumerate() {
        let Some(j) = columns.iter().enumerate().position(|(j, c)| j != i + 1 && c == name) else { continue };
        let (what, owner) = match j {
            0 => ("the time column `t`".to_owned(), None),
            j if (n + 1..=2 * n).contains(&j) => {
                (format!("the momentum column of the coordinate `{}`", names[j - n - 1]), Some(&names[j - n - 1]))
            }
            j if j == 2 * n + 1 => ("the column `energy` (the Hamiltonian H)".to_owned(), None),
            j if j == 2 * n + 2 => ("the column `discrete_energy` (L_d)".to_owned(), None),
            j => {
                let g = &group[j - 2 * n - 3];
                (format!("the momentum-map column of the group coordinate `{g}`"), Some(g))
            }
        };
        let mut labels = vec![LabeledSpan::new_with_span(Some(format!("`{name}` is also {what}")), span_of(name))];
        if let Some((owner, span)) = owner.and_then(|o| declared.iter().find(|(d, _)| d == o)) {
            labels.push(LabeledSpan::new_with_span(Some(format!("the coordinate `{owner}`")), span.clone()));
        }
        return Err(source
            .error_with(format!("the coordinate `{name}` has the name of another output column: {what}"), labels)
            .with_help(
                "rename the coordinate: trajectory.csv (and npy/) have the columns t, the coordinates, p_<coordinate>, \
                 energy, discrete_energy and momentum_<group coordinate>",
            ));
    }
    Ok(())
}

fn built_in(source: &SpecSource, name: &str, span: Range<usize>) -> Result<&'static BuiltIn, Box<SpecError>> {
    ddirac::systems::find(name).ok_or_else(|| {
        let known: Vec<&str> = ddirac::systems::BUILT_IN.iter().map(|b| b.name).collect();
        source.error(Some(span), format!("unknown system `{name}`"), "not a built-in system").with_help(format!(
            "built-in systems: {} (see `ddirac systems`); or define one in a `[system]` table",
            known.join(", ")
        ))
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

/// The `[method]` of `spec` for a system of `coordinates`, refusals pointing at the keys.
pub(crate) fn method(
    source: &SpecSource,
    spec: &Spec,
    coordinates: &[Coordinate],
    spans: &mut Spans,
) -> Result<Method, Box<SpecError>> {
    let m = &spec.method;
    let text = |v: &Option<Spanned<String>>| v.as_ref().map(|v| v.get_ref().clone());
    let value = |v: &Option<Spanned<bool>>| v.as_ref().map(|v| *v.get_ref());
    let keys = MethodKeys {
        rule: text(&m.rule),
        variant: text(&m.variant),
        reduced: value(&m.reduced),
        connection: m
            .connection
            .as_ref()
            .map(|k| k.get_ref().iter().map(|row| row.get_ref().iter().map(|x| *x.get_ref()).collect()).collect()),
        tolerance: m.tolerance.as_ref().map(|t| *t.get_ref()),
        max_iterations: m.max_iterations.as_ref().map(|n| *n.get_ref()),
        jacobian: text(&m.jacobian),
        derivatives: text(&m.derivatives),
        check_invariance: value(&m.check_invariance),
        on_energy_jump: text(&m.on_energy_jump),
        energy_jump_threshold: m.energy_jump_threshold.as_ref().map(|t| *t.get_ref()),
        order: m.order.as_ref().map(|o| *o.get_ref()),
        composition: text(&m.composition),
        atlas: value(&m.atlas),
        sensitivities: value(&m.sensitivities),
    };
    let method = keys::method::method(&keys, coordinates, Spelling::Spec)
        .map_err(|error| source.refusal(error, |key| method_span(m, key)))?;
    spans.composition = m.composition.as_ref().map(|c| c.span()).or_else(|| m.order.as_ref().map(|o| o.span()));
    spans.reduced = m.reduced.as_ref().map(|r| r.span());
    spans.tolerance = m.tolerance.as_ref().map(|t| t.span());
    spans.energy_jump = m.on_energy_jump.as_ref().map(|a| a.span());
    spans.connection = m.connection.as_ref().map(|c| c.span());
    Ok(method)
}

/// Where `[method]` writes the value of `key`.
fn method_span(m: &MethodSpec, key: MethodKey) -> Option<Range<usize>> {
    fn span<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
        v.as_ref().map(|v| v.span())
    }
    let connection = m.connection.as_ref().map(|k| k.get_ref());
    match key {
        MethodKey::Rule => span(&m.rule),
        MethodKey::Variant => span(&m.variant),
        MethodKey::Reduced => span(&m.reduced),
        MethodKey::Connection => span(&m.connection),
        MethodKey::ConnectionRow(j) => connection?.get(j).map(|row| row.span()),
        MethodKey::ConnectionEntry(j, i) => connection?.get(j)?.get_ref().get(i).map(|x| x.span()),
        MethodKey::Tolerance => span(&m.tolerance),
        MethodKey::MaxIterations => span(&m.max_iterations),
        MethodKey::Jacobian => span(&m.jacobian),
        MethodKey::Derivatives => span(&m.derivatives),
        MethodKey::CheckInvariance => span(&m.check_invariance),
        MethodKey::OnEnergyJump => span(&m.on_energy_jump),
        MethodKey::EnergyJumpThreshold => span(&m.energy_jump_threshold),
        MethodKey::Order => span(&m.order),
        MethodKey::Composition => span(&m.composition),
        MethodKey::Atlas => span(&m.atlas),
        MethodKey::Sensitivities => span(&m.sensitivities),
    }
}

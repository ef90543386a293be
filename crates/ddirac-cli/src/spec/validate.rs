//! Checks a parsed [`Spec`] against the system it names (or defines) and turns it into the library's
//! problem, method and output options. Every rejection points at the value's span.

use std::ops::Range;

use ddirac::composition::{self, Composition};
use ddirac::systems::BuiltIn;
use ddirac::{
    Coordinate, Differentiation, DynSystem, EnergyJump, JumpAction, Method, NewtonOptions, OutputOptions, Problem,
    Role, Rule, Variant,
};
use miette::LabeledSpan;
use toml::Spanned;

use super::{expression, initial, time, MethodSpec, Number, Numbers, Spec, SystemRef};
use crate::diagnostics::{SpecError, SpecSource};

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
    /// The `system` value (name or table).
    pub system: Option<Range<usize>>,
    /// The declaration of each group coordinate in `system.group`, by name (`[system]` tables only).
    pub group: Vec<(String, Range<usize>)>,
    /// Each entry of `system.angles`, by name (`[system]` tables only).
    pub angles: Vec<(String, Range<usize>)>,
    /// `method.tolerance`.
    pub tolerance: Option<Range<usize>>,
    /// `method.on_energy_jump`.
    pub energy_jump: Option<Range<usize>>,
    /// `method.composition`, else `method.order`.
    pub composition: Option<Range<usize>>,
    /// Whether the system is a built-in one (named) rather than a `[system]` table.
    pub built_in: bool,
}

impl Spans {
    /// The span and label of the spec value a library error is about, if any.
    pub fn locate(&self, error: &ddirac::Error) -> Option<(Range<usize>, &'static str)> {
        use ddirac::{Error as E, Hypothesis, Input};
        let what = match error {
            E::Size { what, .. } | E::NonFinite { what, .. } | E::Invalid { what, .. } => what,
            E::Undecided { hypothesis: Hypothesis::Periodicity, coordinate, .. } => {
                return match self.angles.iter().find(|(n, _)| n == coordinate) {
                    Some((_, span)) => Some((span.clone(), "this angle")),
                    None => self.system.clone().map(|s| (s, "this system")),
                }
            }
            E::NotInvariant { .. } | E::NoSymmetry | E::Undecided { .. } => {
                return self.reduced.clone().map(|s| (s, "reduction asked here"))
            }
            E::OffPrimaryConstraint { .. } => return self.momentum.clone().map(|s| (s, "off the primary constraint")),
            E::Chart { .. } => return self.system.clone().map(|s| (s, "the atlas of this system")),
            E::Undetermined { .. } => return self.system.clone().map(|s| (s, "this system")),
            E::Newton { .. } | E::Diverged { .. } | E::EnergyJump { .. } => {
                return self.time.clone().map(|s| (s, "this time grid"))
            }
            _ => return None,
        };
        match what {
            Input::Parameter(name) => {
                self.parameters.iter().find(|(n, _)| n == name).map(|(_, span)| (span.clone(), "this parameter"))
            }
            Input::InitialConfiguration => self.q.clone().map(|s| (s, "initial configuration")),
            Input::InitialMomentum | Input::InitialVelocity | Input::MomentumFromVelocity => {
                self.momentum.clone().map(|s| (s, "initial data"))
            }
            Input::Connection => self.connection.clone().map(|s| (s, "this connection")),
            Input::Composition => self.composition.clone().map(|s| (s, "this composition")),
            Input::Every => self.every.clone().map(|s| (s, "this value")),
            Input::Step | Input::Steps => self.time.clone().map(|s| (s, "this time grid")),
            _ => None,
        }
    }

    /// A library error as a diagnostic pointing at the spec values it concerns, if it concerns any.
    ///
    /// A refused reduction points at `reduced = true` and, for a `[system]` table, at the group
    /// coordinate whose translation changes L_d.
    pub fn diagnostic(&self, source: &SpecSource, error: &ddirac::Error) -> Option<Box<SpecError>> {
        let mut labels: Vec<LabeledSpan> = self
            .locate(error)
            .map(|(span, label)| LabeledSpan::new_with_span(Some(label.into()), span))
            .into_iter()
            .collect();
        let help = match error {
            ddirac::Error::NotInvariant { coordinate, tolerance, .. } => {
                if let Some((_, span)) = self.group.iter().find(|(n, _)| n == coordinate) {
                    let label = format!("L_d is not invariant under translations of `{coordinate}`");
                    labels.push(LabeledSpan::new_with_span(Some(label), span.clone()));
                }
                Some(format!(
                    "reduction needs L_d(q0 + a, q1 + a) = L_d(q0, q1) for translations a of every group coordinate \
                     (relative tolerance {tolerance:.0e}); run the unreduced equations (`reduced = false`), or \
                     choose group coordinates that the Lagrangian does not depend on"
                ))
            }
            ddirac::Error::NotPeriodic { coordinate, .. } => {
                if let Some((_, span)) = self.angles.iter().find(|(n, _)| n == coordinate) {
                    let label = format!("L is not 2π-periodic in `{coordinate}`");
                    labels.push(LabeledSpan::new_with_span(Some(label), span.clone()));
                }
                Some(format!(
                    "the chart of an angle wraps it to (−π, π], which changes the motion unless L(q + 2π e, v) = \
                     L(q, v); remove `{coordinate}` from `angles` if it is not an angle on the circle"
                ))
            }
            ddirac::Error::Undecided { hypothesis: ddirac::Hypothesis::Periodicity, .. } => Some(
                "L_d is not finite near the initial data, so the hypothesis could not be tested: check the initial \
                 data and where the Lagrangian is defined; remove the coordinate from `angles` if it is not an angle \
                 on the circle"
                    .into(),
            ),
            ddirac::Error::Undecided { .. } => Some(
                "L_d is not finite near the initial data, so the hypothesis could not be tested: check the initial \
                 data and where the Lagrangian is defined; `check_invariance = false` reduces anyway, with a warning"
                    .into(),
            ),
            ddirac::Error::Undetermined { .. } => Some(
                "every velocity must enter the Lagrangian so that the step equations fix the next configuration \
                 (for a Lagrangian linear in the velocities, as point vortices', their coefficients must make \
                 D1D2 L_d invertible): check its terms and parameters"
                    .into(),
            ),
            ddirac::Error::OffPrimaryConstraint { .. } => Some(
                "for a degenerate Lagrangian p0 is fixed by q0 where L is linear in the velocities: give p0 = \
                 ∂L/∂v(q0, v0), or give the velocities `v` instead of `p`"
                    .into(),
            ),
            ddirac::Error::Newton { .. } | ddirac::Error::Diverged { .. } | ddirac::Error::EnergyJump { .. } => {
                if let Some(span) = self.tolerance.clone() {
                    labels.push(LabeledSpan::new_with_span(Some("Newton tolerance".into()), span));
                }
                if let (ddirac::Error::EnergyJump { .. }, Some(span)) = (error, self.energy_jump.clone()) {
                    labels.push(LabeledSpan::new_with_span(Some("a jump is an error here".into()), span));
                }
                Some(
                    "a smaller step (`time.step`, or more `time.steps`) resolves the motion better; near a \
                     singularity of the coordinates or of the Lagrangian no step may suffice"
                        .into(),
                )
            }
            ddirac::Error::Chart { .. } => Some(
                "a run through an atlas steps in each chart with the Lagrangian carried there by `to_main`, and moves \
                 between charts by `from_main`: both must be exact inverses on the chart's domain (where its \
                 `quality` is positive), its `quality` high only where the chart is regular, and its group \
                 coordinates symmetries of L; `method.atlas = false` runs in the main chart alone"
                    .into(),
            ),
            ddirac::Error::NoSymmetry => {
                if let Some(span) = self.system.clone().filter(|_| labels.is_empty()) {
                    labels.push(LabeledSpan::new_with_span(Some("no group coordinate".into()), span));
                }
                Some(if self.built_in {
                    "this system has no symmetry to reduce by: run the unreduced equations (`reduced = false`)".into()
                } else {
                    "list the coordinates translated by the symmetry in `system.group`".into()
                })
            }
            _ => None,
        };
        if labels.is_empty() {
            return None;
        }
        let message = match error {
            ddirac::Error::Newton { .. } | ddirac::Error::Diverged { .. } | ddirac::Error::EnergyJump { .. } => {
                format!("the integration failed: {error}")
            }
            _ => error.to_string(),
        };
        let diagnostic = source.error_with(message, labels);
        Some(match help {
            Some(help) => diagnostic.with_help(help),
            None => diagnostic,
        })
    }
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
        SystemRef::BuiltIn(name) => {
            let built_in = built_in(source, name, spec.system.span())?;
            let (parameters, overrides) = parameters(source, spec, built_in, &mut spans)?;
            let system = (built_in.build)(&overrides).map_err(|e| {
                let (span, label) = spans.locate(&e).map_or((None, ""), |(s, l)| (Some(s), l));
                source.error(span, e.to_string(), label)
            })?;
            (built_in.name.to_owned(), system, parameters)
        }
        SystemRef::Expression(table) => {
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
    let (q0, momentum) = initial::initial(source, spec, &names, &mut spans)?;

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
    let reuse_jacobian = match &m.jacobian {
        Some(j) => match j.get_ref().as_str() {
            "reuse" => true,
            "fresh" => false,
            other => {
                return Err(source
                    .error(Some(j.span()), format!("unknown Jacobian policy `{other}`"), "not a policy")
                    .with_help(
                    "`method.jacobian` is `reuse` (one Jacobian per step, chord Newton) or `fresh` (classical Newton)",
                ))
            }
        },
        None => defaults.newton.reuse_jacobian,
    };
    let differentiation = match &m.derivatives {
        Some(d) => Differentiation::from_name(d.get_ref()).ok_or_else(|| {
            source
                .error(Some(d.span()), format!("unknown derivative evaluation `{}`", d.get_ref()), "not a choice")
                .with_help(
                    "`method.derivatives` is `auto` (compiled when the Lagrangian allows it), `compiled` or `dual`",
                )
        })?,
        None => defaults.differentiation,
    };
    let action = match &m.on_energy_jump {
        Some(a) => JumpAction::from_name(a.get_ref()).ok_or_else(|| {
            source
                .error(Some(a.span()), format!("unknown action `{}`", a.get_ref()), "not an action")
                .with_help("`method.on_energy_jump` is `warn` (default), `error` or `ignore`")
        })?,
        None => defaults.energy_jump.action,
    };
    let threshold = match &m.energy_jump_threshold {
        Some(t) => {
            let v = finite(source, t, "`method.energy_jump_threshold`")?;
            if v <= 0.0 {
                return Err(source.error(
                    Some(t.span()),
                    "`method.energy_jump_threshold` must be positive",
                    format!("{v}"),
                ));
            }
            v
        }
        None => defaults.energy_jump.threshold,
    };
    let composition = composition(source, m)?;
    spans.composition = m.composition.as_ref().map(|c| c.span()).or_else(|| m.order.as_ref().map(|o| o.span()));
    spans.reduced = m.reduced.as_ref().map(|r| r.span());
    spans.tolerance = m.tolerance.as_ref().map(|t| t.span());
    spans.energy_jump = m.on_energy_jump.as_ref().map(|a| a.span());
    spans.connection = m.connection.as_ref().map(|c| c.span());
    let connection = match &m.connection {
        Some(k) => {
            let rows = connection(source, k, coordinates)?;
            let connection = ddirac::Connection::new(&rows)
                .map_err(|e| source.error(Some(k.span()), e.to_string(), "this connection"));
            Some(connection?)
        }
        None => None,
    };
    Ok(Method {
        rule,
        variant,
        reduced: m.reduced.as_ref().is_some_and(|r| *r.get_ref()),
        connection,
        newton: NewtonOptions { tolerance, max_iterations, reuse_jacobian },
        check_invariance: !matches!(&m.check_invariance, Some(c) if !*c.get_ref()),
        differentiation,
        energy_jump: EnergyJump { threshold, action },
        composition,
        atlas: !matches!(&m.atlas, Some(a) if !*a.get_ref()),
    })
}

/// `method.order` and `method.composition`: the composition of a step.
fn composition(source: &SpecSource, m: &MethodSpec) -> Result<Composition, Box<SpecError>> {
    let order = match &m.order {
        Some(o) => match u8::try_from(*o.get_ref()) {
            Ok(order) if composition::ORDERS.contains(&order) => Some(order),
            _ => {
                return Err(source
                    .error(Some(o.span()), format!("there is no method of order {}", o.get_ref()), "not an order")
                    .with_help("`method.order` is 2 (the basic step), 4, 6 or 8 (compositions of it)"))
            }
        },
        None => None,
    };
    let name = m.composition.as_ref().map(|c| c.get_ref().as_str());
    Composition::select(order, name).map_err(|why| {
        let span = m.composition.as_ref().map(|c| c.span());
        source.error(span, why, "this composition").with_help(
            "`method.composition` is `suzuki` (order 4), `kahan-li` (orders 6, 8) or `triple-jump` (orders 4, 6, 8)",
        )
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

/// `value`, if it is finite; `what` names it in the error.
pub fn finite(source: &SpecSource, value: &Number, what: &str) -> Result<f64, Box<SpecError>> {
    let v = *value.get_ref();
    if v.is_finite() {
        Ok(v)
    } else {
        Err(source.error(Some(value.span()), format!("{what} is not finite ({v})"), "not a finite number"))
    }
}

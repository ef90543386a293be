//! Checks a parsed [`Spec`] against the system it names (or defines) and turns it into the library's
//! problem, method and output options. Every rejection points at the value's span.

use std::ops::Range;

use ddirac::systems::BuiltIn;
use ddirac::{Coordinate, DynSystem, Method, OutputOptions, Problem, Role};
use miette::LabeledSpan;
use toml::Spanned;

use super::{expression, initial, time, MethodSpec, Number, Spec, SystemRef};
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
    }
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

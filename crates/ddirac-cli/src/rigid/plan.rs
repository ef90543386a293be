//! A spec of a rigid system checked and turned into the library's [`RigidProblem`] and [`Method`]:
//! the built-in rigid body (`system = "rigid_body"`, the parameters of [`RigidBody`]) or a `[system]`
//! table with `attitude = "SO(3)"` (a Lagrangian in `R11` … `R33`, `Omega1` … `Omega3` and shape
//! coordinates, with its `symmetry`); the attitude `initial.R` (three rows of three numbers, a rotation
//! to [`ROTATION_TOLERANCE`]), exactly one of `initial.Pi`, `initial.Omega`, and for shape coordinates
//! `initial.q` with `initial.p` (beside `Pi`) or `initial.v` (beside `Omega`). Every refusal points at
//! the value's span.

use std::ops::Range;

use ddirac::rigid::{
    PrincipalAxes, RigidExpressionSystem, RigidInitial, RigidProblem, RigidSystem, Symmetry, ROTATION_TOLERANCE,
};
use ddirac::systems::{Parameters, RigidBody};
use ddirac::{Coordinate, Error, InitialMomentum, Input, Method, Scalar};
use toml::Spanned;

use crate::diagnostics::{SpecError, SpecSource};
use crate::spec::{self, Number, Numbers, Spans, Spec, SystemRef, SystemTable};

/// A rigid system of a spec: the built-in body or one whose Lagrangian is text.
#[derive(Debug, Clone)]
pub enum RigidModel {
    /// `system = "rigid_body"`.
    Body(RigidBody),
    /// A `[system]` table with `attitude = "SO(3)"`.
    Text(Box<RigidExpressionSystem>),
}

impl RigidSystem for RigidModel {
    fn shape(&self) -> Vec<Coordinate> {
        match self {
            RigidModel::Body(b) => b.shape(),
            RigidModel::Text(t) => t.shape(),
        }
    }

    fn lagrangian<D: Scalar>(&self, r: &[[D; 3]; 3], omega: &[D; 3], s: &[D], v: &[D]) -> D {
        match self {
            RigidModel::Body(b) => b.lagrangian(r, omega, s, v),
            RigidModel::Text(t) => t.lagrangian(r, omega, s, v),
        }
    }

    fn symmetry(&self) -> Symmetry {
        match self {
            RigidModel::Body(b) => b.symmetry(),
            RigidModel::Text(t) => t.symmetry(),
        }
    }

    fn principal_axes(&self) -> Option<PrincipalAxes> {
        match self {
            RigidModel::Body(b) => b.principal_axes(),
            RigidModel::Text(t) => t.principal_axes(),
        }
    }
}

/// A validated rigid system's spec, ready to run.
pub struct RigidPlan {
    /// `rigid_body`, or `system.name` of a `[system]` table (default `custom`).
    pub name: String,
    /// The system with its parameters set.
    pub body: RigidModel,
    /// All parameters with their effective values, in the body's order (as written for a table).
    pub parameters: Vec<(String, f64)>,
    /// Step, steps and initial data.
    pub problem: RigidProblem,
    /// Rule, reduction, composition, Newton options.
    pub method: Method,
    /// Report every `every`-th step (and the last).
    pub every: usize,
    /// `output.directory`, if given.
    pub directory: Option<String>,
}

/// Validates a spec naming the rigid body or defining a rigid system.
pub fn validate(source: &SpecSource, spec: &Spec) -> Result<RigidPlan, Box<SpecError>> {
    let (name, body, parameters) = match spec.system.get_ref() {
        SystemRef::Expression(table) => text_system(source, spec, table)?,
        SystemRef::BuiltIn(_) => {
            let (body, parameters) = body(source, spec)?;
            (super::NAME.to_owned(), RigidModel::Body(body), parameters)
        }
    };
    if let Some(k) = &spec.method.connection {
        return Err(source
            .error(Some(k.span()), "a rigid body takes no `method.connection`", "no connection here")
            .with_help("a rigid body is reduced by SO(3) itself (`method.reduced = true`), without a connection K"));
    }
    if let Some(a) = &spec.method.atlas {
        return Err(source
            .error(Some(a.span()), "a rigid body takes no `method.atlas`", "no atlas here")
            .with_help("the attitude is advanced on SO(3) itself, in no chart: there are no charts to switch"));
    }
    if let Some(s) = spec.method.sensitivities.as_ref().filter(|s| *s.get_ref()) {
        return Err(source
            .error(Some(s.span()), "a rigid body has no tangent map yet", "not for a rigid body")
            .with_help("`method.sensitivities` is available for systems in coordinates; remove it for a rigid body"));
    }
    let method = spec::method_of(source, spec, &[], &mut Spans::default())?;
    let (step, steps) = spec::grid(source, &spec.time)?;
    let shape = body.shape();
    let r0 = attitude(source, spec)?;
    let (s0, shape_momentum) = shape_data(source, spec, &shape)?;
    let values = shape_momentum_values(&shape_momentum).unwrap_or_default();
    let momenta = shape_momentum.as_ref().map(|m| matches!(m, InitialMomentum::Momentum(_)));
    let initial = spec.initial.get_ref();
    let initial = match (&initial.pi, &initial.omega, momenta) {
        (Some(pi), None, None | Some(true)) => {
            RigidInitial::Momentum { pi: vector(source, pi, "initial.Pi")?, p: values }
        }
        (None, Some(omega), None | Some(false)) => {
            RigidInitial::Velocity { omega: vector(source, omega, "initial.Omega")?, v: values }
        }
        (Some(pi), Some(omega), _) => {
            return Err(source
                .error_with(
                    "`initial.Pi` and `initial.Omega` are both given",
                    vec![
                        miette::LabeledSpan::new_with_span(Some("the angular momentum".into()), pi.span()),
                        miette::LabeledSpan::new_with_span(Some("the angular velocity".into()), omega.span()),
                    ],
                )
                .with_help("give one of them: the other follows from it (Π = ∂ℓ/∂Ω)"))
        }
        (None, None, _) => {
            return Err(source
                .error(Some(spec.initial.span()), "neither `initial.Pi` nor `initial.Omega` is given", "in this table")
                .with_help("give the body angular momentum `Pi = [..]` or the body angular velocity `Omega = [..]`"))
        }
        (pi, _, _) => {
            let (given, other) = if pi.is_some() { ("Pi", "p") } else { ("Omega", "v") };
            return Err(source
                .error(
                    Some(spec.initial.span()),
                    format!("`initial.{given}` goes with the shape's `initial.{other}`"),
                    "in this table",
                )
                .with_help(
                    "give momenta with momenta (`Pi` and `p`) or velocities with velocities (`Omega` and `v`): the \
                     Legendre transform maps them together",
                ));
        }
    };
    let problem = RigidProblem { s0, ..RigidProblem::new(step, steps, r0, initial) };
    let out = &spec.output;
    let every = match &out.every {
        Some(e) if *e.get_ref() >= 1 => *e.get_ref() as usize,
        Some(e) => {
            return Err(source.error(Some(e.span()), "`output.every` must be at least 1", format!("{}", e.get_ref())))
        }
        None => 1,
    };
    if let Some(w) = &out.wrap_angles {
        return Err(source
            .error(Some(w.span()), "a rigid body takes no `output.wrap_angles`", "no angles here")
            .with_help("the attitude is written as the rotation matrix R (columns R11 … R33), which has no angles"));
    }
    let directory = match &out.directory {
        Some(d) if d.get_ref().trim().is_empty() => {
            return Err(source.error(Some(d.span()), "`output.directory` is empty", "empty"))
        }
        d => d.as_ref().map(|d| d.get_ref().clone()),
    };
    Ok(RigidPlan { name, body, parameters, problem, method, every, directory })
}

/// The values of shape momenta or velocities.
fn shape_momentum_values(momentum: &Option<InitialMomentum>) -> Option<Vec<f64>> {
    match momentum {
        Some(InitialMomentum::Momentum(p)) => Some(p.clone()),
        Some(InitialMomentum::Velocity(v)) => Some(v.clone()),
        None => None,
    }
}

/// The shape's initial values and momenta or velocities: `initial.q` with `initial.p` or `initial.v`
/// for shape coordinates, nothing (and none of those keys) without.
fn shape_data(
    source: &SpecSource,
    spec: &Spec,
    shape: &[Coordinate],
) -> Result<(Vec<f64>, Option<InitialMomentum>), Box<SpecError>> {
    let initial = spec.initial.get_ref();
    if shape.is_empty() {
        let given = [("q", initial.q.as_ref().map(|v| v.span())), ("p", initial.p.as_ref().map(|v| v.span()))]
            .into_iter()
            .chain([("v", initial.v.as_ref().map(|v| v.span()))]);
        for (name, span) in given {
            if let Some(span) = span {
                return Err(source
                    .error(Some(span), format!("a rigid body takes no `initial.{name}`"), "not a key of this body")
                    .with_help(
                        "this body has no shape coordinates: its initial data are the attitude `R` (3 rows of 3 \
                         numbers, body to space) and one of `Pi` (the body angular momentum) and `Omega` (the body \
                         angular velocity)",
                    ));
            }
        }
        return Ok((vec![], None));
    }
    let names: Vec<&str> = shape.iter().map(|c| c.name.as_str()).collect();
    let (q0, momentum) = spec::initial::initial(source, spec, &names, &mut Spans::default(), true)?;
    Ok((q0, Some(momentum)))
}

/// The rigid system of a `[system]` table: `attitude = "SO(3)"`, `symmetry`, no `group`, charts or
/// exact solutions.
fn text_system(source: &SpecSource, spec: &Spec, table: &SystemTable) -> Result<Named, Box<SpecError>> {
    let span = spec.system.span();
    let refuse = |at: Range<usize>, key: &str, why: &str| {
        Err(source
            .error(Some(at), format!("a rigid system takes no `system.{key}`"), "not for a rigid system")
            .with_help(why.to_owned()))
    };
    if let Some(attitude) = table.attitude.as_ref().filter(|a| a.get_ref() != "SO(3)") {
        return Err(source
            .error(Some(attitude.span()), format!("unknown attitude group `{}`", attitude.get_ref()), "not SO(3)")
            .with_help("`system.attitude = \"SO(3)\"`: the attitude is a rotation R (body to space)"));
    }
    if let Some(group) = &table.group {
        return refuse(
            group.span(),
            "group",
            "its group is SO(3), acting on the attitude R: list no group coordinates; \
            what it leaves invariant is `symmetry`",
        );
    }
    if let Some(charts) = &table.charts {
        let at = charts.first().map_or(span.clone(), |c| c.span());
        return refuse(at, "charts", "the attitude is advanced on SO(3) itself, in no chart");
    }
    if let Some(q) = &table.quality {
        return refuse(q.span(), "quality", "the attitude is advanced on SO(3) itself, in no chart");
    }
    if let Some(exact) = &table.exact {
        return refuse(exact.span(), "exact", "exact solutions of rigid systems are not taken");
    }
    let symmetry = match &table.symmetry {
        Some(s) => match s.get_ref().as_str() {
            "SO(3)" => Symmetry::Rotations,
            "vertical" => Symmetry::Vertical,
            "none" => Symmetry::None,
            other => {
                return Err(source
                    .error(Some(s.span()), format!("unknown symmetry `{other}`"), "not a symmetry")
                    .with_help(
                        "`system.symmetry` is `SO(3)` (every rotation of space), `vertical` (rotations about \
                        e3) or `none`",
                    ))
            }
        },
        None => {
            return Err(source.error(Some(span), "a rigid system declares its `symmetry`", "in this table").with_help(
                "write `symmetry = \"SO(3)\"` (L invariant under every rotation of space), `\"vertical\"` \
                    (under rotations about e3) or `\"none\"`: the check tests it before a run",
            ))
        }
    };
    let (system, parameters) = spec::expression::build_rigid(source, spec, table, span, symmetry)?;
    let name = table.name.as_ref().map_or_else(|| "custom".to_owned(), |n| n.get_ref().clone());
    Ok((name, RigidModel::Text(Box::new(system)), parameters))
}

/// A system with its name and its parameters with their values.
type Named = (String, RigidModel, Vec<(String, f64)>);

/// A body and all its parameters with their values, in the body's order.
type BodyParameters = (RigidBody, Vec<(String, f64)>);

/// The body with the spec's parameters, and all its parameters.
fn body(source: &SpecSource, spec: &Spec) -> Result<BodyParameters, Box<SpecError>> {
    let mut body = RigidBody::default_parameters();
    for (name, value) in &spec.parameters {
        let v = spec::finite(source, value, &format!("parameter `{}`", name.get_ref()))?;
        body.set_parameter(name.get_ref(), v).map_err(|e| {
            let (span, label) = match e {
                Error::Invalid { why: ddirac::Reason::UnknownParameter { .. }, .. } => {
                    (name.span(), "unknown parameter")
                }
                _ => (value.span(), "this value"),
            };
            let known: Vec<String> = RigidBody::default_parameters()
                .parameters()
                .iter()
                .map(|(n, v)| format!("{n} (default {v})"))
                .collect();
            source.error(Some(span), e.to_string(), label).with_help(format!(
                "the parameters of `rigid_body`: {}; the moments of inertia are positive",
                known.join(", ")
            ))
        })?;
    }
    let parameters = body.parameters().into_iter().map(|(n, v)| (n.to_owned(), v)).collect();
    Ok((body, parameters))
}

/// `initial.R`: three rows of three finite numbers, a rotation (RᵀR = I, det R = 1) to
/// [`ROTATION_TOLERANCE`].
fn attitude(source: &SpecSource, spec: &Spec) -> Result<[[f64; 3]; 3], Box<SpecError>> {
    let help = "write the attitude (body to space) as three rows: `R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]`";
    let Some(rows) = &spec.initial.get_ref().r else {
        return Err(source
            .error(Some(spec.initial.span()), "`initial.R` is missing", "no attitude in this table")
            .with_help(help));
    };
    if rows.get_ref().len() != 3 {
        let message = format!("`initial.R` has {} rows; a rotation has 3", rows.get_ref().len());
        return Err(source.error(Some(rows.span()), message, "not 3 rows").with_help(help));
    }
    let mut r = [[0.0; 3]; 3];
    for (i, row) in rows.get_ref().iter().enumerate() {
        r[i] = vector(source, row, &format!("row {} of `initial.R`", i + 1)).map_err(|e| e.with_help(help))?;
    }
    let problem = RigidProblem::new(1.0, 1, r, RigidInitial::Momentum { pi: [0.0; 3], p: vec![] });
    if let Err(e @ Error::Invalid { what: Input::InitialAttitude, .. }) = problem.validate(0) {
        return Err(source.error(Some(rows.span()), e.to_string(), "not a rotation").with_help(format!(
            "R must be orthogonal with determinant 1 to {ROTATION_TOLERANCE:e} (largest entry of |RᵀR − I| and \
             |det R − 1|): write its entries to full precision (17 significant digits), e.g. cos and sin of an angle \
             as Python's repr prints them"
        )));
    }
    Ok(r)
}

/// Three finite numbers.
fn vector(source: &SpecSource, numbers: &Numbers, what: &str) -> Result<[f64; 3], Box<SpecError>> {
    let list: &Vec<Number> = numbers.get_ref();
    if list.len() != 3 {
        let message = format!("{what} has {} entries; it takes 3", list.len());
        return Err(source.error(Some(numbers.span()), message, format!("{} entries", list.len())));
    }
    let mut out = [0.0; 3];
    for (i, value) in list.iter().enumerate() {
        out[i] = spec::finite(source, value, &format!("entry {} of {what}", i + 1))?;
    }
    Ok(out)
}

/// A library error refusing a run before its first step, pointing at the spec's value it concerns
/// (a non-invariant Lagrangian at its `symmetry`, with what to declare instead); a failure without a
/// place in the spec stays a numerical one.
pub fn refusal(source: &SpecSource, spec: &Spec, error: Error) -> crate::diagnostics::CliError {
    let help = match &error {
        Error::NotInvariantUnderRotations { .. } => Some(
            "declare the rotations the Lagrangian is invariant under: `symmetry = \"vertical\"` (about e3) or \
             `\"none\"`; a Lagrangian that depends on R only through its third row R31, R32, R33 (the vertical \
             seen from the body, Rᵀe3, as a potential of gravity −g e3 does) is invariant under rotations about e3",
        ),
        _ => None,
    };
    match locate(spec, &error) {
        Some((span, label)) => {
            let report = source.error(Some(span), error.to_string(), label);
            crate::diagnostics::CliError::from(match help {
                Some(help) => report.with_help(help),
                None => report,
            })
        }
        None => crate::diagnostics::CliError::Integration(error),
    }
}

/// Where a library error about the run concerns the spec: the span and its label.
pub fn locate(spec: &Spec, error: &Error) -> Option<(Range<usize>, &'static str)> {
    let m = &spec.method;
    let span = |v: &Option<Spanned<String>>| v.as_ref().map(|v| v.span());
    let symmetry = || match spec.system.get_ref() {
        SystemRef::Expression(table) => table.symmetry.as_ref().map(|s| s.span()),
        SystemRef::BuiltIn(_) => Some(spec.system.span()),
    };
    match error {
        Error::NotReducible { .. } => Some((m.reduced.as_ref()?.span(), "reduced by SO(3)")),
        Error::NotInvariantUnderRotations { .. } => Some((symmetry()?, "the declared symmetry")),
        Error::Undecided { .. } => Some((symmetry()?, "the declared symmetry")),
        Error::Invalid { what: Input::Argument(key), .. } => match key.as_str() {
            "method.variant" => Some((span(&m.variant)?, "this variant")),
            "method.derivatives" => Some((span(&m.derivatives)?, "this choice")),
            "method.rule" => Some((span(&m.rule)?, "this rule")),
            _ => None,
        },
        Error::Invalid { what: Input::InitialAngularMomentum, .. } => {
            Some((spec.initial.get_ref().pi.as_ref()?.span(), "this angular momentum"))
        }
        Error::Invalid { what: Input::InitialAngularVelocity, .. } => {
            Some((spec.initial.get_ref().omega.as_ref()?.span(), "this angular velocity"))
        }
        Error::Invalid { what: Input::Composition, .. } => {
            Some((m.order.as_ref().map(|o| o.span()).or(span(&m.composition)).or(span(&m.rule))?, "this method"))
        }
        _ => None,
    }
}

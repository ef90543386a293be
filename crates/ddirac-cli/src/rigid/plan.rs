//! A spec of the rigid body (`system = "rigid_body"`) checked and turned into the library's
//! [`RigidProblem`] and [`Method`]: the parameters of [`RigidBody`], the attitude `initial.R` (three
//! rows of three numbers, a rotation to [`ROTATION_TOLERANCE`]) and exactly one of `initial.Pi`,
//! `initial.Omega`. Every refusal points at the value's span.

use std::ops::Range;

use ddirac::rigid::{RigidInitial, RigidProblem, ROTATION_TOLERANCE};
use ddirac::systems::{Parameters, RigidBody};
use ddirac::{Error, Input, Method};
use toml::Spanned;

use crate::diagnostics::{SpecError, SpecSource};
use crate::spec::{self, Number, Numbers, Spans, Spec};

/// A validated rigid-body spec, ready to run.
pub struct RigidPlan {
    /// The body with its parameters set.
    pub body: RigidBody,
    /// All parameters with their effective values, in the body's order.
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

/// Validates a spec naming the rigid body.
pub fn validate(source: &SpecSource, spec: &Spec) -> Result<RigidPlan, Box<SpecError>> {
    let (body, parameters) = body(source, spec)?;
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
    let method = spec::method_of(source, spec, &[], &mut Spans::default())?;
    let (step, steps) = spec::grid(source, &spec.time)?;
    let initial = spec.initial.get_ref();
    for (value, name) in [(initial.q.as_ref().map(|v| v.span()), "q"), (initial.p.as_ref().map(|v| v.span()), "p")]
        .into_iter()
        .chain([(initial.v.as_ref().map(|v| v.span()), "v")])
    {
        if let Some(span) = value {
            return Err(source
                .error(Some(span), format!("a rigid body takes no `initial.{name}`"), "not a key of the rigid body")
                .with_help(
                    "the rigid body's initial data are the attitude `R` (3 rows of 3 numbers, body to space) and \
                     one of `Pi` (the body angular momentum) and `Omega` (the body angular velocity)",
                ));
        }
    }
    let r0 = attitude(source, spec)?;
    let initial = match (&initial.pi, &initial.omega) {
        (Some(pi), None) => RigidInitial::Momentum { pi: vector(source, pi, "initial.Pi")?, p: vec![] },
        (None, Some(omega)) => RigidInitial::Velocity { omega: vector(source, omega, "initial.Omega")?, v: vec![] },
        (Some(pi), Some(omega)) => {
            return Err(source
                .error_with(
                    "`initial.Pi` and `initial.Omega` are both given",
                    vec![
                        miette::LabeledSpan::new_with_span(Some("the angular momentum".into()), pi.span()),
                        miette::LabeledSpan::new_with_span(Some("the angular velocity".into()), omega.span()),
                    ],
                )
                .with_help("give one of them: the other follows from it (Π = I Ω)"))
        }
        (None, None) => {
            return Err(source
                .error(Some(spec.initial.span()), "neither `initial.Pi` nor `initial.Omega` is given", "in this table")
                .with_help("give the body angular momentum `Pi = [..]` or the body angular velocity `Omega = [..]`"))
        }
    };
    let problem = RigidProblem::new(step, steps, r0, initial);
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
    Ok(RigidPlan { body, parameters, problem, method, every, directory })
}

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

/// Where a library error about the run concerns the spec: the span and its label.
pub fn locate(spec: &Spec, error: &Error) -> Option<(Range<usize>, &'static str)> {
    let m = &spec.method;
    let span = |v: &Option<Spanned<String>>| v.as_ref().map(|v| v.span());
    match error {
        Error::NotReducible { .. } => Some((m.reduced.as_ref()?.span(), "reduced by SO(3)")),
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

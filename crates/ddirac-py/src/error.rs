//! The exceptions: `ddirac.Error` and its subclasses, from the engine's typed errors.
//!
//! ```text
//! Error                  every error of the package
//! ├── SpecError          a spec file or its overrides (the command line's diagnostic as the message)
//! ├── ExpressionError    a Lagrangian, definition or exact solution in text: `origin`, `text`, `span`,
//! │                      `help` (what the source may use, as `ddirac run` says it)
//! ├── InvarianceError    a reduced run of a Lagrangian not invariant under its group, or undecided
//! └── ConvergenceError   a failed step: `step`, `t`, `h`, `residual` (Newton's method, a non-finite state)
//! ```

use ddirac::expression::{ExpressionError as Expression, Origin};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(ddirac, Error, PyException, "An error of ddirac: its message names the argument and the cause.");
create_exception!(
    ddirac,
    SpecError,
    Error,
    "A spec file or its overrides are wrong; the message is the command line's diagnostic."
);
create_exception!(
    ddirac,
    ExpressionError,
    Error,
    "A text Lagrangian, definition or exact solution is wrong: `origin` names it, `text` is its source, \
     `span` the (start, end) byte range of the fault, when there is one, and `help` what the source may \
     use (the names of the coordinates, velocities, parameters and definitions), when that is the fault; \
     the message ends with the help."
);
create_exception!(
    ddirac,
    InvarianceError,
    Error,
    "A reduced run of a Lagrangian that is not invariant under translation of its group coordinates, or \
     whose invariance could not be tested."
);
create_exception!(
    ddirac,
    ConvergenceError,
    Error,
    "A step failed: Newton's method did not converge or the state became non-finite; `step` and `t` say \
     where, `h` with which step, `residual` how far (None for a non-finite state)."
);

/// A message as `ddirac.Error`.
pub fn raise(error: impl std::fmt::Display) -> PyErr {
    Error::new_err(error.to_string())
}

/// An engine error as the exception of its kind.
pub fn engine(error: ddirac::Error) -> PyErr {
    use ddirac::Error as E;
    let message = error.to_string();
    Python::attach(|py| match error {
        E::Newton { step, t, h, residual, .. } => {
            let err = ConvergenceError::new_err(message);
            let value = err.value(py);
            let _ = (value.setattr("step", step), value.setattr("t", t), value.setattr("h", h));
            let _ = value.setattr("residual", residual);
            err
        }
        E::Diverged { step, t, h, .. } => {
            let err = ConvergenceError::new_err(message);
            let value = err.value(py);
            let _ = (value.setattr("step", step), value.setattr("t", t), value.setattr("h", h));
            let _ = value.setattr("residual", py.None());
            err
        }
        E::NotInvariant { .. }
        | E::NotInvariantUnderRotations { .. }
        | E::Undecided { hypothesis: ddirac::Hypothesis::Invariance, .. } => InvarianceError::new_err(message),
        _ => Error::new_err(message),
    })
}

/// The names a text system declares, for the help of its errors.
pub struct Declared<'a> {
    /// The coordinates, in order.
    pub coordinates: &'a [String],
    /// The parameters, in order.
    pub parameters: &'a [String],
    /// The definitions, in order.
    pub definitions: &'a [String],
    /// Whether the system is rigid: its Lagrangian also uses `Omega1` … `Omega3` and `R11` … `R33`.
    pub rigid: bool,
}

/// Names listed in a help, at most (a generated system may have thousands of definitions).
const LONG_LIST: usize = 12;

/// What the source of `error` may use, when an unknown name or coordinate is the fault: the command
/// line's help for a `[system]` table, with the constants given as `parameters={...}`.
fn help(error: &Expression, declared: &Declared<'_>) -> Option<String> {
    let list = |names: Vec<String>| match names.len() {
        0 => "none".to_owned(),
        n if n > LONG_LIST => format!("{}, … and {} more", names[..LONG_LIST].join(", "), n - LONG_LIST),
        _ => names.join(", "),
    };
    let parameters = || list(declared.parameters.to_vec());
    match error {
        Expression::UnknownName { origin: Origin::ExactSolution(_), .. } => {
            Some(format!("an exact solution may use `t` and the parameters ({})", parameters()))
        }
        Expression::UnknownName { origin: Origin::Lagrangian | Origin::Definition(_), .. } if declared.rigid => {
            Some(format!(
                "the Lagrangian and the definitions of a rigid system may use the body angular velocity (Omega1, \
                 Omega2, Omega3), the attitude's entries (R11, R12, …, R33), the shape coordinates ({}), their \
                 velocities ({}), the parameters ({}) and the definitions ({}); give constants in \
                 `parameters={{...}}`",
                list(declared.coordinates.to_vec()),
                list(declared.coordinates.iter().map(|c| format!("{c}_dot")).collect()),
                parameters(),
                list(declared.definitions.to_vec()),
            ))
        }
        Expression::UnknownName { origin: Origin::Lagrangian | Origin::Definition(_), .. } => Some(format!(
            "the Lagrangian and the definitions may use the coordinates ({}), their velocities ({}), the \
             parameters ({}) and the definitions ({}); give constants in `parameters={{...}}`",
            list(declared.coordinates.to_vec()),
            list(declared.coordinates.iter().map(|c| format!("{c}_dot")).collect()),
            parameters(),
            list(declared.definitions.to_vec()),
        )),
        Expression::UnknownCoordinate { .. } => {
            Some(format!("`exact` gives expressions for coordinates: {}", list(declared.coordinates.to_vec())))
        }
        Expression::Cycle { .. } => Some("a definition may not depend on itself, directly or not".into()),
        _ => None,
    }
}

/// A text system's error as `ddirac.ExpressionError` with its origin, text, span and help (also at the
/// end of the message, as `help: ...`).
pub fn expression(error: Expression, sources: &[(String, String)], declared: &Declared<'_>) -> PyErr {
    let origin = error.origin().cloned();
    let text = origin.as_ref().and_then(|o| {
        let name = match o {
            Origin::Lagrangian => "lagrangian".to_owned(),
            Origin::Definition(n) => format!("definition:{n}"),
            Origin::ExactSolution(n) => format!("exact:{n}"),
            _ => return None,
        };
        sources.iter().find(|(k, _)| *k == name).map(|(_, v)| v.clone())
    });
    let span = error.span().map(|s| (s.start, s.end));
    let help = help(&error, declared);
    let message = match &help {
        Some(help) => format!("{error}\n  help: {help}"),
        None => error.to_string(),
    };
    let err = ExpressionError::new_err(message);
    Python::attach(|py| {
        let value = err.value(py);
        let _ = value.setattr("origin", origin.map(|o| o.to_string()));
        let _ = value.setattr("text", text);
        let _ = value.setattr("span", span);
        let _ = value.setattr("help", help);
    });
    err
}

//! The exceptions: `ddirac.Error` and its subclasses, from the engine's typed errors.
//!
//! ```text
//! Error                  every error of the package
//! ├── SpecError          a spec file or its overrides (the command line's diagnostic as the message)
//! ├── ExpressionError    a Lagrangian, definition or exact solution in text: `origin`, `text`, `span`
//! ├── InvarianceError    a reduced run of a Lagrangian not invariant under its group, or undecided
//! └── ConvergenceError   a failed step: `step`, `t`, `residual` (Newton's method, a non-finite state)
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
    "A text Lagrangian, definition or exact solution is wrong: `origin` names it, `text` is its source \
     and `span` the (start, end) byte range of the fault, when there is one."
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
     where, `residual` how far (None for a non-finite state)."
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
        E::Newton { step, t, residual, .. } => {
            let err = ConvergenceError::new_err(message);
            let value = err.value(py);
            let _ = (value.setattr("step", step), value.setattr("t", t), value.setattr("residual", residual));
            err
        }
        E::Diverged { step, t, .. } => {
            let err = ConvergenceError::new_err(message);
            let value = err.value(py);
            let _ = (value.setattr("step", step), value.setattr("t", t), value.setattr("residual", py.None()));
            err
        }
        E::NotInvariant { .. } | E::Undecided { hypothesis: ddirac::Hypothesis::Invariance, .. } => {
            InvarianceError::new_err(message)
        }
        _ => Error::new_err(message),
    })
}

/// A text system's error as `ddirac.ExpressionError` with its origin, text and span.
pub fn expression(error: Expression, sources: &[(String, String)]) -> PyErr {
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
    let err = ExpressionError::new_err(error.to_string());
    Python::attach(|py| {
        let value = err.value(py);
        let _ = value.setattr("origin", origin.map(|o| o.to_string()));
        let _ = value.setattr("text", text);
        let _ = value.setattr("span", span);
    });
    err
}

//! `ddirac.Error`: the base class of every error the package raises, with the engine's message.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::PyErr;

create_exception!(
    ddirac,
    Error,
    PyException,
    "An error of ddirac: bad input (the message names the argument and the cause), a system that does \
     not have the symmetry it is reduced by, or a failed step (Newton's method, a non-finite state)."
);

/// An engine error as `ddirac.Error`.
pub fn raise(error: impl std::fmt::Display) -> PyErr {
    Error::new_err(error.to_string())
}

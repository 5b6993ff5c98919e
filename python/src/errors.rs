//! Rust errors as Python exceptions, with the CLI's one-line messages.

use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};

/// `vivae_lab::Error` as a Python exception: a file that cannot be read or
/// written is an `OSError`, any other bad input a `ValueError`, the rest a
/// `RuntimeError`; the message is the CLI's, on one line.
pub fn lab(e: vivae_lab::Error) -> PyErr {
    let message = vivae_lab::io::one_line(&e.to_string());
    match e {
        vivae_lab::Error::Read { .. } | vivae_lab::Error::Io { .. } => PyOSError::new_err(message),
        e if e.is_bad_input() => PyValueError::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

/// Any other library error (NEAT, simulator, substrate) as a `ValueError`.
pub fn value(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(vivae_lab::io::one_line(&e.to_string()))
}

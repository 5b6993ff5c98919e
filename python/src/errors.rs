//! Rust errors as Python exceptions, with the CLI's one-line messages.

use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use vivae_lab::run::prepare::Spelling;

/// How Python's keyword arguments are named in the library's refusals.
pub const SPELLING: Spelling = Spelling {
    origin: "arguments",
    key: |k| format!("{k}="),
    on: |k| format!("{k}=True"),
};

/// `vivae_lab::Error` as a Python exception: a file that cannot be read or
/// written is an `OSError` (one that is not UTF-8 text a `ValueError`), any other bad input a `ValueError`, the rest a
/// `RuntimeError`; the message is the CLI's, on one line, with settings
/// spelled as keywords (`out=`, `force=True`).
pub fn lab(e: vivae_lab::Error) -> PyErr {
    let message = vivae_lab::io::one_line(&SPELLING.error(&e));
    match e {
        // Read, but not text: the content is wrong, not the file system.
        vivae_lab::Error::Read { reason, .. } if reason.contains("not UTF-8") => {
            PyValueError::new_err(message)
        }
        vivae_lab::Error::Read { .. } | vivae_lab::Error::Io { .. } => PyOSError::new_err(message),
        e if e.is_bad_input() => PyValueError::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

/// Any other library error (NEAT, simulator, substrate) as a `ValueError`.
pub fn value(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(vivae_lab::io::one_line(&e.to_string()))
}

/// The loader's warnings about `scenario` (unknown labels, …) as Python
/// `UserWarning`s, which the CLI prints on stderr.
pub fn warn_scenario(py: pyo3::Python<'_>, scenario: &vivae_sim::Scenario) -> pyo3::PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    for w in &scenario.warnings {
        let message = std::ffi::CString::new(format!("{}: {w}", scenario.source))
            .unwrap_or_else(|_| c"scenario warning".to_owned());
        PyErr::warn(py, &category, &message, 1)?;
    }
    Ok(())
}

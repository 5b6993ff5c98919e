//! The tasks' own classes and functions in the module: a task with any is
//! one folder here and one line in [`register`]. Everything else the module
//! does for a task (evolving, resuming, reporting a run) it asks the task's
//! entry in `vivae_lab` or its program-side tools in `vivae`; nothing
//! outside a task's folder matches on which task it is.

use pyo3::PyClass;
use pyo3::prelude::*;
use vivae_lab::config::Config;

use crate::errors;

mod classic;
mod driving;
mod gym;
mod predator_prey;

/// Adds every task's own classes and functions to the module `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    classic::register(m)?;
    driving::register(m)?;
    gym::register(m)?;
    predator_prey::register(m)
}

/// A task's resolved config read back from its TOML (its class's
/// `from_config_toml`, how a pickled task is rebuilt in another process).
pub(crate) fn config_of_toml(text: &str) -> PyResult<Config> {
    Config::from_toml(text).map_err(|e| errors::value(format!("config: {e}")))
}

/// `__reduce__` of a task pickled by its resolved `config`: its class's
/// `from_config_toml` and the config's TOML.
pub(crate) fn reduce_to_config<'py, T: PyClass>(
    slf: &Bound<'py, T>,
    config: &Config,
) -> PyResult<(Bound<'py, PyAny>, (String,))> {
    let class = slf.as_any().get_type();
    Ok((class.getattr("from_config_toml")?, (config.to_toml(),)))
}

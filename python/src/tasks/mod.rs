//! The tasks' own classes and functions in the module: a task with any is
//! one folder here and one line in [`register`]. Everything else the module
//! does for a task (evolving, resuming, reporting a run) it asks the task's
//! entry in `vivae_lab` or its program-side tools in `vivae`; nothing
//! outside a task's folder matches on which task it is.

use pyo3::prelude::*;

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

//! The driving experiment's own classes and functions: its simulator
//! stepped for the Gymnasium environments ([`sim::DriveCore`]), its task
//! ([`task::DriveTask`]), an evolved controller ([`controller::Controller`])
//! and a champion's replay.

use pyo3::prelude::*;

mod controller;
mod replay;
mod sim;
mod task;

/// Adds the driving experiment's classes and functions to the module `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<sim::DriveCore>()?;
    m.add_class::<task::DriveTask>()?;
    m.add_class::<controller::Controller>()?;
    m.add_function(wrap_pyfunction!(replay::replay, m)?)
}

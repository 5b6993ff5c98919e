//! The classic-control tasks' steps, for a comparison with Gymnasium's: an
//! episode stepped from a given state under given actions, and the portable
//! sin and cos those steps use.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Adds the classic-control functions to the module `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(classic_episode, m)?)?;
    m.add_function(wrap_pyfunction!(portable_math, m)?)
}

/// The episode of classic-control task `task` from `state` (as Gymnasium's
/// `env.unwrapped.state` holds it) under `actions` (Gymnasium's, a discrete
/// one as its index), until it terminates, is truncated or the actions run
/// out: one dict a step (`state`, `observation`, `reward`, `terminated`, `truncated`).
#[pyfunction]
fn classic_episode<'py>(
    py: Python<'py>,
    task: &str,
    state: Vec<f64>,
    actions: Vec<f64>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let steps = vivae_lab::tasks::gymnasium::episode_of(task, &state, &actions)
        .map_err(PyValueError::new_err)?;
    steps
        .into_iter()
        .map(|s| {
            let d = PyDict::new(py);
            d.set_item("state", s.state)?;
            d.set_item("observation", s.observation)?;
            d.set_item("reward", s.reward)?;
            d.set_item("terminated", s.terminated)?;
            d.set_item("truncated", s.truncated)?;
            Ok(d)
        })
        .collect()
}

/// vivae's portable `sin` or `cos` (`function`) of `x`: the bits its tasks compute.
#[pyfunction]
fn portable_math(function: &str, x: f64) -> PyResult<f64> {
    match function {
        "sin" => Ok(vivae_neat::math::sin(x)),
        "cos" => Ok(vivae_neat::math::cos(x)),
        _ => Err(PyValueError::new_err(format!(
            "function {function:?}: one of \"sin\", \"cos\""
        ))),
    }
}

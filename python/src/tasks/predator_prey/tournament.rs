//! `vivae.tournament`: one predator–prey run's champions against another's,
//! as `vivae tournament RUN_A RUN_B` plays them.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::tasks::predator_prey::tournament as games;

use crate::errors;

/// Plays run `a`'s champions against run `b`'s (finished predator-prey
/// runs; `b` may be `a`), as `vivae tournament` does: A's hunters against
/// B's prey, then B's hunters against A's prey, each side as its champion
/// and as its hall of fame. Returns one dict per row (`hunters_run`,
/// `prey_run`, `hunters`, `prey`, `games`, `catches`, `catch_rate`,
/// `mean_hunter_fitness`, `mean_catch_step` (None without a catch)); with
/// `csv` also writes them there. `threads` (None or 0 = one per core) does
/// not change the results.
#[pyfunction]
#[pyo3(signature = (a, b, threads=None, csv=None))]
pub fn tournament<'py>(
    py: Python<'py>,
    a: PathBuf,
    b: PathBuf,
    #[pyo3(from_py_with = crate::args::opt_threads)] threads: Option<usize>,
    csv: Option<PathBuf>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let rows = py
        .detach(|| games::tournament(&a, &b, threads.unwrap_or(0)))
        .map_err(errors::lab)?;
    if let Some(path) = csv {
        vivae_lab::io::write_atomic(&path, games::csv(&rows).as_bytes()).map_err(errors::lab)?;
    }
    rows.iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("hunters_run", &r.hunters_run)?;
            d.set_item("prey_run", &r.prey_run)?;
            d.set_item("hunters", r.hunters)?;
            d.set_item("prey", r.prey)?;
            d.set_item("games", r.games)?;
            d.set_item("catches", r.catches)?;
            d.set_item("catch_rate", r.catch_rate)?;
            d.set_item("mean_hunter_fitness", r.mean_hunter_fitness)?;
            d.set_item("mean_catch_step", r.mean_catch_step)?;
            Ok(d)
        })
        .collect()
}

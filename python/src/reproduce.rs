//! `vivae.reproduce(name, ...)`: a replication pack (`vivae reproduce NAME`)
//! run from Python, its table returned as data.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::reproduce::{Options, run};

use crate::errors;

/// Runs replication pack `name` (`reproduce_packs()` lists them) as `vivae
/// reproduce` does; returns the table as a dict: `title`, `columns`, `rows`
/// (lists of cells), `notes` and `markdown` (the text the CLI prints).
/// `progress=True` prints a line per finished run to stderr. `methods` picks
/// some of a maze pack's methods (`novelty`, `neat`, `map-elites`);
/// `journal` is a file of finished runs that a call again skips (none: every
/// run is run).
#[pyfunction]
#[pyo3(signature = (name, runs=None, seed=1, quick=false, evaluations=None, threads=0, progress=false, methods=None, journal=None))]
#[allow(clippy::too_many_arguments)]
pub fn reproduce<'py>(
    py: Python<'py>,
    name: &str,
    #[pyo3(from_py_with = crate::args::runs)] runs: Option<usize>,
    #[pyo3(from_py_with = crate::args::seed)] seed: u64,
    quick: bool,
    #[pyo3(from_py_with = crate::args::evaluations)] evaluations: Option<u64>,
    #[pyo3(from_py_with = crate::args::threads)] threads: usize,
    progress: bool,
    methods: Option<Vec<String>>,
    journal: Option<std::path::PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let options = Options {
        runs,
        seed,
        quick,
        evaluations,
        threads,
        methods: methods.unwrap_or_default(),
        journal,
    };
    let table = py
        .detach(|| {
            run(name, &options, &mut |line| {
                if progress {
                    eprintln!("{line}");
                }
            })
        })
        .map_err(errors::lab)?;
    let d = PyDict::new(py);
    d.set_item("title", &table.title)?;
    d.set_item("columns", &table.columns)?;
    d.set_item("rows", &table.rows)?;
    d.set_item("notes", &table.notes)?;
    d.set_item("markdown", table.markdown())?;
    Ok(d)
}

/// The replication packs: (name, description).
#[pyfunction]
pub fn reproduce_packs() -> Vec<(String, String)> {
    vivae_lab::reproduce::packs()
        .map(|p| (p.name.to_string(), p.what.to_string()))
        .collect()
}

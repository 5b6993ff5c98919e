//! MAP-Elites from Python, driven ask/tell as `Population` is.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::strategies::{self as st, Cells};

use crate::asktell::to_python;
use crate::evo::{Genome, merged, neat_setup};
use crate::{args, errors};

/// MAP-Elites over NEAT genomes (Mouret & Clune 2015), on a grid or a CVT.
#[pyclass(module = "vivae._vivae")]
pub struct MapElites {
    inner: st::MapElites,
    recurrent: bool,
}

ask_tell!(MapElites, "MapElites", "MAP-Elites", &["spec"], {
    /// An empty archive over the behaviour box `lower`..`upper`, cut into a
    /// grid of `bins` per dimension, or, with `cvt_cells`, into that many
    /// CVT cells (`cvt_samples` points, `cvt_iterations` of Lloyd's
    /// algorithm, seeded with `seed`). `map` overrides `batch_size`,
    /// `crossover_probability` and `qd_offset`; `params` NEAT's parameters.
    #[new]
    #[pyo3(signature = (inputs, outputs, *, lower, upper, bins=None, cvt_cells=None, cvt_samples=100_000, cvt_iterations=10, seed=1, preset="plain", recurrent=false, params=None, map=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        #[pyo3(from_py_with = args::inputs)] inputs: usize,
        #[pyo3(from_py_with = args::outputs)] outputs: usize,
        #[pyo3(from_py_with = args::lower)] lower: Vec<f64>,
        #[pyo3(from_py_with = args::upper)] upper: Vec<f64>,
        #[pyo3(from_py_with = args::bins)] bins: Option<Vec<usize>>,
        #[pyo3(from_py_with = args::cvt_cells)] cvt_cells: Option<usize>,
        #[pyo3(from_py_with = args::cvt_samples)] cvt_samples: usize,
        #[pyo3(from_py_with = args::cvt_iterations)] cvt_iterations: usize,
        #[pyo3(from_py_with = args::seed)] seed: u64,
        preset: &str,
        recurrent: bool,
        params: Option<&Bound<'_, PyDict>>,
        map: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<MapElites> {
        let cells = match (bins, cvt_cells) {
            (Some(bins), None) => Cells::grid(lower, upper, bins),
            (None, Some(n)) => Cells::cvt(&lower, &upper, n, cvt_samples, cvt_iterations, seed),
            _ => return Err(PyValueError::new_err("give either bins= or cvt_cells=")),
        }
        .map_err(errors::value)?;
        let (params, spec) = neat_setup(inputs, outputs, preset, recurrent, params, None)?;
        let map = merged(st::MapElitesParams::default(), map, "map")?;
        let inner = st::MapElites::new(params, spec, map, cells, seed).map_err(errors::value)?;
        Ok(MapElites { inner, recurrent })
    }

    /// Number of cells.
    #[getter]
    fn cells(&self) -> usize {
        self.inner.cells().len()
    }

    /// The cell a behaviour falls in.
    fn cell_of(
        &self,
        #[pyo3(from_py_with = args::behaviour)] behaviour: Vec<f64>,
    ) -> PyResult<usize> {
        let dims = self.inner.cells().dims();
        if behaviour.len() != dims {
            let given = behaviour.len();
            return Err(PyValueError::new_err(format!(
                "a behaviour of {given} coordinates; the cells have {dims}"
            )));
        }
        Ok(self.inner.cells().cell_of(&behaviour))
    }

    /// Every elite in cell order, as dicts: cell, genome, fitness, behaviour, generation.
    fn elites<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        (self.inner.elites())
            .map(|(cell, e)| {
                let d = PyDict::new(py);
                d.set_item("cell", cell)?;
                let genome = Genome::new(e.genome.clone(), self.recurrent);
                d.set_item("genome", genome)?;
                d.set_item("fitness", e.fitness)?;
                d.set_item("behaviour", e.behaviour.clone())?;
                d.set_item("generation", e.generation)?;
                Ok(d)
            })
            .collect()
    }

    /// Coverage, QD-score, filled cells and best fitness of the archive, as a dict.
    fn archive_stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.archive_stats())
    }
});

//! The search strategies beyond NEAT from Python, driven ask/tell as
//! `Population` is: novelty search, MAP-Elites and NSGA-II over NEAT genomes.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::strategies::{self as st, Cells, Measure, Objective};

use crate::asktell::to_python;
use crate::errors;
use crate::evo::{Genome, merged, neat_setup};

/// Novelty search over a NEAT population (Lehman & Stanley 2011).
#[pyclass(module = "vivae._vivae")]
pub struct NoveltySearch {
    inner: st::NoveltySearch,
    recurrent: bool,
}

ask_tell!(
    NoveltySearch,
    "NoveltySearch",
    "novelty search",
    &["population", "spec"],
    {
        /// A novelty search breeding a NEAT population made as `Population`
        /// makes it; `novelty` overrides its settings by name (`k`,
        /// `threshold`, `threshold_floor`, `lower_after`, `lower_factor`,
        /// `raise_above`, `raise_factor`, `fitness_weight`).
        #[new]
        #[pyo3(signature = (inputs, outputs, *, seed=1, size=None, preset="plain", recurrent=false, params=None, novelty=None))]
        #[allow(clippy::too_many_arguments)]
        fn new(
            inputs: usize,
            outputs: usize,
            seed: u64,
            size: Option<usize>,
            preset: &str,
            recurrent: bool,
            params: Option<&Bound<'_, PyDict>>,
            novelty: Option<&Bound<'_, PyDict>>,
        ) -> PyResult<NoveltySearch> {
            let (params, spec) = neat_setup(inputs, outputs, preset, recurrent, params, size)?;
            let population =
                vivae_neat::Population::new(params, spec, seed).map_err(errors::value)?;
            let novelty = merged(st::NoveltyParams::default(), novelty, "novelty")?;
            let inner = st::NoveltySearch::new(population, novelty).map_err(errors::value)?;
            Ok(NoveltySearch { inner, recurrent })
        }

        /// The archived behaviours, oldest first.
        #[getter]
        fn archive(&self) -> Vec<Vec<f64>> {
            self.inner.archive().map(<[f64]>::to_vec).collect()
        }

        /// The archive threshold ρ_min now.
        #[getter]
        fn threshold(&self) -> f64 {
            self.inner.threshold()
        }

        /// The novelty of each genome of the batch just told (empty before `tell`).
        #[getter]
        fn novelty(&self) -> Vec<f64> {
            self.inner.novelty().to_vec()
        }
    }
);

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
        inputs: usize,
        outputs: usize,
        lower: Vec<f64>,
        upper: Vec<f64>,
        bins: Option<Vec<usize>>,
        cvt_cells: Option<usize>,
        cvt_samples: usize,
        cvt_iterations: usize,
        seed: u64,
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
    fn cell_of(&self, behaviour: Vec<f64>) -> PyResult<usize> {
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

/// NSGA-II (Deb et al. 2002) over NEAT genomes, on fitness and metrics.
#[pyclass(module = "vivae._vivae")]
pub struct Nsga2 {
    inner: st::Nsga2,
    recurrent: bool,
}

/// An objective from Python: `"fitness"` or a metric's index, and `"max"` or `"min"`.
fn objective(measure: &Bound<'_, PyAny>, direction: &str) -> PyResult<Objective> {
    let measure = if let Ok(i) = measure.extract::<usize>() {
        Measure::Metric(i)
    } else if measure.extract::<String>().is_ok_and(|s| s == "fitness") {
        Measure::Fitness
    } else {
        return Err(PyValueError::new_err(format!(
            "objective {measure}: expected \"fitness\" or a metric's index"
        )));
    };
    let maximise = match direction {
        "max" => true,
        "min" => false,
        other => {
            return Err(PyValueError::new_err(format!(
                "objective direction {other:?}: expected \"max\" or \"min\""
            )));
        }
    };
    Ok(Objective { measure, maximise })
}

ask_tell!(Nsga2, "Nsga2", "NSGA-II", &["spec"], {
    /// NSGA-II with `size` parents (and children per generation) over
    /// `objectives`, each (`"fitness"` or a metric's index, `"max"` or
    /// `"min"`), e.g. `[("fitness", "max"), (0, "min")]`.
    #[new]
    #[pyo3(signature = (inputs, outputs, *, objectives, size=100, crossover_probability=0.5, seed=1, preset="plain", recurrent=false, params=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        inputs: usize,
        outputs: usize,
        objectives: Vec<(Bound<'_, PyAny>, String)>,
        size: usize,
        crossover_probability: f64,
        seed: u64,
        preset: &str,
        recurrent: bool,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Nsga2> {
        let objectives = (objectives.iter())
            .map(|(m, d)| objective(m, d))
            .collect::<PyResult<Vec<_>>>()?;
        let nsga = st::Nsga2Params {
            population_size: size,
            objectives,
            crossover_probability,
        };
        let (params, spec) = neat_setup(inputs, outputs, preset, recurrent, params, None)?;
        let inner = st::Nsga2::new(params, spec, nsga, seed).map_err(errors::value)?;
        Ok(Nsga2 { inner, recurrent })
    }

    /// The non-dominated genomes among the parents and the batch just told:
    /// (genome, objective values as measured, fitness), parents first.
    fn pareto_front(&self) -> Vec<(Genome, Vec<f64>, f64)> {
        (self.inner.pareto_front().into_iter())
            .map(|(g, objectives, fitness)| {
                let genome = Genome::new(g.clone(), self.recurrent);
                (genome, objectives, fitness)
            })
            .collect()
    }
});

/// Adds the strategies' classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NoveltySearch>()?;
    m.add_class::<MapElites>()?;
    m.add_class::<Nsga2>()
}

//! NSGA-II from Python, driven ask/tell as `Population` is.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::strategies::{self as st, Measure, Objective};

use crate::evo::{Genome, neat_setup};
use crate::{args, errors};

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
        #[pyo3(from_py_with = args::inputs)] inputs: usize,
        #[pyo3(from_py_with = args::outputs)] outputs: usize,
        objectives: Vec<(Bound<'_, PyAny>, String)>,
        #[pyo3(from_py_with = args::size_given)] size: usize,
        crossover_probability: f64,
        #[pyo3(from_py_with = args::seed)] seed: u64,
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

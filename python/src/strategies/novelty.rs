//! Novelty search from Python, driven ask/tell as `Population` is.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::strategies as st;

use crate::evo::{Genome, merged, neat_setup};
use crate::{args, errors};

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
            #[pyo3(from_py_with = args::inputs)] inputs: usize,
            #[pyo3(from_py_with = args::outputs)] outputs: usize,
            #[pyo3(from_py_with = args::seed)] seed: u64,
            #[pyo3(from_py_with = args::size)] size: Option<usize>,
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

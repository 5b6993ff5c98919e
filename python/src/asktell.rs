//! What every ask/tell class (`Population` and the strategies) shares: the
//! methods, by the [`ask_tell!`] macro, and the helpers they call.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use serde::de::DeserializeOwned;
use vivae_neat::driver::{Evaluation, Strategy};

use crate::errors;
use crate::evo::Genome;

/// An ask/tell class's methods: its own (`$own`) and the ask/tell methods
/// every ask/tell class shares, over its `inner` strategy (one `#[pymethods]`
/// block per class, as pyo3 wants).
macro_rules! ask_tell {
    ($class:ident, $name:literal, $what:literal, $spec:expr, { $($own:tt)* }) => {
        #[pymethods]
        impl $class {
            $($own)*

            /// The genomes to evaluate next (breeding the next batch if the last one was told).
            fn ask(&mut self) -> Vec<Genome> {
                $crate::asktell::ask(&mut self.inner, self.recurrent)
            }

            /// Tells the evaluation of every genome last asked, in order: its
            /// fitness (non-finite counts as 0) and, one list per genome,
            /// its behaviour descriptor and its metrics.
            #[pyo3(signature = (fitnesses, behaviours=None, metrics=None))]
            fn tell(
                &mut self,
                #[pyo3(from_py_with = $crate::args::fitnesses)] fitnesses: Vec<f64>,
                #[pyo3(from_py_with = $crate::args::behaviours)] behaviours: Option<Vec<Vec<f64>>>,
                #[pyo3(from_py_with = $crate::args::metrics)] metrics: Option<Vec<Vec<f64>>>,
            ) -> PyResult<()> {
                if vivae_neat::driver::Strategy::champion(&self.inner).is_some() {
                    // A second tell would replace the fitnesses but not `best_ever`.
                    return Err(pyo3::exceptions::PyValueError::new_err(
                        "tell: this batch was already told; ask() for the next one",
                    ));
                }
                let told = $crate::asktell::evaluations(fitnesses, behaviours, metrics)?;
                vivae_neat::driver::Strategy::tell(&mut self.inner, &told)
                    .map_err($crate::errors::value)
            }

            /// The generation of the genomes last asked.
            #[getter]
            fn generation(&self) -> u32 {
                vivae_neat::driver::Strategy::generation(&self.inner)
            }

            /// (genome, fitness, generation) of the best genome told so far, or None.
            #[getter]
            fn best_ever(&self) -> Option<(Genome, f64, u32)> {
                $crate::asktell::best_ever(&self.inner, self.recurrent)
            }

            /// (genome, fitness) of the best genome of the batch last told
            /// (its generation's champion), or None before `tell`.
            #[getter]
            fn champion(&self) -> Option<($crate::evo::Genome, f64)> {
                vivae_neat::driver::Strategy::champion(&self.inner)
                    .map(|(g, f)| ($crate::evo::Genome::new(g.clone(), self.recurrent), f))
            }

            /// Statistics of the current batch as a dict.
            fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                $crate::asktell::to_python(py, &vivae_neat::driver::Strategy::stats(&self.inner))
            }

            /// The whole state as JSON (restoring it continues bit for bit).
            fn to_json(&self) -> PyResult<String> {
                serde_json::to_string(&self.inner).map_err($crate::errors::value)
            }

            /// A state from `to_json`'s JSON (validated as it is read).
            #[staticmethod]
            fn from_json(text: &str) -> PyResult<$class> {
                let recurrent = $crate::asktell::recurrent_in(text, $spec)?;
                let inner = $crate::asktell::restore(text, $what)?;
                Ok($class { inner, recurrent })
            }

            /// Pickles by JSON: `from_json(to_json())` continues bit for bit.
            fn __reduce__<'py>(
                slf: &Bound<'py, Self>,
            ) -> PyResult<(Bound<'py, PyAny>, (String,))> {
                let json = serde_json::to_string(&slf.borrow().inner).map_err($crate::errors::value)?;
                Ok((slf.get_type().getattr("from_json")?, (json,)))
            }

            fn __repr__(&self) -> String {
                format!(
                    "{}(generation={})",
                    $name,
                    vivae_neat::driver::Strategy::generation(&self.inner)
                )
            }
        }
    };
}

/// The genomes `strategy` asks to have evaluated, as Python genomes.
pub fn ask(strategy: &mut impl Strategy, recurrent: bool) -> Vec<Genome> {
    (strategy.ask().genomes.iter())
        .map(|g| Genome::new(g.clone(), recurrent))
        .collect()
}

/// One evaluation per fitness, with its behaviour and metrics when given
/// (each list, when given, must have one entry per fitness).
pub fn evaluations(
    fitnesses: Vec<f64>,
    behaviours: Option<Vec<Vec<f64>>>,
    metrics: Option<Vec<Vec<f64>>>,
) -> PyResult<Vec<Evaluation>> {
    let n = fitnesses.len();
    let per_genome = |given: Option<Vec<Vec<f64>>>, what: &str| match given {
        Some(v) if v.len() != n => Err(PyValueError::new_err(format!(
            "{} {what} for {n} fitnesses",
            v.len()
        ))),
        Some(v) => Ok(v),
        None => Ok(vec![Vec::new(); n]),
    };
    let behaviours = per_genome(behaviours, "behaviours")?;
    let metrics = per_genome(metrics, "metrics")?;
    Ok(fitnesses
        .into_iter()
        .zip(behaviours)
        .zip(metrics)
        .map(|((fitness, behaviour), metrics)| Evaluation {
            fitness,
            metrics,
            behaviour,
        })
        .collect())
}

/// (genome, fitness, generation) of the best genome `strategy` was told of.
pub fn best_ever(strategy: &impl Strategy, recurrent: bool) -> Option<(Genome, f64, u32)> {
    strategy.best_ever().map(|b| {
        let genome = Genome::new(b.genome.clone(), recurrent);
        (genome, b.fitness, b.generation)
    })
}

/// `value` as the Python object its JSON reads as (dicts, lists, numbers).
pub fn to_python<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(errors::value)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Whether the genome shape in a strategy's JSON allows recurrent links.
pub fn recurrent_in(json: &str, path: &[&str]) -> PyResult<bool> {
    let value: serde_json::Value = serde_json::from_str(json).map_err(errors::value)?;
    let spec = path.iter().fold(&value, |v, k| &v[*k]);
    Ok(spec["allow_recurrent"].as_bool().unwrap_or(false))
}

/// A strategy restored from JSON, validated as it is read.
pub fn restore<T: DeserializeOwned>(text: &str, what: &str) -> PyResult<T> {
    serde_json::from_str(text).map_err(|e| errors::value(format!("{what} JSON: {e}")))
}

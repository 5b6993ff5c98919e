//! The search strategies beyond NEAT from Python, driven ask/tell as
//! `Population` is: novelty search, MAP-Elites and NSGA-II over NEAT genomes,
//! each class in its strategy's own file.

use pyo3::prelude::*;

mod map_elites;
mod novelty;
mod nsga2;

/// Adds the strategies' classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<novelty::NoveltySearch>()?;
    m.add_class::<map_elites::MapElites>()?;
    m.add_class::<nsga2::Nsga2>()
}

//! `vivae._vivae`: the native module of the vivae Python package.
//!
//! It binds vivae-sim (worlds stepped for the Gymnasium and PettingZoo
//! environments), vivae-neat (ask/tell populations, genomes, networks) and
//! vivae-lab (the driving task, runs written as `vivae evolve` writes them,
//! replays). The Python side (`python/vivae/`) wraps it in the environment
//! classes; the GIL is released whenever Rust simulates or evolves.

use pyo3::prelude::*;

mod drive;
mod errors;
mod evo;
mod lab;
mod portable_libm;
mod settings;

#[pymodule]
fn _vivae(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<drive::DriveCore>()?;
    m.add_class::<evo::Genome>()?;
    m.add_class::<evo::Network>()?;
    m.add_class::<evo::Population>()?;
    m.add_class::<lab::DriveTask>()?;
    m.add_class::<lab::Controller>()?;
    m.add_function(wrap_pyfunction!(lab::evolve, m)?)?;
    m.add_function(wrap_pyfunction!(lab::replay, m)?)?;
    m.add_function(wrap_pyfunction!(lab::load_genome, m)?)?;
    m.add_function(wrap_pyfunction!(lab::scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(lab::default_config, m)?)?;
    m.add_function(wrap_pyfunction!(portable_libm::math_is_portable, m)?)?;
    m.add("OVERRIDES", settings::OVERRIDES.to_vec())?;
    Ok(())
}

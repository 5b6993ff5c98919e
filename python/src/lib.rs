//! `vivae._vivae`: the native module of the vivae Python package.
//!
//! It binds vivae-sim (worlds stepped for the Gymnasium and PettingZoo
//! environments), vivae-neat (ask/tell populations, genomes, networks) and
//! vivae-lab (the driving task, runs written as `vivae evolve` writes them,
//! replays). The Python side (`python/vivae/`) wraps it in the environment
//! classes; the GIL is released whenever Rust simulates or evolves.

use pyo3::prelude::*;

mod args;
#[macro_use]
mod asktell;
mod errors;
mod evo;
mod export;
mod lab;
mod pool;
mod render;
mod reproduce;
// The program's portable C math symbols, shared rather than copied.
#[path = "../../crates/vivae/src/portable_libm.rs"]
mod portable_libm;
mod settings;
mod strategies;
mod tasks;

#[pymodule]
fn _vivae(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<evo::Genome>()?;
    m.add_class::<evo::Network>()?;
    m.add_class::<evo::Population>()?;
    strategies::register(m)?;
    tasks::register(m)?;
    m.add_function(wrap_pyfunction!(lab::evolve, m)?)?;
    m.add_function(wrap_pyfunction!(lab::resume, m)?)?;
    m.add_function(wrap_pyfunction!(lab::report, m)?)?;
    m.add_function(wrap_pyfunction!(lab::load_genome, m)?)?;
    m.add_function(wrap_pyfunction!(lab::scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(lab::default_config, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce::reproduce, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce::reproduce_packs, m)?)?;
    m.add_function(wrap_pyfunction!(export::export, m)?)?;
    m.add_function(wrap_pyfunction!(export::record_episode, m)?)?;
    m.add_function(wrap_pyfunction!(export::drive_image, m)?)?;
    m.add_function(wrap_pyfunction!(math_is_portable, m)?)?;
    m.add("OVERRIDES", settings::OVERRIDES.to_vec())?;
    // The registered tasks and strategies: `task=` and `strategy=` take these names.
    let tasks: Vec<&str> = vivae_lab::tasks::names().to_vec();
    m.add("TASKS", tasks)?;
    // Those of them whose episodes a host plays (the program does not run them).
    let hosted: Vec<&str> = (vivae_lab::tasks::entries().into_iter())
        .filter(|t| t.host.is_some())
        .map(|t| t.name)
        .collect();
    m.add("HOSTED_TASKS", hosted)?;
    let strategies: Vec<&str> = (vivae_lab::search::entries().into_iter())
        .map(|e| e.kind)
        .collect();
    m.add("STRATEGIES", strategies)?;
    Ok(())
}

/// Whether std's math (what the SVG stack calls) gives the portable `libm`
/// crate's bits inside this module, over a sweep of arguments.
#[pyfunction]
fn math_is_portable() -> bool {
    portable_libm::std_math_is_portable()
}

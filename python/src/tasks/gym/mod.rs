//! Gymnasium environments from Python, batched: [`Controllers`] activates a
//! whole population's networks in one call per environment step, the
//! player of the lab's `gymnasium` task hands each generation to
//! `vivae.gym` in one call, and `gym_evolve` / `gym_resume` write and
//! continue ordinary run directories (the library's own run code).

mod controllers;

use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::GenerationRecord;
use vivae_lab::tasks::gym::section::GymnasiumConfig;
use vivae_lab::tasks::gym::{self, Episodes, GymRun};
use vivae_neat::driver::Evaluation;
use vivae_neat::{EvalContext, Genome as NeatGenome};

use crate::evo::Genome;
use crate::{args, errors, settings};

pub use controllers::Controllers;

/// Adds the Gymnasium classes and functions to the module `m` and installs
/// the player of `gymnasium` runs.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    gym::set_player(&PLAYER);
    m.add_class::<Controllers>()?;
    m.add_function(wrap_pyfunction!(gym_evolve, m)?)?;
    m.add_function(wrap_pyfunction!(gym_resume, m)?)?;
    m.add_function(wrap_pyfunction!(gym_episode_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(gym_section, m)?)
}

/// The `[gymnasium]` section (a dict) of the run in `out`; refused for a
/// run of another task.
#[pyfunction]
fn gym_section<'py>(py: Python<'py>, out: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let path = out.join(vivae_lab::rundir::files::CONFIG);
    let config = vivae_lab::tasks::read_config(&path).map_err(errors::lab)?;
    if config.experiment.task.name() != gym::NAME {
        return Err(errors::value(format!(
            "{}: not {} run (experiment.task = {})",
            out.display(),
            vivae_lab::error::a(gym::NAME),
            config.experiment.task
        )));
    }
    crate::asktell::to_python(py, &GymnasiumConfig::of(&config))
}

/// The player: `vivae.gym._play(env, genomes, seeds)` under the GIL.
struct PythonPlayer;

static PLAYER: PythonPlayer = PythonPlayer;

/// The Python exception that stopped the last batch, raised again once the
/// run has stopped (the library carries a message, Python wants the exception).
static FAILURE: Mutex<Option<PyErr>> = Mutex::new(None);

impl Episodes for PythonPlayer {
    fn play(
        &self,
        env: &GymnasiumConfig,
        genomes: &[&NeatGenome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, String> {
        Python::attach(|py| {
            let played = (|| -> PyResult<Vec<(f64, f64, f64)>> {
                let genomes: Vec<Genome> = (genomes.iter())
                    .map(|g| Genome::new((*g).clone(), false))
                    .collect();
                let seeds: Vec<Vec<u64>> = (contexts.iter())
                    .map(|c| {
                        (0..env.episodes)
                            .map(|k| gym::episode_seed(c.seed, k))
                            .collect()
                    })
                    .collect();
                let module = py.import("vivae.gym")?;
                let section = crate::asktell::to_python(py, env)?;
                module
                    .call_method1("_play", (section, genomes, seeds))?
                    .extract()
            })();
            match played {
                Ok(rows) => Ok(rows
                    .into_iter()
                    .map(|(fitness, worst, steps)| Evaluation {
                        fitness,
                        metrics: vec![worst, steps],
                        behaviour: Vec::new(),
                    })
                    .collect()),
                Err(e) => {
                    let message = format!("playing {}: {e}", env.env);
                    *FAILURE.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                    Err(message)
                }
            }
        })
    }
}

/// The Gymnasium seeds of the episodes of the evaluations of `seeds`
/// (`episodes` each): what a run resets its environments with.
#[pyfunction]
fn gym_episode_seeds(seeds: Vec<u64>, episodes: u32) -> Vec<Vec<u64>> {
    (seeds.iter())
        .map(|s| (0..episodes).map(|k| gym::episode_seed(*s, k)).collect())
        .collect()
}

/// Evolves controllers of the Gymnasium environment `env` (the
/// `[gymnasium]` section as a dict) and writes the run directory `out`, as
/// every run's: the library's resolution of `overrides`, then its run.
#[pyfunction]
#[pyo3(signature = (env, out=None, config=None, force=false, on_generation=None, **overrides))]
fn gym_evolve<'py>(
    py: Python<'py>,
    env: &Bound<'py, PyDict>,
    out: Option<PathBuf>,
    config: Option<PathBuf>,
    force: bool,
    on_generation: Option<Py<PyAny>>,
    overrides: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let dir = args::run_dir(out)?;
    let settings = PyDict::new(py);
    settings.set_item("task", gym::NAME)?;
    if let Some(o) = overrides {
        settings.update(o.as_mapping())?;
    }
    let mut resolved = settings::resolved(config.as_deref(), Some(&settings))?;
    let section: GymnasiumConfig =
        crate::evo::merged(GymnasiumConfig::of(&resolved.config), Some(env), "env")?;
    resolved.config.owned.set(&section);
    vivae_lab::tasks::check(&resolved.config).map_err(|e| errors::value(format!("env: {e}")))?;
    let prepared = resolved.prepare().map_err(errors::lab)?;
    let run = py
        .detach(|| prepared.create(&dir, force))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Continues the `gymnasium` run in `out` (to `generations` in all, when
/// given), evaluating each generation in one batch as `gym_evolve` does.
#[pyfunction]
#[pyo3(signature = (out, generations=None, on_generation=None))]
fn gym_resume<'py>(
    py: Python<'py>,
    out: PathBuf,
    #[pyo3(from_py_with = args::generations)] generations: Option<u32>,
    on_generation: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let run = py
        .detach(|| Run::resume_in(&out, generations, None, None))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Runs `run` to its end (or to Ctrl-C, or an exception of `on_generation`
/// or of the episodes, each stopping it at its last checkpoint), one batch
/// a generation, and sums it up as a dict.
fn drive<'py>(
    py: Python<'py>,
    mut run: Run,
    on_generation: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let Some(task) = run.task().as_any().downcast_ref::<GymRun>().cloned() else {
        return Err(errors::value(format!(
            "{}: not {} run (experiment.task = {})",
            run.dir().display(),
            vivae_lab::error::a(gym::NAME),
            run.config().experiment.task
        )));
    };
    FAILURE.lock().unwrap_or_else(|p| p.into_inner()).take();
    let stop = AtomicBool::new(false);
    let failure: Mutex<Option<PyErr>> = Mutex::new(None);
    let started = std::time::Instant::now();
    let outcome = py.detach(|| {
        run.run_on(task.batch_evaluator(), &stop, |r: &GenerationRecord| {
            Python::attach(|py| {
                let result = match &on_generation {
                    Some(cb) => record_dict(py, r).and_then(|d| cb.call1(py, (d,)).map(|_| ())),
                    None => Ok(()),
                };
                if let Err(e) = result.and_then(|()| py.check_signals()) {
                    *failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                    stop.store(true, Ordering::SeqCst);
                }
            });
        })
    });
    let played = FAILURE.lock().unwrap_or_else(|p| p.into_inner()).take();
    let stopped = failure.into_inner().unwrap_or_else(|p| p.into_inner());
    let outcome = match (outcome, played) {
        (Err(_), Some(e)) => return Err(interrupted(py, e, &run)),
        (outcome, _) => outcome.map_err(errors::lab)?,
    };
    if let Some(e) = stopped {
        return Err(interrupted(py, e, &run));
    }
    let d = PyDict::new(py);
    d.set_item("out", run.dir().to_path_buf())?;
    d.set_item("generations", run.done())?;
    d.set_item("finished", outcome == Outcome::Finished)?;
    d.set_item("wall_s", started.elapsed().as_secs_f64())?;
    if let Some(c) = run.champion() {
        d.set_item("best", c.fitness)?;
        d.set_item("champion_generation", c.generation)?;
        d.set_item("champion", Genome::new(c.genome, false))?;
    }
    Ok(d)
}

/// `e` as raised to the caller: a Ctrl-C names where the run can resume from.
fn interrupted(py: Python<'_>, e: PyErr, run: &Run) -> PyErr {
    if e.is_instance_of::<PyKeyboardInterrupt>(py) {
        return PyKeyboardInterrupt::new_err(format!(
            "interrupted after generation {}; resume with: vivae.gym.resume({:?})",
            run.done(),
            run.dir().display().to_string()
        ));
    }
    e
}

/// A generation's record as `vivae.evolve` reports it, its throughput
/// named for what this task steps: environment steps.
fn record_dict<'py>(py: Python<'py>, r: &GenerationRecord) -> PyResult<Bound<'py, PyDict>> {
    let d = crate::lab::record_dict(py, r)?;
    d.del_item("robot_steps_per_second")?;
    d.set_item("env_steps_per_second", r.robot_steps_per_second)?;
    Ok(d)
}

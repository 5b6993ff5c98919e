//! Runs from Python: whole runs written as `vivae evolve` writes them,
//! resumed and reported, a champion's genome, the shipped scenarios and the
//! default config (a task's own classes are in `tasks/`).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::config::Config;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::GenerationRecord;

use crate::evo::Genome;
use crate::{args, errors, settings};

/// Evolves as `vivae evolve` does and writes the same run directory (all
/// but `figures/`, `report.html` and the wall times of `timing.csv`).
#[pyfunction]
#[pyo3(signature = (out=None, config=None, force=false, on_generation=None, **overrides))]
pub fn evolve<'py>(
    py: Python<'py>,
    out: Option<PathBuf>,
    config: Option<PathBuf>,
    force: bool,
    on_generation: Option<Py<PyAny>>,
    overrides: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let dir = args::run_dir(out)?;
    let resolved = settings::resolved(config.as_deref(), overrides)?;
    let config = resolved.config.clone();
    if let Some(driver) = vivae_lab::tasks::entry_of(&config)
        .ok()
        .and_then(|e| e.own_driver)
    {
        return own_driver_run(py, &dir, |session| {
            (driver.evolve)(&dir, config, force, session)
        });
    }
    // Without a config file a task starts from its own defaults, which it
    // may fit to its scenario (e.g. a grid archive fitted to its arena).
    let prepared = resolved.prepare().map_err(errors::lab)?;
    for m in &prepared.maps {
        errors::warn_scenario(py, &m.loaded.scenario)?;
    }
    let run = py
        .detach(|| prepared.create(&dir, force))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Runs a task on its own driver (the predator–prey task's two
/// populations): the dict holds `out`, `finished` and the summary line's
/// `key=value` fields (numbers as numbers).
fn own_driver_run<'py>(
    py: Python<'py>,
    dir: &Path,
    run: impl FnOnce(&vivae_lab::tasks::Session<'_>) -> vivae_lab::Result<vivae_lab::tasks::Stopped>
    + Send,
) -> PyResult<Bound<'py, PyDict>> {
    let stop = AtomicBool::new(false);
    let quiet = |_: &str| {};
    let line = py
        .detach(|| {
            let stopped = run(&vivae_lab::tasks::Session {
                interrupted: &stop,
                say: &quiet,
                players: None,
            })?;
            // Nothing sets `stop`: a run here stops only at its end.
            let line = stopped.line().unwrap_or_default().to_string();
            // Its figures and report.html, as the CLI draws them when a run stops.
            if let Some(tools) = vivae::tasks::of_run(dir) {
                (tools.report)(dir)?;
            }
            Ok::<_, vivae_lab::Error>(line)
        })
        .map_err(errors::lab)?;
    let d = PyDict::new(py);
    d.set_item("out", dir.to_path_buf())?;
    for (key, value) in line.split_whitespace().filter_map(|w| w.split_once('=')) {
        if key == "out" {
            continue;
        }
        match (value.parse::<u64>(), value.parse::<f64>()) {
            (Ok(n), _) => d.set_item(key, n)?,
            (_, Ok(x)) => d.set_item(key, x)?,
            _ => d.set_item(key, value)?,
        }
    }
    let done = d
        .get_item("generations")?
        .map(|g| g.extract::<u32>())
        .transpose()?;
    let config = vivae_lab::tasks::read_config(&dir.join("config.toml")).map_err(errors::lab)?;
    d.set_item("finished", done == Some(config.experiment.generations))?;
    Ok(d)
}

/// Continues the interrupted run in `out` (or extends a finished one to
/// `generations`) as `vivae resume` does: the same files, byte for byte.
/// `precision` ("exact" or "fast"), when given, must be the run's own.
#[pyfunction]
#[pyo3(signature = (out, generations=None, threads=None, on_generation=None, precision=None))]
pub fn resume<'py>(
    py: Python<'py>,
    out: PathBuf,
    #[pyo3(from_py_with = args::generations)] generations: Option<u32>,
    #[pyo3(from_py_with = args::opt_threads)] threads: Option<usize>,
    on_generation: Option<Py<PyAny>>,
    precision: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let precision = precision
        .map(|p| p.parse::<vivae_neat::Precision>())
        .transpose()
        .map_err(|e| errors::value(format!("precision: {e}")))?;
    if let Some(driver) = vivae_lab::tasks::own_driver_of_run(&out) {
        return own_driver_run(py, &out, |session| {
            (driver.resume)(&out, generations, session)
        });
    }
    let run = py
        .detach(|| Run::resume_in(&out, generations, threads, precision))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Draws the figures (`figures/`) and `report.html` of the finished or
/// interrupted run in `out`, as the program does at a run's end (and
/// `vivae resume` does for a run whose figures are missing or stale);
/// changes no result file. Returns the report's path.
#[pyfunction]
pub fn report(py: Python<'_>, out: PathBuf) -> PyResult<PathBuf> {
    py.detach(|| {
        // A task that draws its figures from the run directory alone.
        if let Some(tools) = vivae::tasks::of_run(&out).filter(|t| t.finish.is_none()) {
            return (tools.report)(&out);
        }
        // Opened as `vivae resume` opens it (locked; truncated to its newest
        // checkpoint, which a finished run's files already end at).
        let run = Run::resume(&out, None, None)?;
        if run.task().report_curves() {
            // A task without figures of its own: its curves alone.
            return vivae::report_html::write(run.dir());
        }
        if !run.task().entry().substrate {
            let task = &run.config().experiment.task;
            return Err(vivae_lab::io::bad_input(format!(
                "{}: {} run draws no figures; its curves are in generations.csv",
                out.display(),
                vivae_lab::error::a(task.name())
            )));
        }
        vivae::tasks::finish_run(&run)?;
        Ok(run.dir().join(vivae_lab::rundir::files::REPORT))
    })
    .map_err(errors::lab)
}

/// Runs `run` to its end (or to Ctrl-C, or an exception of `on_generation`,
/// each after a checkpoint) and sums it up as a dict.
fn drive<'py>(
    py: Python<'py>,
    mut run: Run,
    on_generation: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let stop = AtomicBool::new(false);
    let failure: Mutex<Option<PyErr>> = Mutex::new(None);
    let started = std::time::Instant::now();
    let mut reused = 0u64;
    let outcome = py.detach(|| {
        run.run(&stop, |r: &GenerationRecord| {
            reused += r.reused as u64;
            Python::attach(|py| {
                let result = match &on_generation {
                    Some(cb) => record_dict(py, r).and_then(|d| cb.call1(py, (d,)).map(|_| ())),
                    None => Ok(()),
                };
                let result = result.and_then(|()| py.check_signals());
                if let Err(e) = result {
                    *failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                    stop.store(true, Ordering::SeqCst);
                }
            });
        })
    });
    let outcome = outcome.map_err(errors::lab)?;
    let wall = started.elapsed().as_secs_f64();
    if let Some(e) = failure.into_inner().unwrap_or_else(|p| p.into_inner()) {
        if e.is_instance_of::<PyKeyboardInterrupt>(py) {
            return Err(PyKeyboardInterrupt::new_err(format!(
                "interrupted after generation {}; checkpoint written. Resume with: vivae.resume({:?})",
                run.done(),
                run.dir().display().to_string()
            )));
        }
        return Err(e);
    }
    let d = PyDict::new(py);
    d.set_item("out", run.dir().to_path_buf())?;
    d.set_item("generations", run.done())?;
    d.set_item("finished", outcome == Outcome::Finished)?;
    d.set_item("wall_s", wall)?;
    d.set_item("evaluations_reused", reused)?;
    if let Some(m) = run.target_progress() {
        // A task with a goal: as the CLI's `solved=` and `evals_to_solve=`.
        d.set_item("solved", m.solved_at.is_some())?;
        d.set_item("evals_to_solve", m.solved_at)?;
        d.set_item("evaluations", m.evaluations)?;
    }
    if let Some(c) = run.champion() {
        d.set_item("best", c.fitness)?;
        d.set_item("champion_generation", c.generation)?;
        if outcome == Outcome::Finished {
            // A task whose champion is validated: validation.json, as the CLI writes it.
            let written = py.detach(|| {
                vivae_lab::tasks::validation::write(
                    run.dir(),
                    run.task(),
                    &c.genome,
                    c.generation,
                    c.fitness,
                )
            });
            if let Some(v) = written.map_err(errors::lab)? {
                d.set_item("validation", validation_dict(py, &v)?)?;
            }
        }
        d.set_item("champion", Genome::new(c.genome, false))?;
    }
    Ok(d)
}

/// `validation.json`'s record as a dict of the same keys (`vivae.gym.validate`'s).
fn validation_dict<'py>(
    py: Python<'py>,
    v: &vivae_lab::tasks::validation::ValidationRecord,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("env", &v.env)?;
    d.set_item("episodes", v.episodes)?;
    d.set_item("seeds", v.seeds.to_vec())?;
    d.set_item("validation_seed", v.validation_seed)?;
    d.set_item("mean", v.mean)?;
    d.set_item("std", v.std)?;
    d.set_item("min", v.min)?;
    d.set_item("max", v.max)?;
    d.set_item("reward_threshold", v.reward_threshold)?;
    d.set_item("solved", v.solved)?;
    d.set_item("generation", v.generation)?;
    d.set_item("fitness", v.fitness)?;
    Ok(d)
}

/// A generation's record as `vivae.evolve`'s `on_generation` gets it.
pub(crate) fn record_dict<'py>(
    py: Python<'py>,
    r: &GenerationRecord,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let row = &r.row;
    d.set_item("generation", row.generation)?;
    d.set_item("total", r.total)?;
    d.set_item("best", row.best)?;
    d.set_item("mean", row.mean)?;
    d.set_item("median", row.median)?;
    d.set_item("worst", row.worst)?;
    d.set_item("species", row.species)?;
    d.set_item("best_ever", r.best_ever)?;
    d.set_item("seconds", r.seconds)?;
    d.set_item("robot_steps_per_second", r.robot_steps_per_second)?;
    d.set_item("reused", r.reused)?;
    Ok(d)
}

/// A champion file's (or run directory's) genome.
#[pyfunction]
pub fn load_genome(source: PathBuf) -> PyResult<(Genome, f64, u32)> {
    let (c, _, _) = vivae_lab::tasks::load_genome_source(&source).map_err(errors::lab)?;
    Ok((Genome::new(c.genome, false), c.fitness, c.generation))
}

/// The shipped scenarios: (name, description).
#[pyfunction]
pub fn scenarios() -> Vec<(String, String)> {
    vivae_lab::tasks::scenarios::all()
        .map(|s| (s.name.to_string(), s.what.to_string()))
        .collect()
}

/// The default config, commented (`vivae config default`).
#[pyfunction]
pub fn default_config() -> String {
    Config::default_commented(&vivae_lab::tasks::sections())
}

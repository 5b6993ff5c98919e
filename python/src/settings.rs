//! Configs from Python: a config file, then keyword overrides that mean
//! what the CLI's flags of the same names mean.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use vivae_lab::config::{Config, TaskName};
use vivae_lab::substrate::PolarGrid;

use crate::errors;

/// The keyword overrides every entry point accepts, as the CLI's flags.
pub const OVERRIDES: &[&str] = &[
    "scenario",
    "generations",
    "population",
    "seed",
    "sensors",
    "neurons",
    "steps",
    "robots",
    "threads",
    "distance_rays",
    "recurrence",
    "normalize_by",
    "normalize_self_loops",
    "train_neurons",
    "train_sensors",
    "train_aggregate",
    "substrate",
    "strategy",
    "behaviour",
    "task",
];

/// `config` (a TOML file) or the paper's default, with `overrides` applied and validated.
pub fn build(config: Option<&Path>, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    let task = match overrides.map(|o| o.get_item("task")).transpose()?.flatten() {
        Some(v) if !v.is_none() => {
            let t = parsed::<TaskName>("task", &v)?;
            vivae_lab::tasks::entry(t.name()).map_err(|e| errors::value(format!("task: {e}")))?;
            Some(t)
        }
        _ => None,
    };
    let c = match config {
        Some(p) => {
            let c = vivae_lab::tasks::read_config(p).map_err(errors::lab)?;
            // As `--task` with `--config`: the file says which task it is.
            if let Some(why) = c.task_mismatch(task.as_ref()) {
                let t = task.as_ref().map_or("", TaskName::name);
                return Err(errors::value(format!("task={t:?}: {why}")));
            }
            c
        }
        // The maze's own defaults, as `vivae evolve --task maze` starts from.
        None => vivae_lab::tasks::default_config(task.as_ref())
            .map_err(|why| errors::value(format!("task: {why}")))?,
    };
    build_from(c, overrides)
}

/// `c` with `overrides` applied and validated.
pub fn build_from(mut c: Config, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    if let Some(o) = overrides {
        apply(&mut c, o)?;
    }
    vivae_lab::tasks::check(&c).map_err(|e| errors::value(format!("arguments: {e}")))?;
    Ok(c)
}

fn grid(key: &str, v: &Bound<'_, PyAny>) -> PyResult<PolarGrid> {
    let s: String = v.extract()?;
    s.parse::<PolarGrid>()
        .map_err(|e| errors::value(format!("{key}={s:?}: {e}")))
}

fn grids(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Vec<PolarGrid>> {
    let items: Vec<Bound<'_, PyAny>> = v.extract()?;
    items.iter().map(|i| grid(key, i)).collect()
}

fn parsed<T: std::str::FromStr<Err = String>>(key: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    let s: String = v.extract()?;
    s.parse::<T>()
        .map_err(|e| errors::value(format!("{key}: {e}")))
}

/// A path given as `str` or `os.PathLike`.
pub fn path_text(v: &Bound<'_, PyAny>) -> PyResult<String> {
    let p: PathBuf = v.extract()?;
    Ok(p.to_string_lossy().into_owned())
}

fn apply(c: &mut Config, o: &Bound<'_, PyDict>) -> PyResult<()> {
    for (k, v) in o.iter() {
        let key: String = k.extract()?;
        if v.is_none() {
            continue;
        }
        match key.as_str() {
            "scenario" => set_scenarios(c, &v)?,
            "generations" => c.experiment.generations = v.extract()?,
            "population" => c.neat.population_size = v.extract()?,
            "seed" => c.experiment.seed = v.extract()?,
            "sensors" => {
                let g = grid(&key, &v)?;
                c.surface_sensors.rings = g.rings;
                c.surface_sensors.angles = g.angles;
            }
            "neurons" => c.substrate.neurons = grid(&key, &v)?,
            "steps" => c.experiment.steps = v.extract()?,
            "robots" => c.experiment.robots = v.extract()?,
            "threads" => c.run.threads = v.extract()?,
            "distance_rays" => c.distance_sensors.rays = v.extract()?,
            "recurrence" => c.substrate.recurrence = parsed(&key, &v)?,
            "normalize_by" => c.substrate.normalize_by = parsed(&key, &v)?,
            "normalize_self_loops" => c.substrate.normalize_self_loops = v.extract()?,
            "train_neurons" => c.substrate.train_neurons = grids(&key, &v)?,
            "train_sensors" => c.substrate.train_sensors = grids(&key, &v)?,
            "train_aggregate" => c.substrate.train_aggregate = parsed(&key, &v)?,
            "substrate" => c.substrate.kind = parsed(&key, &v)?,
            "strategy" => c.strategy.kind = parsed(&key, &v)?,
            "behaviour" => c.strategy.behaviour = parsed(&key, &v)?,
            "task" => c.experiment.task = parsed(&key, &v)?,
            other => {
                return Err(errors::value(format!(
                    "unknown setting {other:?}; expected one of {}",
                    OVERRIDES.join(", ")
                )));
            }
        }
    }
    Ok(())
}

/// `scenario=`: one map (a path or a shipped name) or a list of maps, as
/// one or several `--scenario` flags.
fn set_scenarios(c: &mut Config, v: &Bound<'_, PyAny>) -> PyResult<()> {
    let maps: Vec<String> =
        if v.is_instance_of::<PyList>() || v.is_instance_of::<pyo3::types::PyTuple>() {
            let items: Vec<Bound<'_, PyAny>> = v.extract()?;
            items.iter().map(path_text).collect::<PyResult<_>>()?
        } else if v.is_instance_of::<PyString>() {
            vec![v.extract()?]
        } else {
            vec![path_text(v)?]
        };
    match maps.as_slice() {
        [] => {}
        [one] => {
            c.experiment.scenario = one.clone();
            c.experiment.scenarios.clear();
        }
        several => {
            c.experiment.scenario.clear();
            c.experiment.scenarios = several.to_vec();
        }
    }
    Ok(())
}

/// The config's single scenario path (`None` = the embedded default).
pub fn scenario_path(config: &Config) -> Option<PathBuf> {
    (!config.experiment.scenario.is_empty()).then(|| PathBuf::from(&config.experiment.scenario))
}

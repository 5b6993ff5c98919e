//! Configs from Python: a config file, then keyword overrides that mean
//! what the CLI's flags of the same names mean.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use vivae_lab::config::{Config, TaskKind};
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
        Some(v) if !v.is_none() => Some(parsed::<TaskKind>("task", &v)?),
        _ => None,
    };
    let c = match config {
        Some(p) => {
            let c = vivae_lab::io::read_config(p).map_err(errors::lab)?;
            // As `--task` with `--config`: the file says which task it is.
            if let Some(why) = c.task_mismatch(task) {
                let t = task.map_or("", TaskKind::name);
                return Err(errors::value(format!("task={t:?}: {why}")));
            }
            c
        }
        // The maze's own defaults, as `vivae evolve --task maze` starts from.
        None => Config::for_task(task),
    };
    build_from(c, overrides)
}

/// `c` with `overrides` applied and validated.
pub fn build_from(mut c: Config, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    if let Some(o) = overrides {
        apply(&mut c, o)?;
    }
    c.validate()
        .map_err(|e| errors::value(format!("arguments: {e}")))?;
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
            "generations" => c.experiment.generations = int(&key, &v)?,
            "population" => c.neat.population_size = int(&key, &v)?,
            "seed" => c.experiment.seed = int(&key, &v)?,
            "sensors" => {
                let g = grid(&key, &v)?;
                c.surface_sensors.rings = g.rings;
                c.surface_sensors.angles = g.angles;
            }
            "neurons" => c.substrate.neurons = grid(&key, &v)?,
            "steps" => c.experiment.steps = int(&key, &v)?,
            "robots" => c.experiment.robots = int(&key, &v)?,
            "threads" => c.run.threads = int(&key, &v)?,
            "distance_rays" => c.distance_sensors.rays = int(&key, &v)?,
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

/// The integer `key=v`: a `TypeError` for anything but an int (a bool
/// included), a `ValueError` naming the allowed range for one out of range.
pub fn int<T: TryFrom<i128> + Bounded>(key: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    if v.is_instance_of::<pyo3::types::PyBool>() || !v.is_instance_of::<pyo3::types::PyInt>() {
        let ty = v.get_type().name()?;
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{key}: expected an integer, got {ty}"
        )));
    }
    let n: Option<i128> = v.extract().ok();
    n.and_then(|n| T::try_from(n).ok()).ok_or_else(|| {
        let (lo, hi) = T::RANGE;
        errors::value(format!("{key}={v}: expected an integer from {lo} to {hi}"))
    })
}

/// The range of an integer setting's type, for messages.
pub trait Bounded {
    /// The smallest and largest value.
    const RANGE: (u128, u128);
}

macro_rules! bounded {
    ($($t:ty),*) => {$(impl Bounded for $t {
        const RANGE: (u128, u128) = (<$t>::MIN as u128, <$t>::MAX as u128);
    })*};
}
bounded!(u32, u64, usize);

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

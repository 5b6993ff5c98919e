//! Configs from Python: a config file, then keyword overrides that mean
//! what the CLI's flags of the same names mean.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use vivae_lab::config::Config;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::run::prepare::{Overrides, Resolved, resolve};

use crate::errors::{self, SPELLING};

/// The keyword overrides every entry point accepts: the library's
/// [`Overrides`] keys, which are the CLI's flags too.
pub const OVERRIDES: [&str; 24] = Overrides::KEYS;

/// `config` (a TOML file) or the defaults of the task the keywords name (or
/// their shipped scenario is drawn for; the paper's when none), with
/// `overrides` applied and checked: the library's one resolution, as
/// `vivae evolve` does it.
pub fn resolved(
    config: Option<&Path>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<Resolved> {
    let o = match overrides {
        Some(d) => extract(d)?,
        None => Overrides::default(),
    };
    resolve(config, &o, &SPELLING).map_err(errors::lab)
}

/// [`resolved`]'s config.
pub fn build(config: Option<&Path>, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    Ok(resolved(config, overrides)?.config)
}

/// `c` with `overrides` applied and checked.
pub fn build_from(c: Config, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    match overrides {
        Some(d) => applied(c, &extract(d)?),
        None => applied(c, &Overrides::default()),
    }
}

/// `c` with `o` applied, checked by every rule of its task.
fn applied(mut c: Config, o: &Overrides) -> PyResult<Config> {
    o.apply(&mut c)
        .map_err(|e| errors::value(format!("arguments: {e}")))?;
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

/// The library's overrides of Python keyword arguments `d` (`None` values
/// are unset), each value checked for its key's type and range.
fn extract(d: &Bound<'_, PyDict>) -> PyResult<Overrides> {
    let mut o = Overrides::default();
    for (k, v) in d.iter() {
        let key: String = k.extract()?;
        if v.is_none() {
            continue;
        }
        set(&mut o, &key, &v)?;
    }
    Ok(o)
}

/// Sets override `key` of `o` to the Python value `v`.
fn set(o: &mut Overrides, key: &str, v: &Bound<'_, PyAny>) -> PyResult<()> {
    match key {
        "scenario" => o.scenario = scenarios(v)?,
        "generations" => o.generations = Some(int(key, v)?),
        "population" => o.population = Some(int(key, v)?),
        "seed" => o.seed = Some(int(key, v)?),
        "sensors" => o.sensors = Some(grid(key, v)?),
        "neurons" => o.neurons = Some(grid(key, v)?),
        "steps" => o.steps = Some(int(key, v)?),
        "robots" => o.robots = Some(int(key, v)?),
        "threads" => o.threads = Some(int(key, v)?),
        "distance_rays" => o.distance_rays = Some(int(key, v)?),
        "recurrence" => o.recurrence = Some(parsed(key, v)?),
        "normalize_by" => o.normalize_by = Some(parsed(key, v)?),
        "normalize_self_loops" => o.normalize_self_loops = Some(v.extract()?),
        "train_neurons" => o.train_neurons = Some(grids(key, v)?),
        "train_sensors" => o.train_sensors = Some(grids(key, v)?),
        "train_aggregate" => o.train_aggregate = Some(parsed(key, v)?),
        "substrate" => o.substrate = Some(parsed(key, v)?),
        "strategy" => o.strategy = Some(parsed(key, v)?),
        "behaviour" => o.behaviour = Some(parsed(key, v)?),
        "placements" => o.placements = Some(int(key, v)?),
        "placements_aggregate" => o.placements_aggregate = Some(parsed(key, v)?),
        "precision" => o.precision = Some(parsed(key, v)?),
        "task" | "robot" => {
            let t: String = v.extract()?;
            o.set(key, &t).map_err(errors::value)?;
        }
        other => {
            return Err(errors::value(format!(
                "unknown setting {other:?}; expected one of {}",
                OVERRIDES.join(", ")
            )));
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
fn scenarios(v: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    if v.is_instance_of::<PyList>() || v.is_instance_of::<pyo3::types::PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.extract()?;
        items.iter().map(path_text).collect()
    } else if v.is_instance_of::<PyString>() {
        Ok(vec![v.extract()?])
    } else {
        Ok(vec![path_text(v)?])
    }
}

/// The config's single scenario path (`None` = the embedded default).
pub fn scenario_path(config: &Config) -> Option<PathBuf> {
    (!config.experiment.scenario.is_empty()).then(|| PathBuf::from(&config.experiment.scenario))
}

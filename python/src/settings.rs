//! Configs from Python: a config file, then keyword overrides that mean
//! what the CLI's flags of the same names mean.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use vivae_lab::config::Config;
use vivae_lab::run::prepare::{Overrides, Resolved, ValueKind, resolve, setting};

use crate::args;
use crate::errors::{self, SPELLING};

/// The keyword overrides every entry point accepts: the library's
/// [`Overrides`] keys, which are the CLI's flags too.
pub const OVERRIDES: &[&str] = &Overrides::KEYS;

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

/// Sets override `key` of `o` to the Python value `v`: written as the text
/// the library parses, as its setting's kind says.
fn set(o: &mut Overrides, key: &str, v: &Bound<'_, PyAny>) -> PyResult<()> {
    let Some(setting) = setting(key) else {
        return Err(errors::value(format!(
            "unknown setting {key:?}; expected one of {}",
            OVERRIDES.join(", ")
        )));
    };
    for text in texts(key, setting.kind, v)? {
        (o.set(key, &text)).map_err(|e| errors::value(SPELLING.spell(&e)))?;
    }
    Ok(())
}

/// The Python value `v` of setting `key` as the texts the library parses
/// (one per call of [`Overrides::set`]); a value of the wrong type is a
/// `TypeError` naming `key`, a number out of range a `ValueError`.
fn texts(key: &str, kind: ValueKind, v: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let one = |text: String| Ok(vec![text]);
    match kind {
        ValueKind::Whole { max } => one(args::int_in::<u64>(key, v, 0, max.into())?.to_string()),
        ValueKind::Grid | ValueKind::Name => one(args::text(key, v)?),
        ValueKind::Grids => one(args::items(key, "grids", v, args::text)?.join(",")),
        ValueKind::Bool => one(args::boolean(key, v)?.to_string()),
        ValueKind::Scenarios => scenarios(v),
    }
}

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

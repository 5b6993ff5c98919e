//! A driving champion replayed from Python, as `vivae replay` does.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::tasks::driving::episode::Episode;

use super::task::episode_dict;
use crate::{args, errors, settings};

/// Replays a champion (a run directory or a `champion.json`) as `vivae
/// replay` does, without the figure: its fitness, time on road and behaviour measures.
#[pyfunction]
#[pyo3(signature = (source, **overrides))]
pub fn replay<'py>(
    py: Python<'py>,
    source: PathBuf,
    overrides: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (champion, mut config, _) =
        vivae_lab::tasks::load_genome_source(&source).map_err(errors::lab)?;
    let other_scenario = overrides.is_some_and(|o| o.contains("scenario").unwrap_or(false));
    // A multi-map run replays on its first training map unless told otherwise.
    if !other_scenario && vivae_lab::tasks::maps::is_multi_map(&config) {
        let maps = std::mem::take(&mut config.experiment.scenarios);
        config.experiment.scenario = maps[0].clone();
    }
    let extra = PyDict::new(py);
    // Another scenario has its own robot starts: all of them, unless told.
    if other_scenario {
        extra.set_item("robots", 0)?;
    }
    if let Some(o) = overrides {
        extra.update(o.as_mapping())?;
    }
    // Not a config key: which placement of random obstacles and traffic to replay on.
    let placement_seed: u64 = match extra.get_item("placement_seed")? {
        Some(v) => {
            extra.del_item("placement_seed")?;
            args::int("placement_seed", &v)?
        }
        None => 0,
    };
    // Not a config key either: the distance rays blinded (`vivae replay --blind-rays`).
    let blind_rays = take_flag(&extra, "blind_rays")?;
    // Nor this: the robots' meetings with the placed blocks (`vivae replay --meetings`).
    let meetings = take_flag(&extra, "meetings")?;
    let config = settings::build_from(config, Some(&extra))?;
    let path = settings::scenario_path(&config);
    if let Some(p) = path.as_deref().filter(|p| !other_scenario && !p.exists()) {
        return Err(errors::lab(vivae_lab::io::bad_input(format!(
            "{}: the champion's scenario {} is not there; name one with scenario=",
            source.display(),
            p.display()
        ))));
    }
    let scenario =
        vivae_lab::tasks::scenarios::load_scenario(path.as_deref()).map_err(errors::lab)?;
    let experiment = Episode::new(&config, &scenario.scenario)
        .map_err(|e| errors::lab(vivae_lab::Error::from(e)))?
        .with_placement_seed(placement_seed);
    let experiment = match blind_rays {
        true => experiment
            .with_blind_rays()
            .map_err(|e| errors::lab(vivae_lab::io::bad_input(format!("blind_rays=True: {e}"))))?,
        false => experiment,
    };
    let controller = experiment.robot_controller(&champion.genome).map_err(|e| {
        errors::lab(vivae_lab::Error::Genome {
            path: source.clone(),
            reason: format!("the genome's {e}"),
        })
    })?;
    let episode = py.detach(|| experiment.run(&controller, true));
    let dict = episode_dict(py, &episode)?;
    if meetings {
        let rays = config.distance_sensors.layout().unwrap_or_default().grid();
        let all = py
            .detach(|| {
                vivae_lab::tasks::driving::meetings::meetings(&experiment, &controller, Some(&rays))
            })
            .map_err(|e| errors::lab(vivae_lab::io::bad_input(format!("meetings=True: {e}"))))?;
        dict.set_item("meetings", meeting_dicts(py, &all)?)?;
    }
    Ok(dict)
}

/// Takes the flag `name` (True or False, default False) out of `extra`.
fn take_flag(extra: &Bound<'_, PyDict>, name: &str) -> PyResult<bool> {
    match extra.get_item(name)? {
        Some(v) => {
            extra.del_item(name)?;
            v.extract::<bool>()
                .map_err(|_| errors::value(format!("{name}= takes True or False")))
        }
        None => Ok(false),
    }
}

/// Each meeting as a dict (robots and blocks 1-based, as the CSV of
/// `vivae replay --meetings` has them).
fn meeting_dicts<'py>(
    py: Python<'py>,
    all: &[vivae_lab::tasks::driving::meetings::Meeting],
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    all.iter()
        .map(|m| {
            let d = PyDict::new(py);
            d.set_item("robot", m.robot + 1)?;
            d.set_item("block", m.block + 1)?;
            d.set_item("entry_step", m.entry_step)?;
            d.set_item("exit_step", m.exit_step)?;
            d.set_item("block_across", m.block_across)?;
            d.set_item("entry_across", m.entry_across)?;
            d.set_item("on_line", m.on_line)?;
            d.set_item("touches", m.touches)?;
            d.set_item("clearance", m.clearance)?;
            d.set_item("pass_across", m.pass_across)?;
            d.set_item("shift", m.shift)?;
            d.set_item("seen_at", m.seen_at)?;
            d.set_item("seen_steps", m.seen_steps)?;
            d.set_item("peak", m.peak)?;
            d.set_item("exit", m.exit.name())?;
            Ok(d)
        })
        .collect()
}

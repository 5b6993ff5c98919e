//! Training on several maps at once: every genome is evaluated on each
//! training map, with that map's own robots, and its fitness is the mean over
//! maps (each map weighs the same, whatever its number of robots).
//!
//! The maps are `experiment.scenarios` (`vivae evolve --scenario A --scenario
//! B`). Each map's evaluation is deterministic and composes with
//! multi-resolution evolution (a map's fitness is then its own aggregate over
//! the training resolutions), so the mean does not depend on thread or process
//! count. A run directory keeps a copy of every map under `scenarios/` with a
//! manifest of their FNV-1a hashes; the checkpoint records the hashes too, and
//! `resume` refuses a copy that changed.
//!
//! Each map's arena is bounded by the scenario loader (10⁸ px², a 100 MB
//! surface raster); all maps together by [`MAX_MAPS_RASTER_BYTES`], checked
//! before any map's raster is built.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use vivae_sim::{LoadOptions, Scenario};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{bad_input, fnv1a, read_text};
pub use crate::rundir::{TrainingMap, is_multi_map};
use crate::tasks::scenarios::load_scenario;

/// Most bytes the surface rasters of all training maps may take together
/// (one byte per 1 px cell): ten arenas at the loader's per-map limit.
pub const MAX_MAPS_RASTER_BYTES: f64 = 1e9;

/// Cell side of the quick load that sizes a map before its real load: a
/// raster 4096 times smaller than the real one.
const SIZING_CELL: f64 = 64.0;

/// The map-weighted mean: the sum in map order over the number of maps (so
/// that a test can repeat it bit for bit).
pub fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// Whether `config`'s task trains on maps (its entry's [`crate::tasks::TaskEntry::maps`]).
pub fn uses_maps(config: &Config) -> bool {
    crate::tasks::entry(config.experiment.task.name())
        .ok()
        .is_none_or(|e| e.maps)
}

/// Loads the training maps `config` names: `experiment.scenarios`, else the
/// single `experiment.scenario` (empty = the embedded default); none for a
/// task without maps.
pub fn load(config: &Config) -> Result<Vec<TrainingMap>> {
    if !uses_maps(config) {
        return Ok(Vec::new());
    }
    let maps = load_unchecked(config)?;
    if let Ok(task) = crate::tasks::entry(config.experiment.task.name()) {
        for map in &maps {
            (task.check_map)(&map.loaded.scenario).map_err(bad_input)?;
        }
    }
    Ok(maps)
}

/// The maps of [`load`], before their task's check.
fn load_unchecked(config: &Config) -> Result<Vec<TrainingMap>> {
    if !is_multi_map(config) {
        let path = (!config.experiment.scenario.is_empty())
            .then(|| PathBuf::from(&config.experiment.scenario));
        let loaded = load_scenario(path.as_deref())?;
        return Ok(vec![TrainingMap {
            label: crate::io::scenario_name(path.as_deref()),
            loaded,
        }]);
    }
    check_total_size(&config.experiment.scenarios)?;
    config
        .experiment
        .scenarios
        .iter()
        .map(|name| {
            let path = Path::new(name);
            Ok(TrainingMap {
                label: crate::io::scenario_name(Some(path)),
                loaded: load_scenario(Some(path))?,
            })
        })
        .collect()
}

/// Loads the training maps of the run in `dir` (its config `config`): the
/// copies under `scenarios/` for a multi-map run, else `scenario.svg` (none
/// for a task without maps).
/// With `hashes` (from the checkpoint), a copy whose text changed is refused.
pub fn load_run(dir: &Path, config: &Config, hashes: Option<&[u64]>) -> Result<Vec<TrainingMap>> {
    if !uses_maps(config) {
        return Ok(Vec::new());
    }
    if !is_multi_map(config) {
        let path = dir.join(crate::rundir::files::SCENARIO);
        return Ok(vec![TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        }]);
    }
    let names = &config.experiment.scenarios;
    if let Some(h) = hashes
        && h.len() != names.len()
    {
        return Err(Error::Checkpoint {
            path: dir.to_path_buf(),
            reason: format!(
                "the checkpoint records {} training maps, config.toml names {}",
                h.len(),
                names.len()
            ),
        });
    }
    let mut maps = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        // A run's maps are its own copies, `scenarios/FILE`. The config may
        // name them as written (relative to the run) or as `read_config`
        // resolved them (relative to the working directory, or absolute):
        // the file name finds the copy either way, and nothing outside it.
        let file = Path::new(name).file_name().unwrap_or_default();
        let path = dir.join(crate::rundir::MAPS_DIR).join(file);
        let text = crate::io::read_text(&path)?;
        if let Some(h) = hashes
            && h[i] != fnv1a(text.as_bytes())
        {
            return Err(Error::Checkpoint {
                path,
                reason: format!(
                    "training map {} was edited since the run started (its hash is not the one the checkpoint records); restore it, or start a new run",
                    i + 1
                ),
            });
        }
        maps.push(TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        });
    }
    Ok(maps)
}

/// The surface raster a scenario's arena takes, in bytes (1 px cells, one byte each).
pub fn raster_estimate(scenario: &Scenario) -> f64 {
    scenario.width().ceil() * scenario.height().ceil()
}

/// Refuses training maps `names` whose rasters would together take more than
/// [`MAX_MAPS_RASTER_BYTES`], the message giving the estimate. Each map is
/// sized by a load with coarse cells, so nothing large is built to refuse it.
fn check_total_size(names: &[String]) -> Result<()> {
    let sizing = LoadOptions {
        cell_size: SIZING_CELL,
        ..LoadOptions::default()
    };
    let mut total = 0.0;
    let mut largest = (0.0, "");
    for name in names {
        let path = Path::new(name);
        let scenario = if path.is_file() {
            Scenario::from_svg(&read_text(path)?, name, &sizing)?
        } else {
            // A shipped scenario (small), or the error the real load gives.
            load_scenario(Some(path))?.scenario
        };
        let bytes = raster_estimate(&scenario);
        total += bytes;
        if bytes > largest.0 {
            largest = (bytes, name);
        }
    }
    if total > MAX_MAPS_RASTER_BYTES {
        return Err(bad_input(format!(
            "experiment.scenarios: the {} training maps' surface rasters would take about {:.0} MB in all \
             (the largest, {}, {:.0} MB), more than the limit of {:.0} MB: train on fewer or smaller maps",
            names.len(),
            total / 1e6,
            largest.1,
            largest.0 / 1e6,
            MAX_MAPS_RASTER_BYTES / 1e6
        )));
    }
    Ok(())
}

/// Pairs `(i, j)`, `i < j`, of training maps with the same text: such a map
/// is trained on twice, and counts twice in the mean fitness. Each later
/// copy is paired with the first.
pub fn repeated(maps: &[TrainingMap]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for (j, m) in maps.iter().enumerate() {
        if let Some(i) = (0..j).find(|&i| maps[i].loaded.text == m.loaded.text) {
            pairs.push((i, j));
        }
    }
    pairs
}

/// One warning line for each map of `maps` given more than once (none for a single map).
pub fn repeat_warnings(maps: &[TrainingMap]) -> Vec<String> {
    repeated(maps)
        .into_iter()
        .map(|(i, j)| {
            format!(
                "training maps {} ({}) and {} ({}) are the same map: it is trained on twice and counts twice in the mean fitness",
                i + 1,
                maps[i].loaded.scenario.source,
                j + 1,
                maps[j].loaded.scenario.source
            )
        })
        .collect()
}

/// One text standing for all training maps (compared between MPI ranks):
/// the single map's text, or every map's text after its name.
pub fn fingerprint_text(maps: &[TrainingMap]) -> String {
    match maps {
        [one] => one.loaded.text.clone(),
        _ => maps.iter().fold(String::new(), |mut s, m| {
            let _ = write!(s, "\n--- {} ---\n{}", m.label, m.loaded.text);
            s
        }),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A short run's config training on the shipped `maps` (also the
    /// training tests').
    pub(crate) fn config(maps: &[&str]) -> Config {
        let mut c = Config::default();
        c.experiment.steps = 60;
        c.experiment.scenarios = maps.iter().map(|s| s.to_string()).collect();
        c
    }

    /// Writes `copies` files of one big arena (10001×9990 px, just under the
    /// per-map limit) into a fresh folder; returns their paths.
    fn big_arenas(name: &str, copies: usize) -> Vec<String> {
        let dir = std::env::temp_dir().join(format!("vivae-maps-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="10001" height="9990"><rect id="road1" x="0" y="80" width="400" height="40" inkscape:label="Road"/><rect id="r1" x="100" y="100" width="12" height="12" inkscape:label="Robot"/></svg>"#;
        (0..copies)
            .map(|k| {
                let p = dir.join(format!("arena-{k}.svg"));
                std::fs::write(&p, svg).unwrap();
                p.to_string_lossy().into_owned()
            })
            .collect()
    }

    #[test]
    fn many_big_maps_are_refused_with_their_total_before_any_raster_is_built() {
        let names = big_arenas("total", 24);
        let mut c = Config::default();
        c.experiment.scenarios = names.clone();
        let e = load(&c).unwrap_err();
        let message = e.to_string();
        assert!(e.is_bad_input(), "{e:?}");
        assert!(!message.contains('\n'), "{message}");
        // 24 × 10001 × 9990 bytes ≈ 2398 MB.
        assert!(
            message.contains("24 training maps") && message.contains("about 2398 MB"),
            "{message}"
        );
        assert!(message.contains("limit of 1000 MB"), "{message}");
        // Ten of them fit.
        c.experiment.scenarios.truncate(10);
        assert_eq!(
            check_total_size(&c.experiment.scenarios).map_err(|e| e.to_string()),
            Ok(())
        );
        let dir = Path::new(&names[0]).parent().unwrap().to_path_buf();
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_map_given_twice_is_reported_once_per_extra_copy() {
        let maps = load(&config(&["oval", "roads", "oval", "oval"])).unwrap();
        assert_eq!(repeated(&maps), [(0, 2), (0, 3)]);
        let warnings = repeat_warnings(&maps);
        assert_eq!(warnings.len(), 2);
        assert!(
            warnings[0].starts_with("training maps 1 (oval.svg (shipped)) and 3 "),
            "{}",
            warnings[0]
        );
        assert!(repeat_warnings(&load(&config(&["oval", "roads"])).unwrap()).is_empty());
    }
}

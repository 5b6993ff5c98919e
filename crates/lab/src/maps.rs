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

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::config::Config;
use crate::error::Result;
use crate::io::{LoadedScenario, load_scenario};

/// The map-weighted mean: the sum in map order over the number of maps (so
/// that a test can repeat it bit for bit).
pub fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// A training map as loaded: its label and its SVG.
#[derive(Debug, Clone)]
pub struct TrainingMap {
    /// Short name (the file stem, e.g. `oval`).
    pub label: String,
    /// The parsed scenario and its text.
    pub loaded: LoadedScenario,
}

/// Whether `config` trains on a list of maps (`experiment.scenarios`).
pub fn is_multi_map(config: &Config) -> bool {
    !config.experiment.scenarios.is_empty()
}

/// Loads the training maps `config` names: `experiment.scenarios`, else the
/// single `experiment.scenario` (empty = the embedded default).
pub fn load(config: &Config) -> Result<Vec<TrainingMap>> {
    if !is_multi_map(config) {
        let path = (!config.experiment.scenario.is_empty())
            .then(|| PathBuf::from(&config.experiment.scenario));
        let loaded = load_scenario(path.as_deref())?;
        return Ok(vec![TrainingMap {
            label: crate::io::scenario_name(path.as_deref()),
            loaded,
        }]);
    }
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
mod tests {
    use super::*;
    use crate::experiment::Experiment;
    use crate::rundir::{copy_names, manifest};
    use crate::task::DrivingTask;
    use crate::training::Training;
    use vivae_neat::driver::Task;
    use vivae_neat::{EvalContext, Population};

    fn config(maps: &[&str]) -> Config {
        let mut c = Config::default();
        c.experiment.steps = 60;
        c.experiment.scenarios = maps.iter().map(|s| s.to_string()).collect();
        c
    }

    #[test]
    fn fitness_is_the_mean_over_maps_of_each_maps_own_fitness() {
        let c = config(&["roads", "oval", "traffic"]);
        let maps = load(&c).unwrap();
        let e = Training::new(&c, &maps).unwrap();
        let pop = Population::new(c.neat.clone(), e.cppn_spec(), 3).unwrap();
        let ctx = EvalContext {
            generation: 1,
            index: 0,
            seed: 0,
        };
        for g in pop.genomes().iter().take(4) {
            let alone: Vec<f64> = maps
                .iter()
                .map(|m| {
                    let mut single = c.clone();
                    single.experiment.scenarios.clear();
                    Experiment::new(&single, &m.loaded.scenario)
                        .unwrap()
                        .fitness(g)
                })
                .collect();
            let want = (alone[0] + alone[1] + alone[2]) / 3.0;
            assert_eq!(e.evaluate(g, &ctx).fitness.to_bits(), want.to_bits());
        }
        // Reported and drawn: the first map.
        assert_eq!(e.primary().robots(), 5);
        let steps: u64 = [5u64, 5, 5].iter().map(|r| r * 60).sum();
        assert_eq!(e.robot_steps(), steps);
    }

    #[test]
    fn maps_compose_with_training_resolutions() {
        let mut c = config(&["roads", "oval"]);
        c.substrate.train_neurons = vec![
            crate::substrate::PolarGrid {
                rings: 3,
                angles: 3,
            },
            crate::substrate::PolarGrid {
                rings: 5,
                angles: 5,
            },
        ];
        let maps = load(&c).unwrap();
        let e = Training::new(&c, &maps).unwrap();
        assert_eq!(e.map_labels().collect::<Vec<_>>(), ["roads", "oval"]);
        assert_eq!(e.resolution_labels(), ["s3x5-n3x3", "s3x5-n5x5"]);
        let pop = Population::new(c.neat.clone(), e.cppn_spec(), 5).unwrap();
        let g = &pop.genomes()[0];
        let ctx = EvalContext {
            generation: 1,
            index: 0,
            seed: 0,
        };
        let per_map: Vec<f64> = maps
            .iter()
            .map(|m| {
                crate::resolutions::at_resolutions(&c, &m.loaded.scenario)
                    .unwrap()
                    .unwrap()
                    .evaluate(g, &ctx)
                    .fitness
            })
            .collect();
        assert_eq!(
            e.evaluate(g, &ctx).fitness.to_bits(),
            mean(&per_map).to_bits()
        );
        assert_eq!(e.robot_steps(), 2 * 2 * 5 * 60);
    }

    #[test]
    fn copies_of_maps_with_one_name_get_distinct_files() {
        let c = config(&["oval", "oval", "roads"]);
        let maps = load(&c).unwrap();
        assert_eq!(copy_names(&maps), ["oval.svg", "oval-2.svg", "roads.svg"]);
        let m = manifest(&copy_names(&maps), &maps);
        assert_eq!(m.lines().count(), 4);
        assert!(m.contains("oval-2.svg "));
    }

    #[test]
    fn a_single_scenario_config_builds_the_plain_experiment() {
        let c = Config::default();
        let e = Training::new(&c, &load(&c).unwrap()).unwrap();
        assert_eq!(e.map_labels().count(), 0);
        assert!(e.resolution_labels().is_empty());
    }
}

//! What a run trains on: the task every genome is evaluated on (its maps,
//! each at its resolutions), and the experiment that reports, draws and
//! replays (the first map at the run's own resolution).
//!
//! A single-map, single-resolution run trains on exactly its
//! [`Episode`]. With `substrate.train_neurons`/`train_sensors` a map's
//! task is a [`Combined`] over resolutions ([`crate::tasks::driving::resolutions`]); with
//! `experiment.scenarios` the run's task is the mean over maps of each
//! map's task, each map with its own robots.

use std::sync::Arc;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome, GenomeSpec};

use crate::config::{Aggregate, Config};
use crate::error::Result;
use crate::tasks::driving::combined::{Combined, DrivingTask};
use crate::tasks::driving::episode::{Episode, EpisodeError};
use crate::tasks::driving::resolutions::at_resolutions;
use crate::tasks::maps::{TrainingMap, is_multi_map};

/// The task a run evaluates genomes on, and the experiment it reports.
#[derive(Debug, Clone)]
pub struct Training {
    /// The first map at the run's own resolution: reported, drawn, replayed.
    primary: Episode,
    /// With several maps: (label, experiment) of each at the run's own resolution.
    maps: Vec<(String, Episode)>,
    /// With several resolutions: their labels, in evaluation order.
    resolutions: Vec<String>,
    aggregate: Aggregate,
    task: Arc<dyn DrivingTask>,
}

impl Training {
    /// The training of `config` on `maps` (loaded by [`crate::tasks::maps::load`]
    /// or [`crate::tasks::maps::load_run`]).
    pub fn new(config: &Config, maps: &[TrainingMap]) -> Result<Training> {
        let first = maps
            .first()
            .ok_or_else(|| crate::io::bad_input("no training map"))?;
        if !is_multi_map(config) {
            let (primary, task, resolutions) = map_task(config, first)?;
            refuse_fixed_placements(config, [&primary])?;
            return Ok(Training::of(primary, Vec::new(), resolutions, config, task));
        }
        let mut experiments = Vec::with_capacity(maps.len());
        let mut parts: Vec<(String, Box<dyn DrivingTask>)> = Vec::with_capacity(maps.len());
        let mut resolutions = Vec::new();
        for m in maps {
            let (e, task, r) = map_task(config, m).map_err(|e| match e {
                EpisodeError::Scenario(s) => EpisodeError::Scenario(s),
                other => EpisodeError::Config(format!("training map {}: {other}", m.label)),
            })?;
            experiments.push((m.label.clone(), e));
            parts.push((m.label.clone(), task));
            resolutions = r;
        }
        refuse_fixed_placements(config, experiments.iter().map(|(_, e)| e))?;
        let primary = experiments[0].1.clone();
        let task: Box<dyn DrivingTask> = Box::new(Combined::new(parts, Aggregate::Mean));
        Ok(Training::of(
            primary,
            experiments,
            resolutions,
            config,
            task,
        ))
    }

    fn of(
        primary: Episode,
        maps: Vec<(String, Episode)>,
        resolutions: Vec<String>,
        config: &Config,
        task: Box<dyn DrivingTask>,
    ) -> Training {
        Training {
            primary,
            maps,
            resolutions,
            aggregate: config.substrate.train_aggregate,
            task: Arc::from(task),
        }
    }

    /// The experiment reported, drawn and replayed: the first map at the run's own resolution.
    pub fn primary(&self) -> &Episode {
        &self.primary
    }

    /// The task genomes are evaluated on.
    pub fn task(&self) -> &dyn DrivingTask {
        &*self.task
    }

    /// Labels of the training maps when there are several (else none), in evaluation order.
    pub fn map_labels(&self) -> impl Iterator<Item = &str> {
        self.maps.iter().map(|(l, _)| l.as_str())
    }

    /// Each training map's experiment at the run's own resolution, when there are several maps.
    pub fn map_experiments(&self) -> impl Iterator<Item = &Episode> {
        self.maps.iter().map(|(_, e)| e)
    }

    /// Labels (`sRxA-nRxA`) of the training resolutions when there are several (else none).
    pub fn resolution_labels(&self) -> &[String] {
        &self.resolutions
    }

    /// How the fitnesses at several resolutions combine.
    pub fn aggregate(&self) -> Aggregate {
        self.aggregate
    }

    /// Robot-steps one evaluation simulates, over every map and resolution.
    pub fn robot_steps(&self) -> u64 {
        self.task.robot_steps()
    }

    /// The training maps for a person: `roads.svg (shipped): 5 robots, …`.
    pub fn describe(&self, maps: &[TrainingMap]) -> String {
        if self.maps.is_empty() {
            return maps
                .first()
                .map(|m| m.loaded.scenario.source.clone())
                .unwrap_or_default();
        }
        maps.iter()
            .zip(self.map_experiments())
            .map(|(m, e)| format!("{}: {} robots", m.loaded.scenario.source, e.robots()))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Refuses `experiment.placements` > 1 when none of `maps` places obstacles
/// or traffic per evaluation: every placement would be the same episode.
fn refuse_fixed_placements<'a>(
    config: &Config,
    maps: impl IntoIterator<Item = &'a Episode>,
) -> std::result::Result<(), EpisodeError> {
    let n = config.experiment.placements;
    if n > 1 && !maps.into_iter().any(Episode::varies) {
        return Err(EpisodeError::Config(format!(
            "experiment.placements = {n}: no training map places obstacles or traffic per \
             evaluation, so every placement would be the same episode; use a scenario that \
             does (obstacles-random, oncoming) or drop it"
        )));
    }
    Ok(())
}

/// A map's experiment at the run's own resolution, its training task, and
/// the labels of its resolutions.
type MapTask = (Episode, Box<dyn DrivingTask>, Vec<String>);

/// The [`MapTask`] of `map` under `config`.
fn map_task(config: &Config, map: &TrainingMap) -> std::result::Result<MapTask, EpisodeError> {
    let experiment = Episode::new(config, &map.loaded.scenario)?;
    Ok(match at_resolutions(config, &map.loaded.scenario)? {
        Some(combined) => {
            let labels = combined.labels().map(String::from).collect();
            (experiment, Box::new(combined), labels)
        }
        None => (experiment.clone(), Box::new(experiment), Vec::new()),
    })
}

impl Task for Training {
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        self.task.evaluate(genome, ctx)
    }

    fn metric_names(&self) -> &[&str] {
        self.task.metric_names()
    }

    fn context_free(&self) -> bool {
        self.task.context_free()
    }
}

impl DrivingTask for Training {
    fn robot_steps(&self) -> u64 {
        self.task.robot_steps()
    }

    fn cppn_spec(&self) -> GenomeSpec {
        self.primary.cppn_spec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::maps::tests::config;
    use crate::tasks::maps::{load, mean};
    use vivae_neat::Population;

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
                    Episode::new(&single, &m.loaded.scenario)
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
            crate::controller::substrate::PolarGrid {
                rings: 3,
                angles: 3,
            },
            crate::controller::substrate::PolarGrid {
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
                crate::tasks::driving::resolutions::at_resolutions(&c, &m.loaded.scenario)
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
    fn a_single_scenario_config_builds_the_plain_experiment() {
        let c = Config::default();
        let e = Training::new(&c, &load(&c).unwrap()).unwrap();
        assert_eq!(e.map_labels().count(), 0);
        assert!(e.resolution_labels().is_empty());
    }
}

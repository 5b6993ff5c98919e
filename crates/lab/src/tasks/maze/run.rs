//! The maze benchmark as a run of `vivae evolve` (`experiment.task = "maze"`):
//! its registration, default settings (those of `cargo run --example maze`),
//! and what a maze run records besides fitness.
//!
//! A maze run evolves plain NEAT networks ([`MazeTask::spec`]) on the one
//! maze named by `experiment.scenario`, with the robot of `[physics]` for
//! `experiment.steps` steps. It stops after the generation in which a
//! genome first reaches the goal, as the example does; `evals_to_solve`
//! counts the evaluations up to and including that genome.

use vivae_neat::driver::Evaluation;
use vivae_neat::{Genome, GenomeSpec};
use vivae_sim::Scenario;

use crate::config::Config;
use crate::error::Result;
use crate::io::bad_input;
use crate::search::TaskFacts;
use crate::search::{BehaviourSpace, StrategyConfig};
use crate::tasks::maps::TrainingMap;
use crate::tasks::maze::config::{MazeConfig, MazeRobot};
use crate::tasks::maze::lehman::LehmanTask;
use crate::tasks::maze::walls::LehmanMaze;
use crate::tasks::maze::{CELL, METRICS, MazeModel, MazeTask, NAME};
use crate::tasks::{Finished, HeaderContext, RunTask, TargetProgress, TaskEntry};

/// The maze task's registration.
pub static TASK: TaskEntry = TaskEntry {
    name: NAME,
    default_config: Config::maze,
    validate: crate::tasks::maze::config::validate,
    metric_names: &METRICS,
    generation_columns: COLUMNS,
    // The robot's end position in px (the maze's bounds).
    behaviours: &[crate::tasks::behaviours::BehaviourEntry {
        name: crate::config::strategy::BehaviourName::DEFAULT,
        coordinates: crate::tasks::behaviours::position,
    }],
    build,
    own_driver: None,
    refuse_when_other: crate::tasks::nothing_to_refuse,
    set_robot: Some(|c, r| {
        let robot = r.parse()?;
        c.owned.update(|m: &mut MazeConfig| m.robot = robot);
        Ok(())
    }),
    sections: &[super::section::SECTION],
    reads: &crate::config::SharedSection::ALL,
    scenarios: &super::SCENARIOS,
    maps: true,
    check_map: crate::tasks::any_map,
    substrate: false,
    substrate_episode: None,
    stepped: None,
    reward_threshold: None,
    host: None,
};

/// The maze task of a maze run's `config` on `scenario`; bad input (naming
/// the scenario) when it is not a maze.
pub fn task(config: &Config, scenario: &Scenario) -> Result<MazeTask> {
    MazeTask::with_settings(scenario, &config.physics, config.experiment.steps)
        .map_err(|e| bad_input(e.to_string()))
}

/// The maze of `config`'s Lehman robot on `map` (Lehman's walls for a
/// shipped maze unless `maze.walls = "scenario"`).
pub fn lehman_task(config: &Config, map: &TrainingMap) -> Result<LehmanTask> {
    let (scenario, svg) = (&map.loaded.scenario, &map.loaded.text);
    let maze = LehmanMaze::of_map(scenario, svg, MazeConfig::of(config).walls)
        .map_err(|e| bad_input(e.to_string()))?;
    Ok(LehmanTask::new(
        maze,
        &MazeConfig::of(config),
        config.experiment.steps,
    ))
}

/// The maze run of `config` on the first of `maps` (a maze run has one),
/// with the robot of `maze.robot`.
fn build(config: &Config, maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    let map = maps.first().ok_or_else(|| bad_input("no maze"))?;
    Ok(match MazeConfig::of(config).robot {
        MazeRobot::Lehman => Box::new(lehman_task(config, map)?),
        MazeRobot::Vivae => Box::new(task(config, &map.loaded.scenario)?),
    })
}

/// The columns a maze run adds to `generations.csv`, with their leading comma.
pub const COLUMNS: &str = ",best_distance,solvers,evaluations";

/// One generation of a maze run: the fields it adds to `generations.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MazeGeneration {
    /// The smallest end distance to the goal in the generation, px.
    pub best_distance: f64,
    /// Genomes of the generation that reached the goal.
    pub solvers: usize,
}

impl MazeGeneration {
    /// The generation of `evaluations`.
    pub fn of(evaluations: &[Evaluation]) -> MazeGeneration {
        let distances = evaluations.iter().filter_map(|e| e.metrics.get(1));
        MazeGeneration {
            best_distance: distances.copied().fold(f64::INFINITY, f64::min),
            solvers: evaluations.iter().filter(|e| solved(e)).count(),
        }
    }
}

/// Whether a maze evaluation reached the goal (its first metric).
fn solved(e: &Evaluation) -> bool {
    e.metrics.first() == Some(&1.0)
}

impl<M: MazeModel> RunTask for M {
    fn entry(&self) -> &'static TaskEntry {
        &TASK
    }

    fn genome_spec(&self) -> GenomeSpec {
        MazeTask::spec()
    }

    fn behaviour_space(&self, _config: &Config) -> BehaviourSpace {
        let (lower, upper) = self.bounds();
        let names = crate::tasks::behaviours::position(lower.len());
        BehaviourSpace {
            lower,
            upper,
            names,
        }
    }

    fn robot_steps(&self) -> u64 {
        u64::from(self.episode_steps())
    }

    fn check_genome(&self, genome: &Genome) -> std::result::Result<(), String> {
        crate::tasks::check_shape(genome, &MazeTask::spec(), "the maze")
    }

    fn describe(&self, maps: &[TrainingMap]) -> String {
        maps.first()
            .map(|m| m.loaded.scenario.source.clone())
            .unwrap_or_default()
    }

    /// Cells of [`CELL`] px over this maze's arena (the example's grid).
    fn fit_defaults(&self, config: &mut Config) {
        // The box starts at 0 px: its upper corner is its extent.
        let (_, upper) = self.bounds();
        StrategyConfig::fit(
            config,
            &TaskFacts {
                cell: Some(CELL),
                extent: &upper,
                ..TaskFacts::default()
            },
        );
    }

    fn has_target(&self) -> bool {
        true
    }

    fn reached_target(&self, evaluation: &Evaluation) -> bool {
        solved(evaluation)
    }

    fn generation_fields(&self, progress: &TargetProgress, evaluations: &[Evaluation]) -> String {
        let g = MazeGeneration::of(evaluations);
        format!(
            ",{},{},{}",
            g.best_distance, g.solvers, progress.evaluations
        )
    }

    fn header(&self, config: &Config, ctx: &HeaderContext<'_>) -> String {
        crate::tasks::maze::present::header(config, ctx)
    }

    fn summary(&self, finished: &Finished<'_>) -> Option<(String, String)> {
        Some(crate::tasks::maze::present::summary(self, finished))
    }

    fn replay_text(&self, genome: &Genome) -> Option<(String, String)> {
        Some(crate::tasks::maze::present::replay(self, genome))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(solved: bool, distance: f64) -> Evaluation {
        Evaluation {
            fitness: 300.0 - distance,
            metrics: vec![f64::from(u8::from(solved)), distance, 400.0],
            behaviour: vec![0.0, 0.0],
        }
    }

    #[test]
    fn the_robot_override_sets_the_maze_robot_model_and_names_the_models() {
        let mut o = crate::run::prepare::Overrides::default();
        o.set("task", NAME).unwrap();
        let mut c = Config::maze();
        assert_eq!(MazeConfig::of(&c).robot, MazeRobot::Lehman);
        o.set("robot", "vivae").unwrap();
        o.apply(&mut c).unwrap();
        assert_eq!(MazeConfig::of(&c).robot, MazeRobot::Vivae);
        o.set("robot", "khepera").unwrap();
        let e = o.apply(&mut c).unwrap_err();
        assert!(
            e.contains("khepera") && e.contains("lehman or vivae"),
            "{e}"
        );
    }

    #[test]
    fn evaluations_to_solve_count_up_to_the_first_solver() {
        let task = MazeTask::shipped(crate::tasks::maze::Maze::Hard).unwrap();
        let mut p = TargetProgress::default();
        let told = [eval(false, 50.0), eval(false, 40.0)];
        p.tell(&task, 1, &told);
        let g = MazeGeneration::of(&told);
        assert_eq!((g.best_distance, g.solvers, p.solved_at), (40.0, 0, None));
        assert_eq!(p.summary_fields(), " solved=no evals_to_solve=none");
        let told = [eval(false, 9.0), eval(true, 3.0), eval(true, 2.0)];
        p.tell(&task, 2, &told);
        let g = MazeGeneration::of(&told);
        assert_eq!((g.best_distance, g.solvers), (2.0, 2));
        assert_eq!(task.generation_fields(&p, &told), ",2,2,5");
        assert_eq!((p.solved_at, p.solved_generation), (Some(4), Some(2)));
        p.tell(&task, 3, &[eval(true, 1.0)]);
        assert_eq!((p.solved_at, p.evaluations), (Some(4), 6));
        assert_eq!(p.summary_fields(), " solved=yes evals_to_solve=4");
    }

    #[test]
    fn the_maze_defaults_validate_and_bad_combinations_are_refused() {
        let c = Config::maze();
        crate::tasks::check(&c).unwrap();
        let refused = |edit: &dyn Fn(&mut Config), key: &str| {
            let mut c = Config::maze();
            edit(&mut c);
            let e = crate::tasks::check(&c).unwrap_err().message;
            assert!(
                e.contains(key) && e.contains("maze") && !e.contains('\n'),
                "{e}"
            );
        };
        refused(
            &|c| c.experiment.scenarios = vec!["a".into(), "b".into()],
            "experiment.scenarios",
        );
        refused(&|c| c.experiment.scenario.clear(), "experiment.scenario");
        refused(&|c| c.experiment.robots = 5, "experiment.robots");
        refused(
            &|c| c.substrate.train_neurons = vec![c.substrate.neurons],
            "train_neurons",
        );
        refused(
            &|c| c.substrate.kind = crate::config::es::SubstrateKind::EsHyperneat,
            "substrate.kind",
        );
        refused(&|c| c.distance_sensors.rays = 5, "[distance_sensors]");
        refused(
            &|c| StrategyConfig::update(c, |s| s.behaviour = "side-speed".into()),
            "strategy.behaviour",
        );
        let mut c = Config::maze();
        StrategyConfig::update(&mut c, |s| {
            s.kind = "nsga2".into();
            s.nsga2.objectives = vec!["-contacts".into()];
        });
        let e = crate::tasks::check(&c).unwrap_err().message;
        assert!(e.contains("fitness or solved or distance or steps"), "{e}");
        StrategyConfig::update(&mut c, |s| {
            s.nsga2.objectives = vec!["fitness".into(), "-steps".into()];
        });
        crate::tasks::check(&c).unwrap();
        // A file that only says `task = "maze"` is the maze's defaults.
        let file =
            crate::tasks::config_from_toml("[experiment]\ntask = \"maze\"\nseed = 9\n").unwrap();
        assert_eq!(
            file,
            Config {
                experiment: crate::config::ExperimentConfig {
                    seed: 9,
                    ..Config::maze().experiment
                },
                ..Config::maze()
            }
        );
        assert_eq!(
            crate::tasks::config_from_toml(&Config::maze().to_toml()).unwrap(),
            Config::maze()
        );
    }

    #[test]
    fn map_elites_cells_are_ten_px_over_the_arena() {
        for (maze, bins) in [
            (crate::tasks::maze::Maze::Medium, [30, 14]),
            (crate::tasks::maze::Maze::Hard, [21, 21]),
        ] {
            let task = MazeTask::shipped(maze).unwrap();
            let mut c = Config::maze();
            task.fit_defaults(&mut c);
            assert_eq!(StrategyConfig::of(&c).map_elites.bins, bins);
        }
    }
}

//! The maze benchmark as a run of `vivae evolve` (`experiment.task = "maze"`):
//! its default settings (those of `cargo run --example maze`), the config
//! keys that do not fit it, and what a maze run records besides fitness.
//!
//! A maze run evolves plain NEAT networks ([`MazeTask::spec`]) on the one
//! maze named by `experiment.scenario`, with the robot of `[physics]` for
//! `experiment.steps` steps. It stops after the generation in which a
//! genome first reaches the goal, as the example does; `evals_to_solve`
//! counts the evaluations up to and including that genome.

use serde::{Deserialize, Serialize};
use vivae_neat::driver::Evaluation;
use vivae_sim::Scenario;

use crate::config::Config;
use crate::error::Result;
use crate::io::bad_input;
use crate::tasks::maze::MazeTask;

/// Side of MAP-Elites' grid cells over the maze, px (the example's).
pub const CELL: f64 = 10.0;

/// MAP-Elites bins of [`CELL`]-px cells over `task`'s arena (the example's grid).
pub fn cell_bins(task: &MazeTask) -> Vec<usize> {
    let (_, upper) = task.arena_bounds();
    upper.iter().map(|u| (u / CELL).ceil() as usize).collect()
}

/// The maze task of a maze run's `config` on `scenario`; bad input (naming
/// the scenario) when it is not a maze.
pub fn task(config: &Config, scenario: &Scenario) -> Result<MazeTask> {
    MazeTask::with_settings(scenario, &config.physics, config.experiment.steps)
        .map_err(|e| bad_input(e.to_string()))
}

/// What a maze run has measured so far, kept in its checkpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MazeProgress {
    /// Evaluations done so far.
    pub evaluations: u64,
    /// Evaluations up to and including the first genome that reached the goal.
    pub solved_at: Option<u64>,
    /// The run's generation (1-based) in which it did.
    pub solved_generation: Option<u32>,
}

/// One generation of a maze run: the fields it adds to `generations.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MazeGeneration {
    /// The smallest end distance to the goal in the generation, px.
    pub best_distance: f64,
    /// Genomes of the generation that reached the goal.
    pub solvers: usize,
}

/// The columns a maze run adds to `generations.csv`, with their leading comma.
pub const COLUMNS: &str = ",best_distance,solvers,evaluations";

impl MazeProgress {
    /// Counts the `evaluations` of `generation` (as the example counts:
    /// the first solver's evaluation is the `i + 1`-th of its batch).
    pub fn tell(&mut self, generation: u32, evaluations: &[Evaluation]) -> MazeGeneration {
        let solved = |e: &Evaluation| e.metrics.first() == Some(&1.0);
        if self.solved_at.is_none()
            && let Some(i) = evaluations.iter().position(solved)
        {
            self.solved_at = Some(self.evaluations + i as u64 + 1);
            self.solved_generation = Some(generation);
        }
        self.evaluations += evaluations.len() as u64;
        let distances = evaluations.iter().filter_map(|e| e.metrics.get(1));
        MazeGeneration {
            best_distance: distances.copied().fold(f64::INFINITY, f64::min),
            solvers: evaluations.iter().filter(|e| solved(e)).count(),
        }
    }

    /// The fields of [`COLUMNS`] for `generation`, with their leading commas.
    pub fn fields(&self, generation: &MazeGeneration) -> String {
        format!(
            ",{},{},{}",
            generation.best_distance, generation.solvers, self.evaluations
        )
    }

    /// `solved=yes|no evals_to_solve=N|none` for the summary line, with a leading space.
    pub fn summary_fields(&self) -> String {
        match self.solved_at {
            Some(n) => format!(" solved=yes evals_to_solve={n}"),
            None => " solved=no evals_to_solve=none".into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::strategy::BehaviourKind;

    fn eval(solved: bool, distance: f64) -> Evaluation {
        Evaluation {
            fitness: 300.0 - distance,
            metrics: vec![f64::from(u8::from(solved)), distance, 400.0],
            behaviour: vec![0.0, 0.0],
        }
    }

    #[test]
    fn evaluations_to_solve_count_up_to_the_first_solver() {
        let mut p = MazeProgress::default();
        let g = p.tell(1, &[eval(false, 50.0), eval(false, 40.0)]);
        assert_eq!((g.best_distance, g.solvers, p.solved_at), (40.0, 0, None));
        assert_eq!(p.summary_fields(), " solved=no evals_to_solve=none");
        let g = p.tell(2, &[eval(false, 9.0), eval(true, 3.0), eval(true, 2.0)]);
        assert_eq!((g.best_distance, g.solvers), (2.0, 2));
        assert_eq!((p.solved_at, p.solved_generation), (Some(4), Some(2)));
        p.tell(3, &[eval(true, 1.0)]);
        assert_eq!((p.solved_at, p.evaluations), (Some(4), 6));
        assert_eq!(p.summary_fields(), " solved=yes evals_to_solve=4");
    }

    #[test]
    fn the_maze_defaults_validate_and_bad_combinations_are_refused() {
        let c = Config::maze();
        c.validate().unwrap();
        let refused = |edit: &dyn Fn(&mut Config), key: &str| {
            let mut c = Config::maze();
            edit(&mut c);
            let e = c.validate().unwrap_err().message;
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
            &|c| c.strategy.behaviour = BehaviourKind::SideSpeed,
            "strategy.behaviour",
        );
        let mut c = Config::maze();
        c.strategy.kind = crate::config::strategy::StrategyKind::Nsga2;
        c.strategy.nsga2.objectives = vec!["-contacts".into()];
        let e = c.validate().unwrap_err().message;
        assert!(e.contains("fitness or solved or distance or steps"), "{e}");
        c.strategy.nsga2.objectives = vec!["fitness".into(), "-steps".into()];
        c.validate().unwrap();
        // A file that only says `task = "maze"` is the maze's defaults.
        let file = Config::from_toml("[experiment]\ntask = \"maze\"\nseed = 9\n").unwrap();
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
            Config::from_toml(&Config::maze().to_toml()).unwrap(),
            Config::maze()
        );
    }

    #[test]
    fn map_elites_cells_are_ten_px_over_the_arena() {
        let task = MazeTask::shipped(crate::tasks::maze::Maze::Medium).unwrap();
        assert_eq!(cell_bins(&task), [30, 14]);
        let task = MazeTask::shipped(crate::tasks::maze::Maze::Hard).unwrap();
        assert_eq!(cell_bins(&task), [21, 21]);
    }
}

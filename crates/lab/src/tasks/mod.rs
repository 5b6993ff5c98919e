//! What a run evaluates genomes on, by `experiment.task`: the driving
//! experiment ([`Training`]: CPPNs decoded into substrates) or the maze
//! ([`MazeTask`]: plain networks).

pub mod driving;
pub mod maps;
pub mod maze;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome, GenomeSpec};

use crate::config::{Config, TaskKind};
use crate::error::Result;
use crate::tasks::driving::training::Training;
use crate::tasks::maps::TrainingMap;
use crate::tasks::maze::MazeTask;

/// A run's task.
#[derive(Debug, Clone)]
pub enum RunTask {
    /// Robots driving on roads (boxed: a training is large).
    Driving(Box<Training>),
    /// The maze benchmark (boxed too: both are large).
    Maze(Box<MazeTask>),
}

impl RunTask {
    /// The task of `config` on `maps` (from [`crate::tasks::maps::load`]; a maze run has one).
    pub fn new(config: &Config, maps: &[TrainingMap]) -> Result<RunTask> {
        match config.experiment.task {
            TaskKind::Driving => Ok(RunTask::Driving(Box::new(Training::new(config, maps)?))),
            TaskKind::Maze => {
                let map = maps
                    .first()
                    .ok_or_else(|| crate::io::bad_input("no maze"))?;
                crate::tasks::maze::run::task(config, &map.loaded.scenario)
                    .map(|m| RunTask::Maze(Box::new(m)))
            }
        }
    }

    /// The shape of the genomes the run evolves.
    pub fn genome_spec(&self) -> GenomeSpec {
        match self {
            RunTask::Driving(t) => t.primary().cppn_spec(),
            RunTask::Maze(_) => MazeTask::spec(),
        }
    }

    /// The box the behaviour descriptors of `config`'s strategy lie in
    /// (MAP-Elites' cells cover it).
    pub fn behaviour_bounds(&self, config: &Config) -> (Vec<f64>, Vec<f64>) {
        match self {
            RunTask::Driving(t) => config.strategy.behaviour.bounds(t.primary().robots()),
            RunTask::Maze(m) => m.arena_bounds(),
        }
    }

    /// Robot-steps one evaluation simulates at most.
    pub fn robot_steps(&self) -> u64 {
        match self {
            RunTask::Driving(t) => t.robot_steps(),
            RunTask::Maze(m) => u64::from(m.steps()),
        }
    }

    /// Why `genome` does not fit the task, if it does not.
    pub fn check_genome(&self, genome: &Genome) -> Result<(), String> {
        match self {
            RunTask::Driving(t) => {
                (t.primary().robot_controller(genome).map(drop)).map_err(|e| e.to_string())
            }
            RunTask::Maze(_) => {
                let want = MazeTask::spec();
                let (inputs, outputs) = (genome.num_inputs(), genome.num_outputs());
                if (inputs, outputs) == (want.inputs, want.outputs) {
                    Ok(())
                } else {
                    Err(format!(
                        "network has {inputs} inputs and {outputs} outputs, the maze needs {} and {}",
                        want.inputs, want.outputs
                    ))
                }
            }
        }
    }

    /// The driving experiment's training, if this is the driving task.
    pub fn training(&self) -> Option<&Training> {
        match self {
            RunTask::Driving(t) => Some(t.as_ref()),
            RunTask::Maze(_) => None,
        }
    }

    /// The maze, if this is the maze task.
    pub fn maze(&self) -> Option<&MazeTask> {
        match self {
            RunTask::Driving(_) => None,
            RunTask::Maze(m) => Some(m.as_ref()),
        }
    }
}

impl Task for RunTask {
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        match self {
            RunTask::Driving(t) => t.evaluate(genome, ctx),
            RunTask::Maze(m) => m.evaluate(genome, ctx),
        }
    }

    fn metric_names(&self) -> &[&str] {
        match self {
            RunTask::Driving(t) => t.metric_names(),
            RunTask::Maze(m) => m.metric_names(),
        }
    }
}

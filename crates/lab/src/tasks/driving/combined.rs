//! Tasks of the driving experiment, and how they combine.
//!
//! One episode (one map, one substrate resolution, one fitness function) is
//! a task: [`Episode`](crate::tasks::driving::episode::Episode). [`Combined`] scores
//! several tasks as one ("the mean over maps", "the worst over
//! resolutions"), and is itself a task, so combinations nest.
//!
//! ```
//! use vivae_lab::config::{Aggregate, Config};
//! use vivae_lab::tasks::driving::episode::Episode;
//! use vivae_lab::tasks::driving::combined::{Combined, DrivingTask};
//! use vivae_neat::{driver::Task, EvalContext, Population};
//!
//! let scenario = vivae_lab::tasks::scenarios::load_scenario(None)?.scenario;
//! let mut short = Config::default();
//! short.experiment.steps = 100;
//! let mut long = short.clone();
//! long.experiment.steps = 300;
//! let both = Combined::new(
//!     vec![
//!         ("100 steps".into(), Box::new(Episode::new(&short, &scenario)?) as Box<dyn DrivingTask>),
//!         ("300 steps".into(), Box::new(Episode::new(&long, &scenario)?)),
//!     ],
//!     Aggregate::Min,
//! );
//! assert_eq!(both.robot_steps(), 5 * 100 + 5 * 300);
//! let population = Population::new(short.neat.clone(), both.parts()[0].1.cppn_spec(), 1)?;
//! let ctx = EvalContext { generation: 1, index: 0, seed: 0 };
//! let genome = &population.genomes()[0];
//! let parts = both.fitnesses(genome, &ctx);
//! assert_eq!(both.evaluate(genome, &ctx).fitness, parts[0].min(parts[1]));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome, GenomeSpec};

use crate::config::Aggregate;
use crate::tasks::driving::descriptors::mean_of;

/// A task of the driving experiment: a NEAT [`Task`] over CPPN genomes that
/// also says how much it simulates.
pub trait DrivingTask: Task + Send + fmt::Debug {
    /// Robot-steps one evaluation simulates.
    fn robot_steps(&self) -> u64;

    /// The shape of the CPPN genomes the task evaluates.
    fn cppn_spec(&self) -> GenomeSpec;
}

/// Several tasks scored as one: each part's fitness, combined by an [`Aggregate`].
#[derive(Debug)]
pub struct Combined {
    parts: Vec<(String, Box<dyn DrivingTask>)>,
    aggregate: Aggregate,
}

impl Combined {
    /// The tasks `parts` (label, task), in evaluation order, combined by `aggregate`.
    pub fn new(parts: Vec<(String, Box<dyn DrivingTask>)>, aggregate: Aggregate) -> Combined {
        Combined { parts, aggregate }
    }

    /// The parts, in evaluation order.
    pub fn parts(&self) -> &[(String, Box<dyn DrivingTask>)] {
        &self.parts
    }

    /// Labels of the parts, in evaluation order.
    pub fn labels(&self) -> impl Iterator<Item = &str> {
        self.parts.iter().map(|(l, _)| l.as_str())
    }

    /// How the parts' fitnesses combine.
    pub fn aggregate(&self) -> Aggregate {
        self.aggregate
    }

    /// Every part's fitness for `genome`, in evaluation order.
    pub fn fitnesses(&self, genome: &Genome, ctx: &EvalContext) -> Vec<f64> {
        self.parts
            .iter()
            .map(|(_, t)| t.evaluate(genome, ctx).fitness)
            .collect()
    }
}

/// The parts' fitnesses combine by the aggregate; their behaviours and
/// metrics (when measured) by the mean, coordinate by coordinate
/// ([`crate::tasks::driving::descriptors`]).
impl Task for Combined {
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        let parts: Vec<Evaluation> = (self.parts.iter())
            .map(|(_, t)| t.evaluate(genome, ctx))
            .collect();
        let fitnesses: Vec<f64> = parts.iter().map(|e| e.fitness).collect();
        let behaviours: Vec<&[f64]> = parts.iter().map(|e| &e.behaviour[..]).collect();
        let metrics: Vec<&[f64]> = parts.iter().map(|e| &e.metrics[..]).collect();
        Evaluation {
            fitness: self.aggregate.combine(&fitnesses),
            metrics: mean_of(&metrics),
            behaviour: mean_of(&behaviours),
        }
    }

    fn metric_names(&self) -> &[&str] {
        self.parts.first().map_or(&[], |(_, t)| t.metric_names())
    }

    fn context_free(&self) -> bool {
        self.parts.iter().all(|(_, t)| t.context_free())
    }
}

impl DrivingTask for Combined {
    fn robot_steps(&self) -> u64 {
        self.parts.iter().map(|(_, t)| t.robot_steps()).sum()
    }

    fn cppn_spec(&self) -> GenomeSpec {
        self.parts
            .first()
            .map_or_else(GenomeSpec::cppn, |(_, t)| t.cppn_spec())
    }
}

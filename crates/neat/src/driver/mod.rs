//! The evolution driver: runs generations of a [`Population`] on an
//! [`Evaluator`] until a stop criterion holds, telling [`Observer`]s and a
//! [`Checkpointer`] as it goes, and returns why it stopped as data.
//!
//! The driver does no I/O: result files, progress bars and checkpoint files
//! are observer and checkpointer implementations that live with the program.

mod observer;
mod stop;
mod task;

use std::sync::atomic::Ordering;

pub use observer::{
    CheckpointState, Checkpointer, GenerationReport, HookError, NoCheckpoints, Observer,
};
pub use stop::{StopCriteria, StopReason};
pub use task::{Evaluation, Evaluator, EvaluatorError, ParallelEvaluator, Task};

use crate::error::NeatError;
use crate::eval::EvalContext;
use crate::population::Population;

/// Why a run could not go on.
#[derive(Debug, thiserror::Error)]
pub enum DriverError {
    /// The evaluator failed.
    #[error("evaluation: {0}")]
    Evaluation(#[from] EvaluatorError),
    /// An observer or the checkpointer failed.
    #[error("{0}")]
    Hook(HookError),
    /// The population refused the evaluations.
    #[error(transparent)]
    Neat(#[from] NeatError),
}

/// An observer and a checkpointer seen as one set of hooks.
struct Pair<'a, 'b>(&'a mut dyn Observer, &'b mut dyn Checkpointer);

impl Observer for Pair<'_, '_> {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        self.0.on_generation(report)
    }
}

impl Checkpointer for Pair<'_, '_> {
    fn after_generation(&mut self, state: &CheckpointState<'_>) -> Result<(), HookError> {
        self.1.after_generation(state)
    }
}

/// A population evolving on an evaluator.
pub struct Evolution<E> {
    population: Population,
    evaluator: E,
    done: u32,
    /// Best fitness of the generation evaluated last.
    last_best: Option<f64>,
}

impl<E: Evaluator> Evolution<E> {
    /// Starts a run of `population` (generation counting from 0 done).
    pub fn new(population: Population, evaluator: E) -> Self {
        Evolution::resume(population, evaluator, 0)
    }

    /// Continues a run of which `done` generations are already done (e.g. from a checkpoint).
    pub fn resume(population: Population, evaluator: E, done: u32) -> Self {
        Evolution {
            population,
            evaluator,
            done,
            last_best: None,
        }
    }

    /// Generations of this run done so far.
    pub fn generations_done(&self) -> u32 {
        self.done
    }

    /// The population (ready to evaluate the next generation between runs).
    pub fn population(&self) -> &Population {
        &self.population
    }

    /// The evaluator.
    pub fn evaluator(&self) -> &E {
        &self.evaluator
    }

    /// Gives the population back.
    pub fn into_population(self) -> Population {
        self.population
    }

    /// The stop reason that already holds before any generation is run, if any.
    pub fn already_stopped(&self, stop: &StopCriteria<'_>) -> Option<StopReason> {
        stop.generations
            .filter(|&n| self.done >= n)
            .map(StopReason::Generations)
    }

    /// Runs generations until a criterion of `stop` holds; observers hear of
    /// each evaluated generation, the checkpointer of each bred one.
    pub fn run(
        &mut self,
        stop: &StopCriteria<'_>,
        observer: &mut dyn Observer,
        checkpointer: &mut dyn Checkpointer,
    ) -> Result<StopReason, DriverError> {
        self.run_with(stop, &mut Pair(observer, checkpointer))
    }

    /// [`Evolution::run`] with one value that is both observer and checkpointer
    /// (e.g. a run directory whose checkpoints record how far its files got).
    pub fn run_with<H: Observer + Checkpointer + ?Sized>(
        &mut self,
        stop: &StopCriteria<'_>,
        hooks: &mut H,
    ) -> Result<StopReason, DriverError> {
        if let Some(reason) = self.already_stopped(stop) {
            return Ok(reason);
        }
        loop {
            self.evaluate_generation(hooks)?;
            let reason = self.stop_reason(stop);
            hooks
                .after_generation(&CheckpointState {
                    generations_done: self.done,
                    population: &self.population,
                    stopping: reason.as_ref(),
                })
                .map_err(DriverError::Hook)?;
            if let Some(reason) = reason {
                return Ok(reason);
            }
        }
    }

    /// Evaluates one generation, tells `observer`, breeds the next.
    fn evaluate_generation<O: Observer + ?Sized>(
        &mut self,
        observer: &mut O,
    ) -> Result<(), DriverError> {
        let contexts: Vec<EvalContext> = (0..self.population.genomes().len())
            .map(|i| self.population.eval_context(i))
            .collect();
        let evaluations = self
            .evaluator
            .evaluate(self.population.genomes(), &contexts)?;
        if evaluations.len() != contexts.len() {
            return Err(EvaluatorError(format!(
                "the evaluator returned {} evaluations for {} genomes",
                evaluations.len(),
                contexts.len()
            ))
            .into());
        }
        self.population
            .set_fitnesses(evaluations.iter().map(|e| e.fitness).collect())?;
        let stats = self.population.stats();
        observer
            .on_generation(&GenerationReport {
                generation: self.done + 1,
                population: &self.population,
                evaluations: &evaluations,
                stats: &stats,
            })
            .map_err(DriverError::Hook)?;
        self.last_best = stats.best_fitness;
        self.population.next_generation();
        self.done += 1;
        Ok(())
    }

    /// The criterion of `stop` that holds after the generation just bred, if any.
    fn stop_reason(&self, stop: &StopCriteria<'_>) -> Option<StopReason> {
        if let Some(reason) = self.already_stopped(stop) {
            return Some(reason);
        }
        if let (Some(target), Some(best)) = (stop.target_fitness, self.last_best)
            && best >= target
        {
            return Some(StopReason::TargetFitness {
                fitness: best,
                generation: self.done,
            });
        }
        if let (Some(n), Some(best)) = (stop.stagnation, self.population.best_ever()) {
            // The population now holds the next, unevaluated generation.
            let since = self
                .population
                .generation()
                .saturating_sub(best.generation + 1);
            if since >= n {
                return Some(StopReason::Stagnation(since));
            }
        }
        if stop.interrupt.is_some_and(|f| f.load(Ordering::SeqCst)) {
            return Some(StopReason::Interrupted);
        }
        None
    }
}

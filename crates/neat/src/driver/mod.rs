//! The evolution driver: runs generations of a search [`Strategy`] (NEAT's
//! [`Population`], or any other) on an [`Evaluator`] until a stop criterion
//! holds, telling [`Observer`]s and a [`Checkpointer`] as it goes, and
//! returns why it stopped as data.
//!
//! One generation is: [`Strategy::ask`] for a batch, evaluate it, [`Strategy::tell`]
//! the evaluations, tell the observers, [`Strategy::prepare`] the next batch,
//! check the stop criteria, tell the checkpointer. [`strategy`] shows a
//! strategy of a dozen lines run by the same driver.
//!
//! The driver does no I/O: result files, progress bars and checkpoint files
//! are observer and checkpointer implementations that live with the program.

mod grouped;
mod observer;
mod reuse;
mod stop;
pub mod strategy;
mod task;

use std::sync::atomic::Ordering;

pub use grouped::{GroupTask, GroupedEvaluator};
pub use observer::{
    CheckpointState, Checkpointer, GenerationReport, HookError, NoCheckpoints, Observer,
};
pub use reuse::Reusing;
pub use stop::{StopCriteria, StopReason};
pub use strategy::{Batch, Strategy};
pub(crate) use task::finite_or_zero;
pub use task::{Evaluation, Evaluator, EvaluatorError, ParallelEvaluator, Task};

use crate::error::NeatError;
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
    /// The strategy refused the evaluations.
    #[error(transparent)]
    Neat(#[from] NeatError),
}

/// An observer and a checkpointer seen as one set of hooks.
struct Pair<'a, 'b, S>(&'a mut dyn Observer<S>, &'b mut dyn Checkpointer<S>);

impl<S> Observer<S> for Pair<'_, '_, S> {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        self.0.on_generation(report)
    }
}

impl<S> Checkpointer<S> for Pair<'_, '_, S> {
    fn after_generation(&mut self, state: &CheckpointState<'_, S>) -> Result<(), HookError> {
        self.1.after_generation(state)
    }
}

/// What the stop criteria need of the generation just told.
struct Told {
    /// Best fitness of the batch.
    best: Option<f64>,
    /// Generations since the best-ever genome was found.
    since_best: Option<u32>,
}

/// A strategy (by default a NEAT [`Population`]) evolving on an evaluator.
pub struct Evolution<S, E> {
    strategy: S,
    evaluator: E,
    done: u32,
}

impl<S: Strategy, E: Evaluator> Evolution<S, E> {
    /// Starts a run of `strategy` (generation counting from 0 done).
    pub fn new(strategy: S, evaluator: E) -> Self {
        Evolution::resume(strategy, evaluator, 0)
    }

    /// Continues a run of which `done` generations are already done (e.g. from a checkpoint).
    pub fn resume(strategy: S, evaluator: E, done: u32) -> Self {
        Evolution {
            strategy,
            evaluator,
            done,
        }
    }

    /// Generations of this run done so far.
    pub fn generations_done(&self) -> u32 {
        self.done
    }

    /// The strategy (ready to evaluate the next generation between runs).
    pub fn strategy(&self) -> &S {
        &self.strategy
    }

    /// The evaluator.
    pub fn evaluator(&self) -> &E {
        &self.evaluator
    }

    /// Gives the strategy back.
    pub fn into_strategy(self) -> S {
        self.strategy
    }

    /// The stop reason that already holds before any generation is run, if any.
    pub fn already_stopped(&self, stop: &StopCriteria<'_>) -> Option<StopReason> {
        stop.generations
            .filter(|&n| self.done >= n)
            .map(StopReason::Generations)
    }

    /// Runs generations until a criterion of `stop` holds; observers hear of
    /// each evaluated generation, the checkpointer of each prepared one.
    pub fn run(
        &mut self,
        stop: &StopCriteria<'_>,
        observer: &mut dyn Observer<S>,
        checkpointer: &mut dyn Checkpointer<S>,
    ) -> Result<StopReason, DriverError> {
        self.run_with(stop, &mut Pair(observer, checkpointer))
    }

    /// [`Evolution::run`] with one value that is both observer and checkpointer
    /// (e.g. a run directory whose checkpoints record how far its files got).
    pub fn run_with<H: Observer<S> + Checkpointer<S> + ?Sized>(
        &mut self,
        stop: &StopCriteria<'_>,
        hooks: &mut H,
    ) -> Result<StopReason, DriverError> {
        if let Some(reason) = self.already_stopped(stop) {
            return Ok(reason);
        }
        loop {
            let told = self.evaluate_generation(hooks)?;
            self.strategy.prepare();
            let reason = self.stop_reason(stop, &told);
            hooks
                .after_generation(&CheckpointState {
                    generations_done: self.done,
                    strategy: &self.strategy,
                    stopping: reason.as_ref(),
                })
                .map_err(DriverError::Hook)?;
            if let Some(reason) = reason {
                return Ok(reason);
            }
        }
    }

    /// Asks for a generation, evaluates it, tells the strategy and `observer`.
    fn evaluate_generation<O: Observer<S> + ?Sized>(
        &mut self,
        observer: &mut O,
    ) -> Result<Told, DriverError> {
        let batch = self.strategy.ask();
        let evaluations = self.evaluator.evaluate(batch.genomes, &batch.contexts)?;
        EvaluatorError::unless_one_evaluation_each(&evaluations, batch.contexts.len())?;
        self.strategy.tell(&evaluations)?;
        let stats = self.strategy.stats();
        observer
            .on_generation(&GenerationReport {
                generation: self.done + 1,
                strategy: &self.strategy,
                evaluations: &evaluations,
                reused: self.evaluator.reused(),
                stats: &stats,
            })
            .map_err(DriverError::Hook)?;
        self.done += 1;
        let generation = self.strategy.generation();
        Ok(Told {
            best: self.strategy.champion().map(|(_, fitness)| fitness),
            since_best: (self.strategy.best_ever())
                .map(|b| generation.saturating_sub(b.generation)),
        })
    }

    /// The criterion of `stop` that holds after the generation just told, if any.
    fn stop_reason(&self, stop: &StopCriteria<'_>, told: &Told) -> Option<StopReason> {
        if let Some(reason) = self.already_stopped(stop) {
            return Some(reason);
        }
        if let (Some(target), Some(best)) = (stop.target_fitness, told.best)
            && best >= target
        {
            return Some(StopReason::TargetFitness {
                fitness: best,
                generation: self.done,
            });
        }
        if let (Some(n), Some(since)) = (stop.stagnation, told.since_best)
            && since >= n
        {
            return Some(StopReason::Stagnation(since));
        }
        if stop.interrupt.is_some_and(|f| f.load(Ordering::SeqCst)) {
            return Some(StopReason::Interrupted);
        }
        None
    }
}

impl<E: Evaluator> Evolution<Population, E> {
    /// The population (ready to evaluate the next generation between runs).
    pub fn population(&self) -> &Population {
        &self.strategy
    }

    /// Gives the population back.
    pub fn into_population(self) -> Population {
        self.strategy
    }
}

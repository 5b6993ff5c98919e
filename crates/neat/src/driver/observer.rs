//! Per-generation hooks: [`Observer`]s report, a [`Checkpointer`] saves state.
//!
//! Both are generic over the [`Strategy`](super::Strategy) being run, with
//! NEAT's [`Population`] as the default: `impl Observer for X` observes NEAT
//! runs, `impl<S: Strategy> Observer<S> for X` observes any run.

use std::fmt;

use super::stop::StopReason;
use super::task::Evaluation;
use crate::population::{GenerationStats, Population};

/// An error raised by an observer or a checkpointer (e.g. a file that could not be written).
pub type HookError = Box<dyn std::error::Error + Send + Sync>;

/// What observers are told after a generation has been evaluated.
pub struct GenerationReport<'a, S: ?Sized = Population> {
    /// Generation of this run, 1-based.
    pub generation: u32,
    /// The strategy, told and not yet prepared (for NEAT: fitnesses,
    /// champion and best-ever are set, the next generation is not bred).
    pub strategy: &'a S,
    /// One evaluation per genome, in batch order.
    pub evaluations: &'a [Evaluation],
    /// Indices of the batch whose evaluations were copied from an equal
    /// genome's instead of run ([`Reusing`](super::Reusing)).
    pub reused: &'a [usize],
    /// Statistics of the evaluated generation.
    pub stats: &'a GenerationStats,
}

impl<S: ?Sized> Clone for GenerationReport<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ?Sized> Copy for GenerationReport<'_, S> {}

impl<S: ?Sized + fmt::Debug> fmt::Debug for GenerationReport<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GenerationReport")
            .field("generation", &self.generation)
            .field("strategy", &self.strategy)
            .field("evaluations", &self.evaluations)
            .field("reused", &self.reused)
            .field("stats", &self.stats)
            .finish()
    }
}

/// Is told about every evaluated generation (progress bars, logs, result files).
pub trait Observer<S: ?Sized = Population> {
    /// Called after each generation's evaluation, before the next one is prepared.
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError>;
}

impl<S: ?Sized, O: Observer<S> + ?Sized> Observer<S> for &mut O {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        (**self).on_generation(report)
    }
}

impl<S: ?Sized, O: Observer<S> + ?Sized> Observer<S> for Box<O> {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        (**self).on_generation(report)
    }
}

impl<S: ?Sized, O: Observer<S>> Observer<S> for Vec<O> {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        self.iter_mut().try_for_each(|o| o.on_generation(report))
    }
}

impl<S: ?Sized, A: Observer<S>, B: Observer<S>> Observer<S> for (A, B) {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        self.0.on_generation(report)?;
        self.1.on_generation(report)
    }
}

impl<S: ?Sized> Observer<S> for () {
    fn on_generation(&mut self, _: &GenerationReport<'_, S>) -> Result<(), HookError> {
        Ok(())
    }
}

/// What a checkpointer is given once the next generation is prepared.
pub struct CheckpointState<'a, S: ?Sized = Population> {
    /// Generations of this run done so far.
    pub generations_done: u32,
    /// The strategy, ready to evaluate the next generation: restoring it
    /// and continuing gives exactly the run that would have followed.
    pub strategy: &'a S,
    /// Why the run stops now, if it does (a checkpointer should then save).
    pub stopping: Option<&'a StopReason>,
}

impl<S: ?Sized> Clone for CheckpointState<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ?Sized> Copy for CheckpointState<'_, S> {}

impl<S: ?Sized + fmt::Debug> fmt::Debug for CheckpointState<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CheckpointState")
            .field("generations_done", &self.generations_done)
            .field("strategy", &self.strategy)
            .field("stopping", &self.stopping)
            .finish()
    }
}

/// Saves the state of a run so that it can continue after a crash.
///
/// It decides its own cadence; a run that stops always tells it (`stopping`).
pub trait Checkpointer<S: ?Sized = Population> {
    /// Called after every generation, once the next one is prepared.
    fn after_generation(&mut self, state: &CheckpointState<'_, S>) -> Result<(), HookError>;
}

impl<S: ?Sized, C: Checkpointer<S> + ?Sized> Checkpointer<S> for &mut C {
    fn after_generation(&mut self, state: &CheckpointState<'_, S>) -> Result<(), HookError> {
        (**self).after_generation(state)
    }
}

impl<S: ?Sized, C: Checkpointer<S> + ?Sized> Checkpointer<S> for Box<C> {
    fn after_generation(&mut self, state: &CheckpointState<'_, S>) -> Result<(), HookError> {
        (**self).after_generation(state)
    }
}

/// A checkpointer that saves nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCheckpoints;

impl<S: ?Sized> Checkpointer<S> for NoCheckpoints {
    fn after_generation(&mut self, _: &CheckpointState<'_, S>) -> Result<(), HookError> {
        Ok(())
    }
}

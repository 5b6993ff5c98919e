//! Per-generation hooks: [`Observer`]s report, a [`Checkpointer`] saves state.

use super::stop::StopReason;
use super::task::Evaluation;
use crate::population::{GenerationStats, Population};

/// An error raised by an observer or a checkpointer (e.g. a file that could not be written).
pub type HookError = Box<dyn std::error::Error + Send + Sync>;

/// What observers are told after a generation has been evaluated.
#[derive(Debug, Clone, Copy)]
pub struct GenerationReport<'a> {
    /// Generation of this run, 1-based.
    pub generation: u32,
    /// The population, evaluated and not yet bred (fitnesses, champion, best-ever are set).
    pub population: &'a Population,
    /// One evaluation per genome, in population order.
    pub evaluations: &'a [Evaluation],
    /// Statistics of the evaluated generation.
    pub stats: &'a GenerationStats,
}

/// Is told about every evaluated generation (progress bars, logs, result files).
pub trait Observer {
    /// Called after each generation's evaluation, before the next one is bred.
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError>;
}

impl<O: Observer + ?Sized> Observer for &mut O {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        (**self).on_generation(report)
    }
}

impl<O: Observer + ?Sized> Observer for Box<O> {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        (**self).on_generation(report)
    }
}

impl<O: Observer> Observer for Vec<O> {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        self.iter_mut().try_for_each(|o| o.on_generation(report))
    }
}

impl<A: Observer, B: Observer> Observer for (A, B) {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        self.0.on_generation(report)?;
        self.1.on_generation(report)
    }
}

impl Observer for () {
    fn on_generation(&mut self, _: &GenerationReport<'_>) -> Result<(), HookError> {
        Ok(())
    }
}

/// What a checkpointer is given once a generation is bred.
#[derive(Debug, Clone, Copy)]
pub struct CheckpointState<'a> {
    /// Generations of this run done so far.
    pub generations_done: u32,
    /// The population, ready to evaluate the next generation: restoring it
    /// and continuing gives exactly the run that would have followed.
    pub population: &'a Population,
    /// Why the run stops now, if it does (a checkpointer should then save).
    pub stopping: Option<&'a StopReason>,
}

/// Saves the state of a run so that it can continue after a crash.
///
/// It decides its own cadence; a run that stops always tells it (`stopping`).
pub trait Checkpointer {
    /// Called after every generation, once the next population is bred.
    fn after_generation(&mut self, state: &CheckpointState<'_>) -> Result<(), HookError>;
}

impl<C: Checkpointer + ?Sized> Checkpointer for &mut C {
    fn after_generation(&mut self, state: &CheckpointState<'_>) -> Result<(), HookError> {
        (**self).after_generation(state)
    }
}

/// A checkpointer that saves nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCheckpoints;

impl Checkpointer for NoCheckpoints {
    fn after_generation(&mut self, _: &CheckpointState<'_>) -> Result<(), HookError> {
        Ok(())
    }
}

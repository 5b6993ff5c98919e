//! What is evaluated: a [`Task`] scores one genome, an [`Evaluator`] a whole generation.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::eval::EvalContext;
use crate::genome::Genome;

/// The result of evaluating one genome: its fitness and anything else the task measured.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Evaluation {
    /// The fitness NEAT selects on (higher is better; non-finite counts as 0).
    pub fitness: f64,
    /// Further measurements, in the order of [`Task::metric_names`].
    pub metrics: Vec<f64>,
    /// A behaviour descriptor (e.g. for novelty search); empty when the task has none.
    pub behaviour: Vec<f64>,
}

impl Evaluation {
    /// An evaluation that holds only a fitness.
    pub fn fitness(fitness: f64) -> Evaluation {
        Evaluation {
            fitness,
            ..Evaluation::default()
        }
    }

    /// The fitness a strategy selects on: non-finite counts as 0.
    pub fn finite_fitness(&self) -> f64 {
        finite_or_zero(self.fitness)
    }
}

/// `x`, or 0 when it is not finite: how the driver reads a non-finite
/// fitness or behaviour coordinate.
pub(crate) fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

/// A problem genomes are evaluated on.
///
/// `evaluate` must be deterministic given the genome and the context: any
/// randomness comes from `ctx.seed`, which depends only on (run seed,
/// generation, index), so results never depend on scheduling or thread count.
/// Every `Fn(&Genome, &EvalContext) -> f64 + Sync` closure is a task.
pub trait Task: Sync {
    /// Scores one genome.
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation;

    /// Names of the extra metrics each [`Evaluation`] carries (none by default).
    fn metric_names(&self) -> &[&str] {
        &[]
    }

    /// Whether `evaluate` ignores its context, so that equal genomes always
    /// get equal evaluations and a [`Reusing`](super::Reusing) evaluator may
    /// run each genome once (false by default).
    fn context_free(&self) -> bool {
        false
    }
}

impl<F> Task for F
where
    F: Fn(&Genome, &EvalContext) -> f64 + Sync,
{
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        Evaluation::fitness(self(genome, ctx))
    }
}

/// Evaluates a whole generation: the seam where evaluation can be spread over
/// threads, processes or machines.
///
/// An implementation must return one evaluation per genome, in order, equal
/// to what `Task::evaluate` gives for `(genomes[i], contexts[i])`.
pub trait Evaluator {
    /// Evaluates `genomes[i]` in `contexts[i]` for every `i`.
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError>;

    /// Indices of the last batch whose evaluations were reused from an equal
    /// genome's instead of run (none unless the evaluator reuses).
    fn reused(&self) -> &[usize] {
        &[]
    }
}

/// Why a generation could not be evaluated (e.g. a worker process was lost).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct EvaluatorError(pub String);

impl EvaluatorError {
    /// The error an evaluator's caller gives unless it got one evaluation per genome.
    pub fn unless_one_evaluation_each(
        evaluations: &[Evaluation],
        genomes: usize,
    ) -> Result<(), EvaluatorError> {
        if evaluations.len() == genomes {
            return Ok(());
        }
        Err(EvaluatorError(format!(
            "the evaluator returned {} evaluations for {genomes} genomes",
            evaluations.len()
        )))
    }

    /// The error every [`Evaluator`] gives unless there is one context per genome.
    pub fn unless_one_context_each(
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<(), EvaluatorError> {
        if genomes.len() == contexts.len() {
            return Ok(());
        }
        Err(EvaluatorError(format!(
            "{} genomes but {} evaluation contexts",
            genomes.len(),
            contexts.len()
        )))
    }
}

/// `run` on the threads of `pool`, or of rayon's global pool.
pub(super) fn on_pool<R: Send>(
    pool: Option<&rayon::ThreadPool>,
    run: impl FnOnce() -> R + Send,
) -> R {
    match pool {
        Some(pool) => pool.install(run),
        None => run(),
    }
}

/// Evaluates a [`Task`] on the rayon threads of `pool` (or of the global pool).
///
/// Results are collected by index, so they are identical at any thread count.
pub struct ParallelEvaluator<'p, T> {
    task: T,
    pool: Option<&'p rayon::ThreadPool>,
}

impl<T: Task> ParallelEvaluator<'static, T> {
    /// Evaluates `task` on rayon's global thread pool.
    pub fn new(task: T) -> Self {
        ParallelEvaluator { task, pool: None }
    }
}

impl<'p, T: Task> ParallelEvaluator<'p, T> {
    /// Evaluates `task` on the threads of `pool`.
    pub fn with_pool(task: T, pool: &'p rayon::ThreadPool) -> Self {
        ParallelEvaluator {
            task,
            pool: Some(pool),
        }
    }

    /// The task.
    pub fn task(&self) -> &T {
        &self.task
    }
}

impl<T: Task> Evaluator for ParallelEvaluator<'_, T> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError> {
        EvaluatorError::unless_one_context_each(genomes, contexts)?;
        let task = &self.task;
        Ok(on_pool(self.pool, || {
            genomes
                .par_iter()
                .zip(contexts.par_iter())
                // One genome per job: a thread that runs out of work takes
                // single evaluations from the other, rather than waiting
                // while it finishes a run of a dozen (half a core-second
                // idle in the default run's ten seconds).
                .with_max_len(1)
                .map(|(g, ctx)| task.evaluate(g, ctx))
                .collect()
        }))
    }
}

//! A run's progress towards its task's target, for a task that stops once an
//! evaluation reaches it (a goal reached): kept in the checkpoints.

use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Evaluation, Task};

use crate::tasks::RunTask;

/// Evaluations done so far, and when the target was first reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetProgress {
    /// Evaluations done so far.
    pub evaluations: u64,
    /// Evaluations up to and including the first genome that reached the target.
    pub solved_at: Option<u64>,
    /// The run's generation (1-based) in which it did.
    pub solved_generation: Option<u32>,
}

impl TargetProgress {
    /// Counts the `evaluations` of `generation` (the first solver's
    /// evaluation is the `i + 1`-th of its batch, as Lehman's code counts).
    pub fn tell<T: RunTask + ?Sized>(
        &mut self,
        task: &T,
        generation: u32,
        evaluations: &[Evaluation],
    ) {
        if self.solved_at.is_none()
            && let Some(i) = evaluations.iter().position(|e| task.reached_target(e))
        {
            self.solved_at = Some(self.evaluations + i as u64 + 1);
            self.solved_generation = Some(generation);
        }
        self.evaluations += evaluations.len() as u64;
    }

    /// `solved=yes|no evals_to_solve=N|none` for the summary line, with a leading space.
    pub fn summary_fields(&self) -> String {
        match self.solved_at {
            Some(n) => format!(" solved=yes evals_to_solve={n}"),
            None => " solved=no evals_to_solve=none".into(),
        }
    }
}

impl Task for Box<dyn RunTask> {
    fn evaluate(&self, genome: &vivae_neat::Genome, ctx: &vivae_neat::EvalContext) -> Evaluation {
        (**self).evaluate(genome, ctx)
    }

    fn metric_names(&self) -> &[&str] {
        (**self).metric_names()
    }
}

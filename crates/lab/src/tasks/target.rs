//! A run's progress towards its task's target, for a task that stops once an
//! evaluation reaches it (a goal reached): kept in the checkpoints.

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use vivae_neat::driver::{Evaluation, Task};

use crate::tasks::{RunTask, names};

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
    /// Of `evaluations`, those the checks of training solvers counted as
    /// ([`RunTask::holds_target`]).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub checked: u64,
}

/// Whether `n` is 0 (a count a checkpoint leaves out then).
fn is_zero(n: &u64) -> bool {
    *n == 0
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
        self.tell_checked(task, generation, evaluations, |_| None);
    }

    /// [`TargetProgress::tell`] for a task that checks its solvers: each
    /// evaluation that reaches the target, in batch order, is checked by
    /// `check` (given its index: whether it holds, and the evaluations the
    /// check counts as; none: it holds, unchecked) until one holds. The
    /// checks count in the evaluations, before the solver's own batch
    /// position. Returns the index of the one that held.
    pub fn tell_checked<T: RunTask + ?Sized>(
        &mut self,
        task: &T,
        generation: u32,
        evaluations: &[Evaluation],
        mut check: impl FnMut(usize) -> Option<(bool, u64)>,
    ) -> Option<usize> {
        let mut checked = 0;
        let mut solver = None;
        if self.solved_at.is_none() {
            for (i, _) in (evaluations.iter().enumerate()).filter(|(_, e)| task.reached_target(e)) {
                let held = match check(i) {
                    None => true,
                    Some((held, cost)) => {
                        checked += cost;
                        held
                    }
                };
                if held {
                    self.solved_at = Some(self.evaluations + checked + i as u64 + 1);
                    self.solved_generation = Some(generation);
                    solver = Some(i);
                    break;
                }
            }
        }
        self.checked += checked;
        self.evaluations += evaluations.len() as u64 + checked;
        solver
    }

    /// `solved=yes|no evals_to_solve=N|none` for the summary line, with a leading space.
    pub fn summary_fields(&self) -> String {
        match self.solved_at {
            Some(n) => format!(" solved=yes evals_to_solve={n}"),
            None => " solved=no evals_to_solve=none".into(),
        }
    }
}

/// A run's [`TargetProgress`] as a checkpoint holds it: stored under its
/// task's name (`"maze": {…}` beside the checkpoint's other progress
/// fields, flattened into them), nothing for a task without a target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StoredTarget(Option<(&'static str, TargetProgress)>);

impl StoredTarget {
    /// A new run's: no evaluations yet, for a task with a target.
    pub fn start(task: &dyn RunTask) -> StoredTarget {
        StoredTarget(
            task.has_target()
                .then(|| (task.entry().name, TargetProgress::default())),
        )
    }

    /// The progress, if the run's task has a target.
    pub fn get(&self) -> Option<&TargetProgress> {
        self.0.as_ref().map(|(_, p)| p)
    }

    /// The progress to update, if the run's task has a target.
    pub fn get_mut(&mut self) -> Option<&mut TargetProgress> {
        self.0.as_mut().map(|(_, p)| p)
    }

    /// Whether it is what a run of `task` keeps: progress stored under its
    /// name when it has a target, nothing otherwise.
    pub fn fits(&self, task: &dyn RunTask) -> bool {
        self.0.map(|(name, _)| name) == task.has_target().then(|| task.entry().name)
    }
}

impl Serialize for StoredTarget {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(usize::from(self.0.is_some())))?;
        if let Some((name, progress)) = &self.0 {
            map.serialize_entry(name, progress)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for StoredTarget {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Keys;
        impl<'de> Visitor<'de> for Keys {
            type Value = StoredTarget;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a task's target progress under the task's name")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<StoredTarget, A::Error> {
                let mut stored = None;
                while let Some(key) = map.next_key::<String>()? {
                    let Some(&name) = names().iter().find(|n| **n == key) else {
                        return Err(de::Error::unknown_field(&key, names()));
                    };
                    if stored.is_some() {
                        return Err(de::Error::custom("target progress of two tasks"));
                    }
                    stored = Some((name, map.next_value()?));
                }
                Ok(StoredTarget(stored))
            }
        }
        // As a struct whose fields are the task names: flattened into the
        // checkpoint's progress, it takes only those keys from it.
        deserializer.deserialize_struct("StoredTarget", names(), Keys)
    }
}

impl Task for Box<dyn RunTask> {
    fn evaluate(&self, genome: &vivae_neat::Genome, ctx: &vivae_neat::EvalContext) -> Evaluation {
        (**self).evaluate(genome, ctx)
    }

    fn metric_names(&self) -> &[&str] {
        (**self).metric_names()
    }

    fn context_free(&self) -> bool {
        (**self).context_free()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::TaskName;

    fn eval(fitness: f64) -> Evaluation {
        Evaluation {
            fitness,
            ..Evaluation::default()
        }
    }

    #[test]
    fn a_run_stops_only_on_a_solver_that_holds_its_check() {
        let c = crate::tasks::default_config(Some(&TaskName("cartpole".into()))).unwrap();
        let task = crate::tasks::build(&c, &[]).unwrap();
        let mut p = TargetProgress::default();
        // Two of the batch reach 475 in training; the first fails its check
        // (20 evaluations spent), the second holds: it is the solver, after
        // 3 evaluations of the batch and both checks.
        let told = [eval(100.0), eval(500.0), eval(480.0), eval(500.0)];
        let mut asked = Vec::new();
        let held = p.tell_checked(task.as_ref(), 1, &told, |i| {
            asked.push(i);
            Some((i == 2, 20))
        });
        assert_eq!((held, asked), (Some(2), vec![1, 2]));
        assert_eq!((p.solved_at, p.solved_generation), (Some(3 + 40), Some(1)));
        assert_eq!((p.evaluations, p.checked), (4 + 40, 40));
        // Solved: later generations check nothing.
        let later = p.tell_checked(task.as_ref(), 2, &told, |_| panic!("checked"));
        assert_eq!((later, p.evaluations, p.solved_at), (None, 48, Some(43)));
        // Every check failing: not solved, the checks still counted.
        let mut q = TargetProgress::default();
        assert_eq!(
            q.tell_checked(task.as_ref(), 1, &told, |_| Some((false, 20))),
            None
        );
        assert_eq!((q.solved_at, q.evaluations, q.checked), (None, 64, 60));
        // A task without a check: the first evaluation that reaches the target.
        let mut r = TargetProgress::default();
        r.tell(task.as_ref(), 1, &told);
        assert_eq!((r.solved_at, r.evaluations, r.checked), (Some(2), 4, 0));
    }
}

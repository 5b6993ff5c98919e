//! Tasks that score several genomes at once, and their evaluator.

use rayon::prelude::*;

use super::task::{Evaluation, Evaluator, EvaluatorError, on_pool};
use crate::eval::EvalContext;
use crate::genome::Genome;

/// A problem that scores genomes a group at a time (for instance their
/// networks side by side as vector lanes, see
/// [`RecurrentLanes`](crate::RecurrentLanes)).
///
/// Each genome's evaluation must be what scoring it alone gives: a
/// deterministic function of the genome and its context, whatever else is in
/// its group, so results never depend on grouping or thread count.
pub trait GroupTask: Sync {
    /// The most genomes one call scores (at least 1).
    fn group_size(&self) -> usize;

    /// Scores `genomes[i]` in `contexts[i]` (at most [`GroupTask::group_size`]
    /// of them), pushing one evaluation each onto `out`, in order.
    fn evaluate_group(
        &self,
        genomes: &[Genome],
        contexts: &[EvalContext],
        out: &mut Vec<Evaluation>,
    );
}

/// Evaluates a [`GroupTask`] group by group on the rayon threads of `pool`
/// (or of the global pool); results in genome order, the same at any thread count.
pub struct GroupedEvaluator<'p, T> {
    task: T,
    pool: Option<&'p rayon::ThreadPool>,
}

impl<T: GroupTask> GroupedEvaluator<'static, T> {
    /// Evaluates `task` on rayon's global thread pool.
    pub fn new(task: T) -> Self {
        GroupedEvaluator { task, pool: None }
    }
}

impl<'p, T: GroupTask> GroupedEvaluator<'p, T> {
    /// Evaluates `task` on the threads of `pool`.
    pub fn with_pool(task: T, pool: &'p rayon::ThreadPool) -> Self {
        GroupedEvaluator {
            task,
            pool: Some(pool),
        }
    }
}

impl<T: GroupTask> Evaluator for GroupedEvaluator<'_, T> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError> {
        EvaluatorError::unless_one_context_each(genomes, contexts)?;
        let (task, size) = (&self.task, self.task.group_size().max(1));
        let groups: Vec<Vec<Evaluation>> = on_pool(self.pool, || {
            genomes
                .par_chunks(size)
                .zip(contexts.par_chunks(size))
                .map(|(g, c)| {
                    let mut out = Vec::with_capacity(g.len());
                    task.evaluate_group(g, c, &mut out);
                    out
                })
                .collect()
        });
        let evaluations: Vec<Evaluation> = groups.into_iter().flatten().collect();
        if evaluations.len() != genomes.len() {
            return Err(EvaluatorError(format!(
                "the group task returned {} evaluations for {} genomes",
                evaluations.len(),
                genomes.len()
            )));
        }
        Ok(evaluations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::ParallelEvaluator;
    use crate::genome::GenomeSpec;
    use crate::population::Population;
    use crate::{NeatParams, Network, RecurrentLanes, RecurrentNetwork};

    /// Twenty steps of a constant input; fitness from the last output.
    fn alone(g: &Genome, ctx: &EvalContext) -> f64 {
        let mut net = RecurrentNetwork::from_genome(g);
        let (x, mut out) = ([ctx.seed as f64 / u64::MAX as f64, 1.0], [0.0]);
        for _ in 0..20 {
            net.activate(&x, &mut out);
        }
        out[0]
    }

    struct Lanes;

    impl GroupTask for Lanes {
        fn group_size(&self) -> usize {
            3
        }

        fn evaluate_group(&self, g: &[Genome], c: &[EvalContext], out: &mut Vec<Evaluation>) {
            let mut lanes = RecurrentLanes::new(3);
            lanes.recompile(g);
            let x: Vec<[f64; 2]> = c
                .iter()
                .map(|c| [c.seed as f64 / u64::MAX as f64, 1.0])
                .collect();
            let mut o = vec![[0.0]; g.len()];
            for _ in 0..20 {
                let ins: Vec<&[f64]> = x.iter().map(|x| &x[..]).collect();
                let mut outs: Vec<&mut [f64]> = o.iter_mut().map(|o| &mut o[..]).collect();
                lanes.activate(&ins, &mut outs);
            }
            out.extend(o.iter().map(|o| Evaluation::fitness(o[0])));
        }
    }

    #[test]
    fn grouped_evaluation_equals_one_at_a_time() {
        let spec = GenomeSpec {
            allow_recurrent: true,
            ..GenomeSpec::plain(2, 1)
        };
        let mut pop = Population::new(NeatParams::plain_neat(), spec, 4).unwrap();
        for _ in 0..3 {
            pop.evaluate(|g, ctx| alone(g, &ctx));
            pop.next_generation();
        }
        let genomes = pop.genomes().to_vec();
        let contexts: Vec<EvalContext> = (0..genomes.len())
            .map(|index| EvalContext {
                generation: 3,
                index,
                seed: crate::eval_seed(4, 3, index),
            })
            .collect();
        let want = ParallelEvaluator::new(alone)
            .evaluate(&genomes, &contexts)
            .unwrap();
        let got = GroupedEvaluator::new(Lanes)
            .evaluate(&genomes, &contexts)
            .unwrap();
        assert_eq!(got.len(), genomes.len());
        for (a, b) in got.iter().zip(&want) {
            assert_eq!(a.fitness.to_bits(), b.fitness.to_bits());
        }
    }
}

//! Reusing evaluations: when a task's evaluation depends on the genome alone
//! ([`Task::context_free`](super::Task::context_free)), a genome equal bit for
//! bit to one of the same batch or of the batch before gets that genome's
//! evaluation instead of being run again.
//!
//! NEAT copies each species' elites into the next generation unchanged, and a
//! child whose mutations all missed (or a crossover of two equal parents) is
//! its parent again: in the paper's driving run 5,439 of the 40,000
//! evaluations (14%) are of a genome the batch or the one before already holds.
//! Because such a task's evaluation is a pure function of the genome, the
//! copy has the bits a second run would give, so reusing it changes no
//! result, only the work.

use std::collections::HashMap;

use super::task::{Evaluation, Evaluator, EvaluatorError};
use crate::eval::{EvalContext, splitmix64};
use crate::genome::Genome;

/// An [`Evaluator`] that runs each distinct genome of a batch once and
/// reuses the evaluations of the batch before for genomes equal to its own.
///
/// Only for tasks whose evaluations ignore their context: an evaluation
/// reused from the last batch was made in another generation, with another
/// seed. With `enabled` false it passes every batch through unchanged.
#[derive(Debug)]
pub struct Reusing<E> {
    inner: E,
    enabled: bool,
    /// The distinct genomes of the last batch with their evaluations.
    last: Vec<(Genome, Evaluation)>,
    /// `last`'s positions by genome hash.
    by_hash: HashMap<u64, usize>,
    /// Indices of the last batch whose evaluations were reused.
    reused: Vec<usize>,
}

impl<E: Evaluator> Reusing<E> {
    /// Reuses evaluations around `inner` when `enabled` (pass the task's
    /// [`Task::context_free`](super::Task::context_free)).
    pub fn new(inner: E, enabled: bool) -> Self {
        Reusing {
            inner,
            enabled,
            last: Vec::new(),
            by_hash: HashMap::new(),
            reused: Vec::new(),
        }
    }

    /// The evaluator that runs the genomes.
    pub fn inner(&self) -> &E {
        &self.inner
    }

    /// Gives the inner evaluator back.
    pub fn into_inner(self) -> E {
        self.inner
    }
}

/// Where genome `i` of a batch gets its evaluation.
#[derive(Clone, Copy)]
enum Source {
    /// Run by the inner evaluator.
    Run,
    /// Copied from entry `j` of the last batch.
    Last(usize),
    /// Copied from genome `k < i` of the same batch.
    Earlier(usize),
}

impl<E: Evaluator> Evaluator for Reusing<E> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError> {
        EvaluatorError::unless_one_context_each(genomes, contexts)?;
        self.reused.clear();
        if !self.enabled {
            return self.inner.evaluate(genomes, contexts);
        }
        let hashes: Vec<u64> = genomes.iter().map(genome_hash).collect();
        let mut first_of: HashMap<u64, usize> = HashMap::with_capacity(genomes.len());
        let sources: Vec<Source> = (genomes.iter().zip(&hashes).enumerate())
            .map(|(i, (g, &h))| {
                if let Some(&j) = self.by_hash.get(&h)
                    && same_bits(&self.last[j].0, g)
                {
                    return Source::Last(j);
                }
                match first_of.get(&h) {
                    Some(&k) if same_bits(&genomes[k], g) => Source::Earlier(k),
                    Some(_) => Source::Run,
                    None => {
                        first_of.insert(h, i);
                        Source::Run
                    }
                }
            })
            .collect();
        let run: Vec<usize> = (0..genomes.len())
            .filter(|&i| matches!(sources[i], Source::Run))
            .collect();
        let (ran, subset) = if run.len() == genomes.len() {
            (self.inner.evaluate(genomes, contexts)?, None)
        } else {
            let subset: Vec<Genome> = run.iter().map(|&i| genomes[i].clone()).collect();
            let subset_contexts: Vec<EvalContext> = run.iter().map(|&i| contexts[i]).collect();
            (
                self.inner.evaluate(&subset, &subset_contexts)?,
                Some(subset),
            )
        };
        EvaluatorError::unless_one_evaluation_each(&ran, run.len())?;
        let mut ran = ran.into_iter();
        let mut out: Vec<Evaluation> = Vec::with_capacity(genomes.len());
        for (i, source) in sources.iter().enumerate() {
            let evaluation = match *source {
                Source::Run => ran.next().expect("one evaluation per genome run"),
                Source::Last(j) => self.last[j].1.clone(),
                Source::Earlier(k) => out[k].clone(),
            };
            if !matches!(source, Source::Run) {
                self.reused.push(i);
            }
            out.push(evaluation);
        }
        let batch = Batch {
            genomes,
            hashes: &hashes,
            sources: &sources,
            out: &out,
        };
        self.remember(batch, subset.map(Vec::into_iter));
        Ok(out)
    }

    fn reused(&self) -> &[usize] {
        &self.reused
    }
}

/// A batch just evaluated, as [`Reusing::remember`] needs it.
struct Batch<'a> {
    genomes: &'a [Genome],
    /// Each genome's [`genome_hash`].
    hashes: &'a [u64],
    sources: &'a [Source],
    out: &'a [Evaluation],
}

impl<E> Reusing<E> {
    /// Keeps the batch's distinct genomes and their evaluations for the next
    /// batch: the genomes run are moved from `ran` (the copies handed to the
    /// inner evaluator, in batch order; none when it was given the batch
    /// itself), those reused from the last batch are moved out of it.
    fn remember(&mut self, batch: Batch<'_>, mut ran: Option<std::vec::IntoIter<Genome>>) {
        let mut older: Vec<Option<Genome>> = std::mem::take(&mut self.last)
            .into_iter()
            .map(|(g, _)| Some(g))
            .collect();
        self.by_hash.clear();
        for (i, source) in batch.sources.iter().enumerate() {
            let genome = match *source {
                Source::Run => match &mut ran {
                    Some(ran) => ran.next().expect("one copy per genome run"),
                    None => batch.genomes[i].clone(),
                },
                // Two genomes of the batch can equal one of the last: it is kept once.
                Source::Last(j) => match older[j].take() {
                    Some(g) => g,
                    None => continue,
                },
                Source::Earlier(_) => continue,
            };
            self.by_hash
                .entry(batch.hashes[i])
                .or_insert(self.last.len());
            self.last.push((genome, batch.out[i].clone()));
        }
    }
}

/// A hash of every bit of `g` that an evaluation can see.
///
/// Each gene is mixed on its own and folded in by a rotation and an xor, so
/// the genes' mixes need not wait for one another (a chain of mixes through
/// every gene took 600 ns for the default run's champion, this 165 ns).
/// Equal hashes are only candidates: [`same_bits`] decides.
fn genome_hash(g: &Genome) -> u64 {
    let mut h = g.nodes().len() as u64;
    for n in g.nodes() {
        h = h.rotate_left(7) ^ splitmix64(u64::from(n.id));
    }
    for l in g.links() {
        let ends = u64::from(l.from) << 32 | u64::from(l.to);
        let gene = splitmix64(ends ^ u64::from(l.innovation).rotate_left(17))
            ^ splitmix64(l.weight.to_bits() ^ u64::from(l.enabled)).rotate_left(32);
        h = h.rotate_left(7) ^ gene;
    }
    splitmix64(h)
}

/// Whether `a` and `b` are the same genome bit for bit (weights compared by
/// their bits, so −0 and +0 differ, as they may in an evaluation).
fn same_bits(a: &Genome, b: &Genome) -> bool {
    a.nodes() == b.nodes()
        && a.links().len() == b.links().len()
        && (a.links().iter().zip(b.links())).all(|(x, y)| {
            (x.innovation, x.from, x.to, x.enabled) == (y.innovation, y.from, y.to, y.enabled)
                && x.weight.to_bits() == y.weight.to_bits()
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::ParallelEvaluator;
    use crate::eval::eval_seed;
    use crate::genome::GenomeSpec;
    use crate::params::NeatParams;
    use crate::population::Population;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Counts the genomes it runs; its fitness is the first link's weight.
    struct Counting<'a>(&'a AtomicUsize);

    impl crate::driver::Task for Counting<'_> {
        fn evaluate(&self, g: &Genome, _: &EvalContext) -> Evaluation {
            self.0.fetch_add(1, Ordering::Relaxed);
            Evaluation::fitness(g.links()[0].weight)
        }
    }

    fn contexts(generation: u32, n: usize) -> Vec<EvalContext> {
        (0..n)
            .map(|index| EvalContext {
                generation,
                index,
                seed: eval_seed(7, generation, index),
            })
            .collect()
    }

    fn genomes(n: usize, seed: u64) -> Vec<Genome> {
        let params = NeatParams {
            population_size: n,
            ..NeatParams::default()
        };
        Population::new(params, GenomeSpec::cppn(), seed)
            .unwrap()
            .genomes()
            .to_vec()
    }

    #[test]
    fn equal_genomes_are_run_once_and_get_equal_evaluations() {
        let runs = AtomicUsize::new(0);
        let mut e = Reusing::new(ParallelEvaluator::new(Counting(&runs)), true);
        let mut batch = genomes(6, 1);
        batch[4] = batch[1].clone();
        batch[5] = batch[1].clone();
        let first = e.evaluate(&batch, &contexts(1, 6)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 4);
        assert_eq!(e.reused(), &[4, 5]);
        assert_eq!(first[4], first[1]);
        assert_eq!(first[5], first[1]);
        // The next batch: two of the last batch's genomes again, two new.
        let mut next = genomes(4, 2);
        next[0] = batch[2].clone();
        next[3] = batch[5].clone();
        let second = e.evaluate(&next, &contexts(2, 4)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 6);
        assert_eq!(e.reused(), &[0, 3]);
        assert_eq!(second[0], first[2]);
        assert_eq!(second[3], first[1]);
        // Only the batch before is kept.
        let third = e.evaluate(&batch[..1], &contexts(3, 1)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 7);
        assert!(e.reused().is_empty());
        assert_eq!(third[0], first[0]);
    }

    #[test]
    fn what_a_batch_reused_or_ran_is_kept_for_the_next() {
        let runs = AtomicUsize::new(0);
        let mut e = Reusing::new(ParallelEvaluator::new(Counting(&runs)), true);
        let first = genomes(3, 1);
        let a = e.evaluate(&first, &contexts(1, 3)).unwrap();
        // Two copies of one genome of the last batch, and a new genome run
        // beside them (the inner evaluator gets copies of the batch's genomes).
        let new = genomes(1, 2).remove(0);
        let second = vec![first[1].clone(), first[1].clone(), new.clone()];
        let b = e.evaluate(&second, &contexts(2, 3)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 4);
        assert_eq!(e.reused(), &[0, 1]);
        // Both are still known one batch later, with their evaluations.
        let third = vec![new, first[1].clone(), first[0].clone()];
        let c = e.evaluate(&third, &contexts(3, 3)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 5);
        assert_eq!(e.reused(), &[0, 1]);
        assert_eq!((c[0].clone(), c[1].clone()), (b[2].clone(), a[1].clone()));
    }

    #[test]
    fn a_genome_differing_in_one_weight_bit_is_run() {
        let runs = AtomicUsize::new(0);
        let mut e = Reusing::new(ParallelEvaluator::new(Counting(&runs)), true);
        let a = genomes(1, 3).remove(0);
        let mut b = a.clone();
        let w = b.links[0].weight;
        b.links[0].weight = f64::from_bits(w.to_bits() ^ 1);
        let mut c = a.clone();
        c.links[0].enabled = !c.links[0].enabled;
        let out = e.evaluate(&[a, b, c], &contexts(1, 3)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 3);
        assert!(e.reused().is_empty());
        assert_ne!(out[0], out[1]);
    }

    #[test]
    fn a_disabled_reuse_runs_every_genome() {
        let runs = AtomicUsize::new(0);
        let mut e = Reusing::new(ParallelEvaluator::new(Counting(&runs)), false);
        let g = genomes(1, 4).remove(0);
        let batch = vec![g.clone(), g.clone(), g];
        e.evaluate(&batch, &contexts(1, 3)).unwrap();
        e.evaluate(&batch, &contexts(2, 3)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 6);
        assert!(e.reused().is_empty());
    }
}

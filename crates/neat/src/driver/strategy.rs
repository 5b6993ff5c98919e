//! The search algorithm behind the driver, as an ask/tell [`Strategy`].
//!
//! A strategy hands out a batch of genomes to evaluate ([`Strategy::ask`]),
//! is told their evaluations ([`Strategy::tell`]), and turns what it was told
//! into the next batch, lazily in `ask` or at once in [`Strategy::prepare`].
//! NEAT's [`Population`] is one; anything else that searches over
//! [`Genome`]s (an evolution strategy, random search, MAP-Elites) can be
//! another and runs on the same [`Evolution`](super::Evolution) driver,
//! observers, checkpointers and evaluators.
//!
//! A strategy is serialisable: its serialised form is a checkpoint, and a
//! strategy restored from it must continue bit-identically (keep every
//! random generator in the state, e.g. a `rand_pcg::Pcg64`).
//!
//! A (1+1) evolution strategy on NEAT's mutation operators, in full:
//!
//! ```
//! use rand::SeedableRng;
//! use rand_pcg::Pcg64;
//! use serde::{Deserialize, Serialize};
//! use vivae_neat::driver::{Batch, Evaluation, Evolution, NoCheckpoints, ParallelEvaluator, StopCriteria, StopReason, Strategy};
//! use vivae_neat::{mutation::mutate, BestEver, EvalContext, GenerationStats, Genome, GenomeSpec, InnovationTracker, NeatError, NeatParams};
//!
//! /// Mutates the best genome so far; the child replaces it when better.
//! #[derive(Serialize, Deserialize)]
//! struct OnePlusOne { spec: GenomeSpec, params: NeatParams, tracker: InnovationTracker, rng: Pcg64,
//!     seed: u64, generation: u32, child: Vec<Genome>, fitness: Option<f64>, best: Option<BestEver> }
//!
//! impl OnePlusOne {
//!     fn new(spec: GenomeSpec, params: NeatParams, seed: u64) -> Self {
//!         let (mut rng, mut tracker) = (Pcg64::seed_from_u64(seed), InnovationTracker::new((spec.inputs + spec.outputs) as u32));
//!         let child = vec![Genome::minimal(&spec, &params, &mut tracker, &mut rng)];
//!         OnePlusOne { spec, params, tracker, rng, seed, generation: 0, child, fitness: None, best: None }
//!     }
//! }
//!
//! impl Strategy for OnePlusOne {
//!     fn ask(&mut self) -> Batch<'_> {
//!         if let (Some(_), Some(best)) = (self.fitness.take(), &self.best) {
//!             self.generation += 1;
//!             self.child = vec![best.genome.clone()];
//!             mutate(&mut self.child[0], &self.spec, &self.params, &mut self.tracker, &mut self.rng);
//!         }
//!         Batch::new(&self.child, self.seed, self.generation)
//!     }
//!     fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
//!         let [e] = evaluations else { return Err(NeatError::FitnessCount { given: evaluations.len(), genomes: 1 }) };
//!         let f = if e.fitness.is_finite() { e.fitness } else { 0.0 };
//!         if self.best.as_ref().is_none_or(|b| f > b.fitness) {
//!             self.best = Some(BestEver { genome: self.child[0].clone(), fitness: f, generation: self.generation });
//!         }
//!         self.fitness = Some(f);
//!         Ok(())
//!     }
//!     fn generation(&self) -> u32 { self.generation }
//!     fn champion(&self) -> Option<(&Genome, f64)> { self.fitness.map(|f| (&self.child[0], f)) }
//!     fn best_ever(&self) -> Option<&BestEver> { self.best.as_ref() }
//!     fn stats(&self) -> GenerationStats { GenerationStats::of_batch(self.generation, &self.child, self.fitness.as_slice()) }
//! }
//!
//! // Drive the sum of the link weights to 3.
//! let task = |g: &Genome, _: &EvalContext| -(g.links().iter().map(|l| l.weight).sum::<f64>() - 3.0).abs();
//! let mut evolution = Evolution::new(OnePlusOne::new(GenomeSpec::plain(2, 1), NeatParams::plain_neat(), 7), ParallelEvaluator::new(task));
//! let reason = evolution.run(&StopCriteria::generations(2000).or_target(-0.01), &mut (), &mut NoCheckpoints)?;
//! assert!(matches!(reason, StopReason::TargetFitness { .. }), "{reason:?}");
//! assert!(evolution.strategy().best_ever().unwrap().fitness >= -0.01);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::task::Evaluation;
use crate::error::NeatError;
use crate::eval::{EvalContext, eval_seed};
use crate::genome::Genome;
use crate::population::{BestEver, GenerationStats, Population};

/// The genomes a strategy asks to have evaluated, each with its context.
#[derive(Debug, Clone, PartialEq)]
pub struct Batch<'a> {
    /// The genomes to evaluate, in order.
    pub genomes: &'a [Genome],
    /// One context per genome: `contexts[i]` goes with `genomes[i]`.
    pub contexts: Vec<EvalContext>,
}

impl<'a> Batch<'a> {
    /// `genomes` as generation `generation` of the run seeded with `run_seed`:
    /// genome `i` is evaluated with seed `eval_seed(run_seed, generation, i)`.
    pub fn new(genomes: &'a [Genome], run_seed: u64, generation: u32) -> Batch<'a> {
        let contexts = (0..genomes.len())
            .map(|index| EvalContext {
                generation,
                index,
                seed: eval_seed(run_seed, generation, index),
            })
            .collect();
        Batch { genomes, contexts }
    }
}

/// A search algorithm over genomes, driven ask/tell (pyribs-style).
///
/// One generation is `ask`, evaluate the batch, `tell`. What the accessors
/// say holds between `tell` and the next `ask` or `prepare`, when observers
/// and stop criteria read them. Serialising a strategy at any point and
/// deserialising it must give a strategy that continues bit-identically.
pub trait Strategy: Serialize + DeserializeOwned {
    /// The genomes to evaluate next, with their contexts. If the previous
    /// batch was told and not yet turned into a new one, this does it first
    /// (for NEAT: breeds the next generation); otherwise it hands out the
    /// current batch again.
    fn ask(&mut self) -> Batch<'_>;

    /// Tells the evaluations of the batch last asked, one per genome in order.
    /// A wrong count is [`NeatError::FitnessCount`]; non-finite fitness counts as 0.
    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError>;

    /// Does now the work the next `ask` would do lazily, so that the state
    /// (e.g. a checkpoint) is ready to evaluate. Doing nothing is allowed.
    fn prepare(&mut self) {}

    /// The generation of the batch last asked (and, once told, evaluated).
    fn generation(&self) -> u32;

    /// The best genome of the batch just told and its fitness (`None` before `tell`).
    fn champion(&self) -> Option<(&Genome, f64)>;

    /// The best genome told so far, with its fitness and [`Strategy::generation`].
    fn best_ever(&self) -> Option<&BestEver>;

    /// Statistics of the current batch (see [`GenerationStats::of_batch`]).
    fn stats(&self) -> GenerationStats;
}

/// NEAT: a batch is a generation; `prepare` breeds the next one
/// ([`Population::next_generation`]) once the current one is evaluated.
impl Strategy for Population {
    fn ask(&mut self) -> Batch<'_> {
        self.prepare();
        Batch::new(self.genomes(), self.seed(), self.generation())
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        self.set_fitnesses(evaluations.iter().map(|e| e.fitness).collect())
    }

    fn prepare(&mut self) {
        if self.is_evaluated() {
            self.next_generation();
        }
    }

    fn generation(&self) -> u32 {
        Population::generation(self)
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        Population::champion(self)
    }

    fn best_ever(&self) -> Option<&BestEver> {
        Population::best_ever(self)
    }

    fn stats(&self) -> GenerationStats {
        Population::stats(self)
    }
}

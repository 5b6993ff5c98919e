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
//! use vivae_neat::driver::{Batch, Evaluation, Evolution, NoCheckpoints};
//! use vivae_neat::driver::{ParallelEvaluator, StopCriteria, StopReason, Strategy};
//! use vivae_neat::{BestEver, EvalContext, GenerationStats, Genome, GenomeSpec};
//! use vivae_neat::{InnovationTracker, NeatError, NeatParams, mutation::mutate};
//!
//! /// Mutates the best genome so far; the child replaces it when better.
//! #[derive(Serialize, Deserialize)]
//! struct OnePlusOne {
//!     spec: GenomeSpec, params: NeatParams, tracker: InnovationTracker, rng: Pcg64, seed: u64,
//!     generation: u32, child: [Genome; 1], fitness: Option<f64>, best: Option<BestEver>,
//! }
//!
//! impl Strategy for OnePlusOne {
//!     fn ask(&mut self) -> Batch<'_> {
//!         if let (Some(_), Some(best)) = (self.fitness.take(), &self.best) {
//!             let (child, params) = (&mut self.child[0], &self.params);
//!             *child = best.genome.clone();
//!             mutate(child, &self.spec, params, &mut self.tracker, &mut self.rng);
//!             self.generation += 1;
//!         }
//!         Batch::new(&self.child, self.seed, self.generation)
//!     }
//!     fn tell(&mut self, told: &[Evaluation]) -> Result<(), NeatError> {
//!         let given = told.len();
//!         let [e] = told else { return Err(NeatError::FitnessCount { given, genomes: 1 }) };
//!         let f = e.finite_fitness();
//!         if self.best.as_ref().is_none_or(|b| f > b.fitness) {
//!             let genome = self.child[0].clone();
//!             self.best = Some(BestEver { genome, fitness: f, generation: self.generation });
//!         }
//!         self.fitness = Some(f);
//!         Ok(())
//!     }
//!     fn generation(&self) -> u32 { self.generation }
//!     fn champion(&self) -> Option<(&Genome, f64)> { Some((&self.child[0], self.fitness?)) }
//!     fn best_ever(&self) -> Option<&BestEver> { self.best.as_ref() }
//!     fn stats(&self) -> GenerationStats {
//!         GenerationStats::of_batch(self.generation, &self.child, self.fitness.as_slice())
//!     }
//! }
//!
//! // Starting from a minimal genome, drive the sum of the link weights to 3.
//! let (spec, params, seed) = (GenomeSpec::plain(2, 1), NeatParams::plain_neat(), 7);
//! let (mut rng, mut tracker) = (Pcg64::seed_from_u64(seed), InnovationTracker::new(3));
//! let child = [Genome::minimal(&spec, &params, &mut tracker, &mut rng)];
//! let (generation, fitness, best) = (0, None, None);
//! let es = OnePlusOne { spec, params, tracker, rng, seed, generation, child, fitness, best };
//! let task = |g: &Genome, _: &EvalContext| {
//!     -(g.links().iter().map(|l| l.weight).sum::<f64>() - 3.0).abs()
//! };
//! let mut evolution = Evolution::new(es, ParallelEvaluator::new(task));
//! let stop = StopCriteria::generations(2000).or_target(-0.01);
//! let reason = evolution.run(&stop, &mut (), &mut NoCheckpoints)?;
//! let StopReason::TargetFitness { generation, .. } = reason else { panic!("{reason:?}") };
//! assert!(generation > 1 && evolution.strategy().best_ever().unwrap().fitness >= -0.01);
//! // The strategy is the run's state: a checkpoint is its JSON.
//! let restored: OnePlusOne = serde_json::from_str(&serde_json::to_string(evolution.strategy())?)?;
//! assert_eq!(restored.best_ever(), evolution.strategy().best_ever());
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

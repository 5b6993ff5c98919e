//! The told-batch state every strategy shares: the batch of genomes, its
//! generation, what the strategy was told of it and the best genome ever.
//!
//! The strategies keep these as fields of their own serialised state (so
//! each checkpoint's JSON keeps its field names and order) and borrow them
//! as a [`ToldBatch`], which answers the driver's questions ([`ask`],
//! [`champion`], [`best_ever`], [`stats`]) and records a told batch
//! ([`record`]) the same way for all of them.
//!
//! [`ask`]: crate::driver::Strategy::ask
//! [`champion`]: crate::driver::Strategy::champion
//! [`best_ever`]: crate::driver::Strategy::best_ever
//! [`stats`]: crate::driver::Strategy::stats

use super::invalid;
use crate::driver::Batch;
use crate::error::NeatError;
use crate::genome::Genome;
use crate::population::{BestEver, GenerationStats};
use crate::stats::argmax;

/// What a strategy keeps of the batch it was told; the fitness the task
/// reported is what the driver reads.
pub(crate) trait Told {
    /// The reported fitness per genome of the batch (finite).
    fn fitness(&self) -> &[f64];
}

/// `impl Told` for a strategy's record `$told` of a batch, whose
/// `fitness: Vec<f64>` field is the reported fitness.
macro_rules! impl_told {
    ($told:ident) => {
        impl $crate::strategies::told::Told for $told {
            fn fitness(&self) -> &[f64] {
                &self.fitness
            }
        }
    };
}
pub(crate) use impl_told;

/// The told state of a strategy breeding its own batches: `impl Told` for
/// its record `$told`, and `$state::told_batch()` borrowing the fields
/// every such state has (`seed`, `generation`, `batch`, `told`, `best`).
macro_rules! own_batch_state {
    ($state:ident, $told:ident) => {
        $crate::strategies::told::impl_told!($told);

        impl $state {
            /// The batch, its generation, what was told of it and the best ever.
            fn told_batch(&self) -> $crate::strategies::told::ToldBatch<'_, $told> {
                let batch = (self.seed, self.generation, &self.batch[..]);
                $crate::strategies::told::ToldBatch::new(batch, &self.told, &self.best)
            }
        }
    };
}
pub(crate) use own_batch_state;

/// The public type `$name` of a strategy breeding its own batches: a
/// checkpoint is its `State`'s JSON, and reading one checks NEAT's settings
/// and the genome spec, the state's own parts (`State::check_own`), then
/// its told batch.
macro_rules! own_batch_strategy {
    ($(#[$doc:meta])* pub struct $name:ident(State);) => {
        $(#[$doc])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(try_from = "State")]
        pub struct $name(State);

        impl TryFrom<State> for $name {
            type Error = $crate::error::NeatError;

            fn try_from(s: State) -> Result<Self, $crate::error::NeatError> {
                $crate::strategies::check_neat(&s.params, &s.spec)?;
                s.check_own()?;
                s.told_batch().check()?;
                Ok($name(s))
            }
        }
    };
}
pub(crate) use own_batch_strategy;

/// A strategy's told-batch state, borrowed from its fields.
pub(crate) struct ToldBatch<'a, T> {
    /// The run seed (every evaluation's seed derives from it).
    pub seed: u64,
    /// The generation of the batch.
    pub generation: u32,
    /// The batch, in order.
    pub genomes: &'a [Genome],
    /// What the strategy was told of the batch (`None` before `tell`).
    pub told: &'a Option<T>,
    /// The fittest genome of every batch told so far.
    pub best: &'a Option<BestEver>,
}

impl<'a, T: Told> ToldBatch<'a, T> {
    /// Borrows the parts: the batch as `(run seed, generation, genomes)`.
    pub fn new(
        (seed, generation, genomes): (u64, u32, &'a [Genome]),
        told: &'a Option<T>,
        best: &'a Option<BestEver>,
    ) -> Self {
        ToldBatch {
            seed,
            generation,
            genomes,
            told,
            best,
        }
    }

    /// The batch to evaluate, with its contexts.
    pub fn batch(&self) -> Batch<'a> {
        Batch::new(self.genomes, self.seed, self.generation)
    }

    /// The batch's reported fitness (empty before `tell`).
    pub fn fitness(&self) -> &'a [f64] {
        self.told.as_ref().map_or(&[], |t| t.fitness())
    }

    /// The batch's first fittest genome and its fitness (after `tell`).
    pub fn champion(&self) -> Option<(&'a Genome, f64)> {
        let f = self.told.as_ref()?.fitness();
        argmax(f).map(|i| (&self.genomes[i], f[i]))
    }

    /// The fittest genome told so far.
    pub fn best_ever(&self) -> Option<&'a BestEver> {
        self.best.as_ref()
    }

    /// Statistics of the batch, without species.
    pub fn stats(&self) -> GenerationStats {
        GenerationStats::of_batch(self.generation, self.genomes, self.fitness())
    }

    /// Checks a restored state: the told fitness matches the batch, and the
    /// best ever is finite and not from a later generation.
    pub fn check(&self) -> Result<(), NeatError> {
        if self
            .told
            .as_ref()
            .is_some_and(|t| t.fitness().len() != self.genomes.len())
        {
            let given = self.fitness().len();
            return Err(invalid("told", given, "does not match the batch"));
        }
        if self
            .best
            .as_ref()
            .is_some_and(|b| !b.fitness.is_finite() || b.generation > self.generation)
        {
            return Err(invalid("best", "record", "non-finite or from the future"));
        }
        Ok(())
    }
}

/// Records what a strategy was told of `genomes` (generation `generation`):
/// `best` becomes the batch's first fittest genome when it beats it, and
/// `told` the new record. `told.fitness()` has one value per genome.
pub(crate) fn record<T: Told>(
    slot: &mut Option<T>,
    best: &mut Option<BestEver>,
    genomes: &[Genome],
    generation: u32,
    told: T,
) {
    BestEver::offer(best, genomes, told.fitness(), generation);
    *slot = Some(told);
}

/// The [`Strategy`](crate::driver::Strategy) methods of a strategy
/// `Self(State)` whose state has a `told_batch()`: `ask` (after
/// `prepare`), `generation`, `champion`, `best_ever` and (unless called
/// with `without_stats`) `stats`.
macro_rules! told_batch_accessors {
    () => {
        $crate::strategies::told::told_batch_accessors!(without_stats);

        fn stats(&self) -> $crate::population::GenerationStats {
            self.0.told_batch().stats()
        }
    };
    (without_stats) => {
        fn ask(&mut self) -> $crate::driver::Batch<'_> {
            self.prepare();
            self.0.told_batch().batch()
        }

        fn generation(&self) -> u32 {
            self.0.told_batch().generation
        }

        fn champion(&self) -> Option<(&$crate::genome::Genome, f64)> {
            self.0.told_batch().champion()
        }

        fn best_ever(&self) -> Option<&$crate::population::BestEver> {
            self.0.told_batch().best_ever()
        }
    };
}
pub(crate) use told_batch_accessors;

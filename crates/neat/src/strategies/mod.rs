//! Search strategies beyond NEAT's fitness-driven population, each a
//! [`Strategy`](crate::driver::Strategy) on the same driver, all breeding
//! with NEAT's crossover, mutation and innovation history:
//!
//! * [`NoveltySearch`] (Lehman & Stanley 2011): NEAT's speciated
//!   reproduction selecting on behavioural novelty (optionally mixed with
//!   fitness), with an archive under an adaptive threshold.
//! * [`MapElites`] (Mouret & Clune 2015): the best genome per cell of a grid
//!   or CVT partition of the behaviour space.
//! * [`Nsga2`] (Deb et al. 2002): several objectives, chosen among an
//!   evaluation's fitness and metrics, by non-dominated sorting and crowding.
//!
//! Each is its own checkpoint: serialised and restored it continues
//! bit-identically, and restoring checks what it reads.
//!
//! ## Layout (archives, breeding, told state), as pyribs separates them
//!
//! * `novelty.rs`, `map_elites.rs`, `nsga2.rs`: one file per strategy, its
//!   settings, its serialised state (the checkpoint's fields, in order), and
//!   how it breeds the next batch (ask/tell/prepare).
//! * [`archive`]: what the strategies keep, apart from breeding, one file
//!   each: MAP-Elites' cells ([`archive::grid`], [`archive::cvt`]) and
//!   elites ([`archive::elites`]), NSGA-II's Pareto ranking
//!   ([`archive::pareto`]), novelty search's archive and threshold
//!   ([`archive::novelty`]) with its k-nearest-neighbour search ([`knn`]).
//! * `told.rs`: the told-batch state all of them share (the batch, its
//!   generation, what was told of it, the best ever). Its parts stay fields
//!   of each strategy's serialised state, so that every checkpoint keeps its
//!   JSON (field names and order); `ToldBatch` borrows them, answers
//!   `ask`, `generation`, `champion`, `best_ever` and `stats`, checks them
//!   when a checkpoint is read, and `told::record` records a told batch, the
//!   same way for all. Its macros write what would otherwise be repeated
//!   per strategy: `impl_told` (the told record's fitness),
//!   `own_batch_state` (`told_batch()` of a state holding its own batch),
//!   `own_batch_strategy` (the public type and its checked restore) and
//!   `told_batch_accessors` (the `Strategy` methods).
//! * This file: NEAT's breeding (`Breeding`: a child by crossover +
//!   mutation over one innovation history, a batch of them from any parent
//!   selection, the next batch in place of the last in `next_batch`,
//!   generation 0 in `first_batch`) and the shared checks (`check_neat`,
//!   `check_count`).
//!
//! The old paths still work: `strategies::knn`, and every archive type is
//! also re-exported from its strategy's module (`map_elites::Cells`,
//! `nsga2::non_dominated_fronts`, `novelty::NoveltyParams`, ...).

pub mod archive;
pub mod map_elites;
pub mod novelty;
pub mod nsga2;
mod told;

pub use archive::knn;
pub use map_elites::{Cells, Elite, MapElites, MapElitesParams, MapElitesStats};
pub use novelty::{NoveltyMetric, NoveltyParams, NoveltySearch};
pub use nsga2::{Measure, Nsga2, Nsga2Params, Objective};

use rand::{Rng, RngExt, SeedableRng};
use rand_pcg::Pcg64;

use crate::crossover::crossover;
use crate::error::NeatError;
use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::mutation::mutate;
use crate::params::NeatParams;

/// What NEAT's breeding needs besides the parents: shared by the strategies.
pub(crate) struct Breeding<'a, R: Rng + ?Sized> {
    pub spec: &'a GenomeSpec,
    pub params: &'a NeatParams,
    pub tracker: &'a mut InnovationTracker,
    pub rng: &'a mut R,
}

impl<'a, R: Rng + ?Sized> Breeding<'a, R> {
    /// Borrows what breeding needs from a strategy's state.
    pub fn new(
        spec: &'a GenomeSpec,
        params: &'a NeatParams,
        tracker: &'a mut InnovationTracker,
        rng: &'a mut R,
    ) -> Self {
        Breeding {
            spec,
            params,
            tracker,
            rng,
        }
    }

    /// A child of `a` (crossed with `b` if given, the fitter parent giving
    /// the disjoint genes), then mutated as NEAT does: a crossover child
    /// skips mutation with `mate_only_probability`.
    pub fn child(&mut self, a: (&Genome, f64), b: Option<(&Genome, f64)>) -> Genome {
        let mut child = match b {
            Some(b) => {
                let c = crossover(a.0, a.1, b.0, b.1, self.params, self.rng);
                if self.rng.random_bool(self.params.mate_only_probability) {
                    return c;
                }
                c
            }
            None => a.0.clone(),
        };
        mutate(&mut child, self.spec, self.params, self.tracker, self.rng);
        child
    }

    /// `n` children pushed to `batch`: each of a parent drawn by `pick`
    /// (with the fitness crossover compares), crossed with a second one drawn
    /// the same way with probability `crossover`.
    pub fn children<'g>(
        &mut self,
        n: usize,
        crossover: f64,
        batch: &mut Vec<Genome>,
        mut pick: impl FnMut(&mut R) -> (&'g Genome, f64),
    ) {
        for _ in 0..n {
            let a = pick(self.rng);
            let b = self.rng.random_bool(crossover).then(|| pick(self.rng));
            batch.push(self.child(a, b));
        }
    }

    /// The next generation in place of `batch`: `n` children bred as
    /// [`Breeding::children`] breeds them (`crossover` their crossover
    /// probability); `generation` counts it.
    pub fn next_batch<'g>(
        &mut self,
        (batch, generation): (&mut Vec<Genome>, &mut u32),
        (n, crossover): (usize, f64),
        pick: impl FnMut(&mut R) -> (&'g Genome, f64),
    ) {
        batch.clear();
        self.children(n, crossover, batch, pick);
        *generation += 1;
    }

    /// `n` minimal genomes (NEAT's generation 0).
    pub fn minimal(&mut self, n: usize) -> Vec<Genome> {
        (0..n)
            .map(|_| Genome::minimal(self.spec, self.params, self.tracker, self.rng))
            .collect()
    }
}

/// Generation 0 of a strategy breeding its own batches: `n` minimal
/// genomes drawn from a `Pcg64` seeded with `seed`, returned with that
/// generator and the innovation history they started.
pub(crate) fn first_batch(
    spec: &GenomeSpec,
    params: &NeatParams,
    seed: u64,
    n: usize,
) -> (Pcg64, InnovationTracker, Vec<Genome>) {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
    let batch = Breeding::new(spec, params, &mut tracker, &mut rng).minimal(n);
    (rng, tracker, batch)
}

/// Checks NEAT's settings, then the genome spec.
pub(crate) fn check_neat(params: &NeatParams, spec: &GenomeSpec) -> Result<(), NeatError> {
    params.validate()?;
    spec.validate()
}

/// One evaluation per genome, or [`NeatError::FitnessCount`].
pub(crate) fn check_count(given: usize, genomes: usize) -> Result<(), NeatError> {
    if given == genomes {
        Ok(())
    } else {
        Err(NeatError::FitnessCount { given, genomes })
    }
}

/// A setting (or a restored state's field) out of its range.
pub(crate) fn invalid(
    field: &'static str,
    value: impl ToString,
    reason: &'static str,
) -> NeatError {
    NeatError::InvalidParam {
        field,
        value: value.to_string(),
        reason,
    }
}

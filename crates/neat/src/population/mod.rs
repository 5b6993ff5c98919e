//! The population: evaluation, speciation, fitness sharing and reproduction.
//!
//! One file per job: this one holds the state and its accessors and records
//! fitness; `reproduce.rs` makes the next generation, `speciate.rs` sorts
//! genomes into species, `restore.rs` reads a checkpoint back and checks it,
//! `record.rs` has what a run keeps of its genomes (best ever, statistics).

mod record;
mod reproduce;
mod restore;
mod speciate;

use rand::SeedableRng;
use rand_pcg::Pcg64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{GenomeAt, NeatError, PopulationError};
use crate::eval::{EvalContext, eval_seed};
use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;
use crate::species::Species;
use crate::stats::argmax;

pub use record::{BestEver, GenerationStats};
pub use reproduce::allocate_offspring;
use restore::{RawPopulation, check_genome, check_history};

/// Declares a population's fields, once for the two forms that hold them:
/// the checked [`Population`] and the `RawPopulation` a checkpoint is read
/// into before it is checked (`restore.rs`), which differ only in how they
/// hold genomes, species and the best ever. The order is the JSON's.
macro_rules! population_fields {
    ($(#[$attr:meta])* $vis:vis struct $name:ident of ($genome:ty, $species:ty, $best:ty);) => {
        $(#[$attr])*
        $vis struct $name {
            params: $crate::params::NeatParams,
            spec: $crate::genome::GenomeSpec,
            seed: u64,
            generation: u32,
            rng: rand_pcg::Pcg64,
            tracker: $crate::innovation::InnovationTracker,
            genomes: Vec<$genome>,
            fitness: Option<Vec<f64>>,
            species: Vec<$species>,
            next_species_id: u32,
            threshold: f64,
            best_ever: Option<$best>,
            /// Generation of the last refocus on the two best species
            /// (`population_stagnation_limit`); absent from the JSON when there was none.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            refocused: Option<u32>,
        }
    };
}
pub(crate) use population_fields;

population_fields! {
    /// A NEAT population with its complete state (RNG, species, innovations, best-ever),
    /// serialisable so that a restored checkpoint continues bit-identically.
    ///
    /// Deserialising validates the whole state (see [`Population::from_json`]):
    /// a `Population` read from JSON is always consistent.
    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields, try_from = "RawPopulation")]
    pub struct Population of (Genome, Species, BestEver);
}

impl Population {
    /// A generation-0 population of minimal genomes; validates `params` and `spec`.
    pub fn new(params: NeatParams, spec: GenomeSpec, seed: u64) -> Result<Population, NeatError> {
        params.validate()?;
        spec.validate()?;
        let mut rng = Pcg64::seed_from_u64(seed);
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        let genomes = (0..params.population_size)
            .map(|_| Genome::minimal(&spec, &params, &mut tracker, &mut rng))
            .collect();
        Ok(Population::assemble(
            params, spec, seed, rng, tracker, genomes,
        ))
    }

    /// A generation-0 population made of existing genomes (e.g. a previous run's final
    /// population); each must pass [`Genome::check`] and match the spec's inputs/outputs,
    /// and together they must number every link alike.
    /// The population size is the number of genomes given until `params` says otherwise.
    pub fn from_genomes(
        params: NeatParams,
        spec: GenomeSpec,
        genomes: Vec<Genome>,
        seed: u64,
    ) -> Result<Population, NeatError> {
        params.validate()?;
        spec.validate()?;
        if genomes.is_empty() {
            return Err(PopulationError::Empty.into());
        }
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        for (i, g) in genomes.iter().enumerate() {
            check_genome(GenomeAt::Member(i), g, &spec)?;
            for l in g.links() {
                tracker.absorb_link(l.from, l.to, l.innovation);
            }
            for n in g.nodes() {
                tracker.absorb_node(n.id);
            }
        }
        // Genomes that number the same link differently (or two links alike)
        // cannot evolve together.
        check_history(
            &tracker,
            &spec,
            genomes
                .iter()
                .enumerate()
                .map(|(i, g)| (GenomeAt::Member(i), g)),
        )?;
        let rng = Pcg64::seed_from_u64(seed);
        Ok(Population::assemble(
            params, spec, seed, rng, tracker, genomes,
        ))
    }

    fn assemble(
        params: NeatParams,
        spec: GenomeSpec,
        seed: u64,
        rng: Pcg64,
        tracker: InnovationTracker,
        genomes: Vec<Genome>,
    ) -> Population {
        let threshold = params.compatibility_threshold;
        let mut pop = Population {
            params,
            spec,
            seed,
            generation: 0,
            rng,
            tracker,
            genomes,
            fitness: None,
            species: Vec::new(),
            next_species_id: 0,
            threshold,
            best_ever: None,
            refocused: None,
        };
        let genomes = std::mem::take(&mut pop.genomes);
        pop.speciate(&genomes, &[]);
        pop.genomes = genomes;
        pop
    }

    /// The parameters in force.
    pub fn params(&self) -> &NeatParams {
        &self.params
    }

    /// Replaces the parameters from the next reproduction on (validated first).
    /// The compatibility threshold restarts from the new `compatibility_threshold`.
    pub fn set_params(&mut self, params: NeatParams) -> Result<(), NeatError> {
        params.validate()?;
        self.threshold = params.compatibility_threshold;
        self.params = params;
        Ok(())
    }

    /// What the genomes look like.
    pub fn spec(&self) -> &GenomeSpec {
        &self.spec
    }

    /// The run seed (source of every [`EvalContext::seed`]).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Current generation number (0 = initial population).
    pub fn generation(&self) -> u32 {
        self.generation
    }

    /// The genomes of the current generation.
    pub fn genomes(&self) -> &[Genome] {
        &self.genomes
    }

    /// The species of the current generation.
    pub fn species(&self) -> &[Species] {
        &self.species
    }

    /// The innovation history.
    pub fn tracker(&self) -> &InnovationTracker {
        &self.tracker
    }

    /// The compatibility threshold in force (moves with the dynamic threshold).
    pub fn compatibility_threshold(&self) -> f64 {
        self.threshold
    }

    /// Whether the current generation has fitness values.
    pub fn is_evaluated(&self) -> bool {
        self.fitness.is_some()
    }

    /// Fitness of every genome of the current generation (empty before evaluation).
    pub fn fitnesses(&self) -> Vec<f64> {
        self.fitness.clone().unwrap_or_default()
    }

    /// The best genome of the run so far, with its fitness and generation.
    pub fn best_ever(&self) -> Option<&BestEver> {
        self.best_ever.as_ref()
    }

    /// The context of evaluation `index` in the current generation.
    pub fn eval_context(&self, index: usize) -> EvalContext {
        EvalContext {
            generation: self.generation,
            index,
            seed: eval_seed(self.seed, self.generation, index),
        }
    }

    /// Evaluates every genome in parallel (rayon). Results are collected by index, so
    /// they are identical at any thread count when `f` is deterministic.
    pub fn evaluate<F>(&mut self, f: F)
    where
        F: Fn(&Genome, EvalContext) -> f64 + Sync,
    {
        let contexts: Vec<EvalContext> = (0..self.genomes.len())
            .map(|i| self.eval_context(i))
            .collect();
        let fitness: Vec<f64> = self
            .genomes
            .par_iter()
            .zip(contexts.into_par_iter())
            // One genome per job, as in `ParallelEvaluator`: no thread waits
            // at the end of a generation while the other finishes a long run.
            .with_max_len(1)
            .map(|(g, ctx)| f(g, ctx))
            .collect();
        self.record_fitness(fitness);
    }

    /// Sets fitness values computed elsewhere (one per genome, in order).
    pub fn set_fitnesses(&mut self, fitness: Vec<f64>) -> Result<(), NeatError> {
        if fitness.len() != self.genomes.len() {
            return Err(NeatError::FitnessCount {
                given: fitness.len(),
                genomes: self.genomes.len(),
            });
        }
        self.record_fitness(fitness);
        Ok(())
    }

    fn record_fitness(&mut self, mut fitness: Vec<f64>) {
        // Non-finite fitness would break sorting and JSON; it counts as 0.
        for f in &mut fitness {
            if !f.is_finite() {
                *f = 0.0;
            }
        }
        BestEver::offer(
            &mut self.best_ever,
            &self.genomes,
            &fitness,
            self.generation,
        );
        self.fitness = Some(fitness);
    }

    /// The best genome of the current generation and its fitness (after evaluation).
    pub fn champion(&self) -> Option<(&Genome, f64)> {
        let f = self.fitness.as_ref()?;
        argmax(f).map(|i| (&self.genomes[i], f[i]))
    }

    /// Statistics of the current generation.
    pub fn stats(&self) -> GenerationStats {
        GenerationStats {
            species: self.species.len(),
            compatibility_threshold: self.threshold,
            ..GenerationStats::of_batch(
                self.generation,
                &self.genomes,
                self.fitness.as_deref().unwrap_or_default(),
            )
        }
    }

    /// Writes the complete state as JSON (exact: restoring continues bit-identically).
    pub fn to_json(&self) -> Result<String, NeatError> {
        serde_json::to_string(self).map_err(|e| NeatError::Checkpoint(e.to_string()))
    }

    /// Restores a population written by [`Population::to_json`], validating
    /// it: parameters and spec, every genome (members, species
    /// representatives, best ever) against [`Genome::check`] and the spec's
    /// inputs and outputs, one finite fitness per genome, species that
    /// partition the genomes, an innovation history consistent with itself
    /// and the genomes, and counters above every id in use. Malformed JSON is
    /// [`NeatError::Checkpoint`]; anything inconsistent is the typed error
    /// naming it.
    pub fn from_json(text: &str) -> Result<Population, NeatError> {
        let raw: RawPopulation =
            serde_json::from_str(text).map_err(|e| NeatError::Checkpoint(e.to_string()))?;
        Population::try_from(raw)
    }
}

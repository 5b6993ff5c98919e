//! The population: evaluation, speciation, fitness sharing and reproduction.

use std::collections::BTreeSet;

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::crossover::crossover;
use crate::distance::{Compatibility, GeneTable};
use crate::error::{GenomeAt, NeatError, PopulationError};
use crate::eval::{EvalContext, eval_seed};
use crate::genome::{Genome, GenomeSpec, NodeKind, RawGenome};
use crate::innovation::InnovationTracker;
use crate::mutation::mutate;
use crate::params::NeatParams;
use crate::species::Species;
use crate::stats::{self, argmax};

/// The best genome seen so far in the run (see [`Population::best_ever`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BestEver {
    /// The genome.
    pub genome: Genome,
    /// Its fitness.
    pub fitness: f64,
    /// The generation in which it was evaluated.
    pub generation: u32,
}

impl BestEver {
    /// Replaces `best` with the batch's first fittest genome (generation
    /// `generation`) when it beats it; `fitness` has one value per genome.
    pub(crate) fn offer(
        best: &mut Option<BestEver>,
        genomes: &[Genome],
        fitness: &[f64],
        generation: u32,
    ) {
        if let Some(i) = argmax(fitness)
            && best.as_ref().is_none_or(|b| fitness[i] > b.fitness)
        {
            *best = Some(BestEver {
                genome: genomes[i].clone(),
                fitness: fitness[i],
                generation,
            });
        }
    }
}

/// Summary statistics of the current generation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GenerationStats {
    /// Generation number (0 = initial population).
    pub generation: u32,
    /// Number of genomes.
    pub population: usize,
    /// Number of species.
    pub species: usize,
    /// Current compatibility threshold (changes with the dynamic threshold).
    pub compatibility_threshold: f64,
    /// Mean number of nodes per genome (inputs, outputs and hidden).
    pub mean_nodes: f64,
    /// Mean number of hidden nodes per genome.
    pub mean_hidden: f64,
    /// Mean number of enabled links per genome.
    pub mean_links: f64,
    /// Best fitness of this generation (None before evaluation).
    pub best_fitness: Option<f64>,
    /// Mean fitness of this generation (None before evaluation).
    pub mean_fitness: Option<f64>,
}

impl GenerationStats {
    /// Statistics of any batch of genomes, without species (`species` and
    /// `compatibility_threshold` are 0); `fitness` is empty before evaluation,
    /// else one value per genome.
    pub fn of_batch(generation: u32, genomes: &[Genome], fitness: &[f64]) -> GenerationStats {
        let n = genomes.len().max(1) as f64;
        let sum = |g: fn(&Genome) -> usize| genomes.iter().map(g).sum::<usize>() as f64 / n;
        GenerationStats {
            generation,
            population: genomes.len(),
            species: 0,
            compatibility_threshold: 0.0,
            mean_nodes: sum(|g| g.nodes().len()),
            mean_hidden: sum(|g| g.num_hidden()),
            mean_links: sum(|g| g.num_enabled_links()),
            best_fitness: argmax(fitness).map(|i| fitness[i]),
            mean_fitness: stats::mean(fitness),
        }
    }
}

/// A NEAT population with its complete state (RNG, species, innovations, best-ever),
/// serialisable so that a restored checkpoint continues bit-identically.
///
/// Deserialising validates the whole state (see [`Population::from_json`]):
/// a `Population` read from JSON is always consistent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, try_from = "RawPopulation")]
pub struct Population {
    params: NeatParams,
    spec: GenomeSpec,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    genomes: Vec<Genome>,
    fitness: Option<Vec<f64>>,
    species: Vec<Species>,
    next_species_id: u32,
    threshold: f64,
    best_ever: Option<BestEver>,
    /// Generation of the last refocus on the two best species
    /// (`population_stagnation_limit`); absent from the JSON when there was none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    refocused: Option<u32>,
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

    /// Produces the next generation: species stagnation, explicit fitness sharing,
    /// offspring allocation, elitism, crossover and mutation, then speciation.
    /// Genomes never evaluated count as fitness 0.
    pub fn next_generation(&mut self) {
        let fitness = self
            .fitness
            .take()
            .unwrap_or_else(|| vec![0.0; self.genomes.len()]);
        let champion = argmax(&fitness).unwrap_or(0);
        let refocus = self.refocus_due();
        self.update_species_records(&fitness, champion);
        let champ_species = self
            .species
            .iter()
            .position(|s| s.members.contains(&champion));
        let alloc = if refocus {
            self.refocused = Some(self.generation);
            self.refocus_allocation(&fitness)
        } else {
            self.allocate(&fitness, champ_species)
        };
        let next = self.reproduce(&fitness, &alloc, champ_species, refocus);

        // Speciate the new generation against representatives of the old one.
        let old = std::mem::take(&mut self.genomes);
        self.speciate(&next, &old);
        self.genomes = next;
        self.generation += 1;
        self.adjust_threshold();
    }

    /// Species records and stagnation: updates each species' best fitness,
    /// then drops the species stagnant for `stagnation_limit` generations
    /// (never the champion's).
    fn update_species_records(&mut self, fitness: &[f64], champion: usize) {
        let generation = self.generation;
        for s in &mut self.species {
            let best = s
                .members
                .iter()
                .map(|&m| fitness[m])
                .fold(f64::NEG_INFINITY, f64::max);
            if s.best_fitness.is_none_or(|b| best > b) {
                s.best_fitness = Some(best);
                s.last_improved = generation;
            }
        }
        let limit = self.params.stagnation_limit;
        self.species
            .retain(|s| s.members.contains(&champion) || s.stagnation(generation) < limit);
    }

    /// Whether the population's best fitness has not risen for
    /// `population_stagnation_limit` generations (counted from the last
    /// refocus, if later).
    fn refocus_due(&self) -> bool {
        let (Some(limit), Some(best)) = (self.params.population_stagnation_limit, &self.best_ever)
        else {
            return false;
        };
        let since = best.generation.max(self.refocused.unwrap_or(0));
        self.generation.saturating_sub(since) >= limit
    }

    /// Stanley's delta coding: the two species with the best members get half
    /// the population each (the best one all of it when it is alone), every
    /// other species none; the two count as improved now, so that species
    /// stagnation does not remove them next.
    fn refocus_allocation(&mut self, fitness: &[f64]) -> Vec<usize> {
        let best = |s: &Species| {
            s.members
                .iter()
                .map(|&m| fitness[m])
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let mut order: Vec<usize> = (0..self.species.len()).collect();
        order.sort_by(|&a, &b| {
            best(&self.species[b])
                .total_cmp(&best(&self.species[a]))
                .then(a.cmp(&b))
        });
        let mut alloc = vec![0; self.species.len()];
        let total = self.params.population_size;
        match order[..] {
            [] => {}
            [only] => alloc[only] = total,
            [first, second, ..] => {
                alloc[first] = total / 2;
                alloc[second] = total - total / 2;
            }
        }
        for &k in order.iter().take(2) {
            self.species[k].last_improved = self.generation;
        }
        alloc
    }

    /// Offspring per species: explicit fitness sharing, then at least one
    /// child for the champion's species (taken from the largest allocation).
    fn allocate(&self, fitness: &[f64], champ_species: Option<usize>) -> Vec<usize> {
        // Explicit fitness sharing: a species' share is the sum of its members' f/|S|,
        // i.e. its mean fitness. Negative fitness is shifted so that the lowest is 0.
        let min = fitness.iter().copied().fold(0.0, f64::min);
        let shares: Vec<f64> = self
            .species
            .iter()
            .map(|s| {
                s.members.iter().map(|&m| fitness[m] - min).sum::<f64>() / s.members.len() as f64
            })
            .collect();
        let mut alloc = allocate_offspring(&shares, self.params.population_size);
        if let Some(c) = champ_species
            && alloc[c] == 0
            && let Some(donor) = (0..alloc.len()).max_by_key(|&i| (alloc[i], usize::MAX - i))
        {
            alloc[donor] -= 1;
            alloc[c] += 1;
        }
        alloc
    }

    /// Reproduction, species by species: each species' elites, then
    /// `alloc[si]` children in all bred from its best members (when
    /// `refocus`: one copy of its champion, then mutated copies of it).
    fn reproduce(
        &mut self,
        fitness: &[f64],
        alloc: &[usize],
        champ_species: Option<usize>,
        refocus: bool,
    ) -> Vec<Genome> {
        let mut next: Vec<Genome> = Vec::with_capacity(self.params.population_size);
        // Each species' members, best first.
        let pools: Vec<Vec<usize>> = self
            .species
            .iter()
            .map(|s| {
                let mut sorted = s.members.clone();
                sorted.sort_by(|&a, &b| fitness[b].total_cmp(&fitness[a]).then(a.cmp(&b)));
                sorted
            })
            .collect();
        for (si, sorted) in pools.iter().enumerate() {
            let n_off = alloc[si];
            if n_off == 0 {
                continue;
            }
            let len = sorted.len();
            let elites = if refocus {
                1
            } else {
                self.elites(len, Some(si) == champ_species).min(n_off)
            };
            for &m in &sorted[..elites] {
                next.push(self.genomes[m].clone());
            }
            if refocus {
                for _ in elites..n_off {
                    let mut child = self.genomes[sorted[0]].clone();
                    mutate(
                        &mut child,
                        &self.spec,
                        &self.params,
                        &mut self.tracker,
                        &mut self.rng,
                    );
                    next.push(child);
                }
                continue;
            }
            let keep =
                ((self.params.survival_threshold * len as f64).ceil() as usize).clamp(1, len);
            let pool = &sorted[..keep];
            for _ in elites..n_off {
                let child = self.offspring(pool, si, &pools, fitness);
                next.push(child);
            }
        }
        next
    }

    /// How many of a species of `len` members are copied unchanged (before
    /// capping at its offspring count): at least one for the champion's.
    fn elites(&self, len: usize, has_champion: bool) -> usize {
        let elites = if len >= self.params.elitism_min_species_size {
            (self.params.elitism_fraction * len as f64).ceil() as usize
        } else {
            0
        };
        if has_champion { elites.max(1) } else { elites }
    }

    /// Moves the compatibility threshold towards `target_species`, if set.
    fn adjust_threshold(&mut self) {
        if let Some(target) = self.params.target_species {
            let n = self.species.len();
            if n < target {
                self.threshold =
                    (self.threshold - self.params.threshold_step).max(self.params.threshold_min);
            } else if n > target {
                self.threshold += self.params.threshold_step;
            }
        }
    }

    /// One child of species `si` bred from `pool` (its best members).
    fn offspring(
        &mut self,
        pool: &[usize],
        si: usize,
        pools: &[Vec<usize>],
        fitness: &[f64],
    ) -> Genome {
        let params = &self.params;
        let rng = &mut self.rng;
        let a = pool[rng.random_range(0..pool.len())];
        let mut child = if rng.random_bool(params.mating_probability) {
            let interspecies =
                pools.len() > 1 && rng.random_bool(params.interspecies_mating_probability);
            let b = if interspecies {
                let mut other = rng.random_range(0..pools.len() - 1);
                if other >= si {
                    other += 1;
                }
                let p = &pools[other];
                let top = ((params.survival_threshold * p.len() as f64).ceil() as usize)
                    .clamp(1, p.len());
                Some(p[rng.random_range(0..top)])
            } else if pool.len() > 1 {
                let mut b = pool[rng.random_range(0..pool.len() - 1)];
                if b == a {
                    b = pool[pool.len() - 1];
                }
                Some(b)
            } else {
                None
            };
            match b {
                Some(b) => {
                    let c = crossover(
                        &self.genomes[a],
                        fitness[a],
                        &self.genomes[b],
                        fitness[b],
                        params,
                        rng,
                    );
                    if rng.random_bool(params.mate_only_probability) {
                        return c;
                    }
                    c
                }
                None => self.genomes[a].clone(),
            }
        } else {
            self.genomes[a].clone()
        };
        mutate(&mut child, &self.spec, params, &mut self.tracker, rng);
        child
    }

    /// Assigns `genomes` to species: each joins the first species whose representative
    /// (a random member of `old`, or the stored one) is within the threshold, else founds
    /// a new species. Empty species are dropped.
    fn speciate(&mut self, genomes: &[Genome], old: &[Genome]) {
        for s in &mut self.species {
            if !old.is_empty() && !s.members.is_empty() {
                let m = s.members[self.rng.random_range(0..s.members.len())];
                s.representative = old[m].clone();
            }
            s.members.clear();
        }
        // Every genome meets many representatives: lay each out once (the
        // representatives in one table, the genome being placed in another).
        let compatible = Compatibility::new(&self.params, self.threshold);
        let mut reps = GeneTable::new();
        for s in &self.species {
            reps.push(&s.representative, &self.params);
        }
        let mut this = GeneTable::new();
        for (i, g) in genomes.iter().enumerate() {
            this.clear();
            this.push(g, &self.params);
            let found =
                (0..self.species.len()).find(|&k| compatible.within(this.view(0), reps.view(k)));
            match found {
                Some(k) => self.species[k].members.push(i),
                None => {
                    reps.push(g, &self.params);
                    self.species.push(Species {
                        id: self.next_species_id,
                        representative: g.clone(),
                        members: vec![i],
                        created: self.generation + u32::from(!old.is_empty()),
                        best_fitness: None,
                        last_improved: self.generation + u32::from(!old.is_empty()),
                    });
                    self.next_species_id += 1;
                }
            }
        }
        self.species.retain(|s| !s.members.is_empty());
    }
}

/// A population as read, not yet checked (the serialised form of [`Population`]).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPopulation {
    params: NeatParams,
    spec: GenomeSpec,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    genomes: Vec<RawGenome>,
    fitness: Option<Vec<f64>>,
    species: Vec<RawSpecies>,
    next_species_id: u32,
    threshold: f64,
    best_ever: Option<RawBestEver>,
    #[serde(default)]
    refocused: Option<u32>,
}

/// A [`Species`] as read, its representative not yet checked.
#[derive(Deserialize)]
struct RawSpecies {
    id: u32,
    representative: RawGenome,
    members: Vec<usize>,
    created: u32,
    best_fitness: Option<f64>,
    last_improved: u32,
}

/// A [`BestEver`] as read, its genome not yet checked.
#[derive(Deserialize)]
struct RawBestEver {
    genome: RawGenome,
    fitness: f64,
    generation: u32,
}

/// Checks a raw genome's invariants and its shape against `spec`.
fn checked_genome(at: GenomeAt, raw: RawGenome, spec: &GenomeSpec) -> Result<Genome, NeatError> {
    let genome = Genome::try_from(raw).map_err(|error| PopulationError::Genome { at, error })?;
    check_genome(at, &genome, spec)?;
    Ok(genome)
}

/// Checks a genome's invariants and that its inputs and outputs match `spec`.
fn check_genome(at: GenomeAt, genome: &Genome, spec: &GenomeSpec) -> Result<(), PopulationError> {
    genome
        .check()
        .map_err(|error| PopulationError::Genome { at, error })?;
    let (inputs, outputs) = (genome.num_inputs(), genome.num_outputs());
    if inputs != spec.inputs || outputs != spec.outputs {
        return Err(PopulationError::Shape {
            at,
            inputs,
            outputs,
            spec_inputs: spec.inputs,
            spec_outputs: spec.outputs,
        });
    }
    // Ids say what a node is in every genome of the run; crossover relies on it.
    for n in genome.nodes() {
        let expected = NodeKind::of_id(n.id, spec);
        if n.kind != expected {
            return Err(PopulationError::NodeKind {
                at,
                id: n.id,
                kind: n.kind.name(),
                expected: expected.name(),
            });
        }
    }
    Ok(())
}

/// Checks the innovation history against itself and the genomes: one number
/// per link and one link per number, every genome link numbered as the
/// history says, split nodes hidden and unique, counters above every id in
/// use. Together these keep later mutations from ever duplicating a number.
fn check_history<'a>(
    tracker: &InnovationTracker,
    spec: &GenomeSpec,
    genomes: impl Iterator<Item = (GenomeAt, &'a Genome)>,
) -> Result<(), PopulationError> {
    use PopulationError as E;
    let mut numbers = BTreeSet::new();
    let mut innovation = None;
    for (_, _, i) in tracker.recorded_links() {
        if !numbers.insert(i) {
            return Err(E::SharedInnovation(i));
        }
        innovation = innovation.max(Some(i));
    }
    let first_hidden = (spec.inputs + spec.outputs) as u64;
    let mut splits = BTreeSet::new();
    let mut node = None;
    for id in tracker.split_ids() {
        if u64::from(id) < first_hidden || !splits.insert(id) {
            return Err(E::SplitNode(id));
        }
        node = node.max(Some(id));
    }
    for (at, g) in genomes {
        for l in g.links() {
            let recorded = tracker.innovation_of(l.from, l.to);
            if recorded != Some(l.innovation) {
                return Err(E::InnovationMismatch {
                    at,
                    from: l.from,
                    to: l.to,
                    innovation: l.innovation,
                    recorded,
                });
            }
        }
        node = node.max(g.nodes().last().map(|n| n.id));
    }
    let counters = [
        (
            "the innovation counter",
            tracker.innovations(),
            "innovation number",
            innovation,
        ),
        ("the node counter", tracker.next_node_id(), "node id", node),
    ];
    for (counter, value, what, used) in counters {
        if let Some(used) = used
            && used >= value
        {
            return Err(E::Counter {
                counter,
                value,
                what,
                used,
            });
        }
    }
    Ok(())
}

impl TryFrom<RawPopulation> for Population {
    type Error = NeatError;

    fn try_from(raw: RawPopulation) -> Result<Population, NeatError> {
        raw.params.validate()?;
        raw.spec.validate()?;
        let spec = &raw.spec;
        let genomes = checked_genomes(raw.genomes, spec)?;
        check_fitness(raw.fitness.as_deref(), genomes.len())?;
        let species = checked_species(raw.species, genomes.len(), spec)?;
        let best_ever = checked_best_ever(raw.best_ever, raw.generation, spec)?;
        if !(raw.threshold.is_finite() && raw.threshold >= 0.0) {
            return Err(PopulationError::Threshold(raw.threshold).into());
        }
        if let Some(generation) = raw.refocused.filter(|&g| g > raw.generation) {
            return Err(PopulationError::FutureGeneration {
                what: "refocused",
                generation,
                current: raw.generation,
            }
            .into());
        }
        let every_genome = genomes
            .iter()
            .enumerate()
            .map(|(i, g)| (GenomeAt::Member(i), g))
            .chain(
                species
                    .iter()
                    .map(|s| (GenomeAt::Representative(s.id), &s.representative)),
            )
            .chain(best_ever.iter().map(|b| (GenomeAt::BestEver, &b.genome)));
        check_history(&raw.tracker, spec, every_genome)?;
        check_species_counter(&species, raw.next_species_id)?;

        Ok(Population {
            params: raw.params,
            spec: raw.spec,
            seed: raw.seed,
            generation: raw.generation,
            rng: raw.rng,
            tracker: raw.tracker,
            genomes,
            fitness: raw.fitness,
            species,
            next_species_id: raw.next_species_id,
            threshold: raw.threshold,
            best_ever,
            refocused: raw.refocused,
        })
    }
}

/// The members: at least one, each checked against `spec`.
fn checked_genomes(raw: Vec<RawGenome>, spec: &GenomeSpec) -> Result<Vec<Genome>, NeatError> {
    if raw.is_empty() {
        return Err(PopulationError::Empty.into());
    }
    raw.into_iter()
        .enumerate()
        .map(|(i, g)| checked_genome(GenomeAt::Member(i), g, spec))
        .collect()
}

/// Fitness values, if recorded: one per genome, all finite.
fn check_fitness(fitness: Option<&[f64]>, genomes: usize) -> Result<(), PopulationError> {
    if let Some(fitness) = fitness {
        if fitness.len() != genomes {
            return Err(PopulationError::FitnessCount {
                given: fitness.len(),
                genomes,
            });
        }
        if let Some(i) = fitness.iter().position(|f| !f.is_finite()) {
            return Err(PopulationError::NonFiniteFitness(format!("genome {i}")));
        }
    }
    Ok(())
}

/// Species: unique ids, members that partition the `n` genomes, finite
/// records, representatives checked against `spec`.
fn checked_species(
    raw: Vec<RawSpecies>,
    n: usize,
    spec: &GenomeSpec,
) -> Result<Vec<Species>, NeatError> {
    use PopulationError as E;
    let mut ids = BTreeSet::new();
    let mut listed = vec![0usize; n];
    let mut species = Vec::with_capacity(raw.len());
    for s in raw {
        if !ids.insert(s.id) {
            return Err(E::DuplicateSpecies(s.id).into());
        }
        if s.members.is_empty() {
            return Err(E::EmptySpecies(s.id).into());
        }
        for &member in &s.members {
            let count = listed.get_mut(member).ok_or(E::MissingMember {
                species: s.id,
                member,
                genomes: n,
            })?;
            *count += 1;
        }
        if s.best_fitness.is_some_and(|f| !f.is_finite()) {
            return Err(E::NonFiniteFitness(format!("species {}", s.id)).into());
        }
        species.push(Species {
            id: s.id,
            representative: checked_genome(GenomeAt::Representative(s.id), s.representative, spec)?,
            members: s.members,
            created: s.created,
            best_fitness: s.best_fitness,
            last_improved: s.last_improved,
        });
    }
    if let Some(member) = listed.iter().position(|&c| c != 1) {
        return Err(E::Membership {
            member,
            count: listed[member],
        }
        .into());
    }
    Ok(species)
}

/// The best-ever record, if any: finite fitness, not from a generation
/// after `current`, its genome checked against `spec`.
fn checked_best_ever(
    raw: Option<RawBestEver>,
    current: u32,
    spec: &GenomeSpec,
) -> Result<Option<BestEver>, NeatError> {
    let Some(b) = raw else {
        return Ok(None);
    };
    if !b.fitness.is_finite() {
        return Err(PopulationError::NonFiniteFitness("the best-ever genome".into()).into());
    }
    if b.generation > current {
        return Err(PopulationError::FutureGeneration {
            what: "the best-ever record",
            generation: b.generation,
            current,
        }
        .into());
    }
    Ok(Some(BestEver {
        genome: checked_genome(GenomeAt::BestEver, b.genome, spec)?,
        fitness: b.fitness,
        generation: b.generation,
    }))
}

/// The species counter is above every species id in use.
fn check_species_counter(species: &[Species], next_species_id: u32) -> Result<(), PopulationError> {
    if let Some(used) = species.iter().map(|s| s.id).max()
        && used >= next_species_id
    {
        return Err(PopulationError::Counter {
            counter: "next_species_id",
            value: next_species_id,
            what: "species id",
            used,
        });
    }
    Ok(())
}

/// Splits `total` offspring among species in proportion to `shares` (largest remainder,
/// ties to the earlier species); always sums exactly to `total`. All-zero shares split
/// evenly.
pub fn allocate_offspring(shares: &[f64], total: usize) -> Vec<usize> {
    if shares.is_empty() {
        return Vec::new();
    }
    let sum: f64 = shares.iter().filter(|s| s.is_finite() && **s > 0.0).sum();
    let quotas: Vec<f64> = if sum > 0.0 {
        shares
            .iter()
            .map(|&s| {
                if s.is_finite() && s > 0.0 {
                    s / sum * total as f64
                } else {
                    0.0
                }
            })
            .collect()
    } else {
        vec![total as f64 / shares.len() as f64; shares.len()]
    };
    let mut alloc: Vec<usize> = quotas.iter().map(|q| q.floor() as usize).collect();
    let assigned: usize = alloc.iter().sum();
    let mut rest = total.saturating_sub(assigned);
    let mut order: Vec<usize> = (0..shares.len()).collect();
    order.sort_by(|&a, &b| {
        let ra = quotas[a] - quotas[a].floor();
        let rb = quotas[b] - quotas[b].floor();
        rb.total_cmp(&ra).then(a.cmp(&b))
    });
    let mut k = 0;
    while rest > 0 {
        alloc[order[k % order.len()]] += 1;
        rest -= 1;
        k += 1;
    }
    // Floating error could over-assign by one; take it back from the largest.
    while alloc.iter().sum::<usize>() > total {
        let i = (0..alloc.len()).max_by_key(|&i| alloc[i]).unwrap_or(0);
        alloc[i] -= 1;
    }
    alloc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocation_sums_exactly() {
        assert_eq!(allocate_offspring(&[1.0, 1.0, 1.0], 100), vec![34, 33, 33]);
        assert_eq!(allocate_offspring(&[0.0, 0.0], 5), vec![3, 2]);
        assert_eq!(allocate_offspring(&[3.0, 1.0], 8), vec![6, 2]);
        assert_eq!(allocate_offspring(&[], 8), Vec::<usize>::new());
    }

    /// Parameters under which a mutated copy is an exact copy.
    fn frozen(limit: Option<u32>) -> NeatParams {
        NeatParams {
            population_size: 40,
            compatibility_threshold: 0.5,
            add_node_probability: 0.0,
            add_link_probability: 0.0,
            weight_mutation_probability: 0.0,
            toggle_enable_probability: 0.0,
            activation_mutation_probability: 0.0,
            population_stagnation_limit: limit,
            ..NeatParams::plain_neat()
        }
    }

    #[test]
    fn population_stagnation_refocuses_on_two_champions() {
        let mut pop = Population::new(frozen(Some(2)), GenomeSpec::plain(3, 1), 7).unwrap();
        // Constant fitness: the best never rises after generation 0.
        for _ in 0..2 {
            pop.evaluate(|_, _| 1.0);
            assert!(pop.species().len() >= 2, "the test needs two species");
            pop.next_generation();
        }
        assert_eq!(pop.refocused, None);
        pop.evaluate(|_, _| 1.0);
        let champions: Vec<Genome> = pop.species()[..2]
            .iter()
            .map(|s| pop.genomes()[s.members[0]].clone())
            .collect();
        pop.next_generation();
        assert_eq!(pop.refocused, Some(2));
        for (k, champion) in champions.iter().enumerate() {
            let copies = pop.genomes().iter().filter(|g| *g == champion).count();
            assert_eq!(copies, 20, "champion {k}");
        }
        // The refocus survives a checkpoint; one dated after the current generation is refused.
        let json = pop.to_json().unwrap();
        assert_eq!(Population::from_json(&json).unwrap(), pop);
        let future = json.replace("\"refocused\":2", "\"refocused\":99");
        assert_ne!(future, json);
        let e = Population::from_json(&future).unwrap_err().to_string();
        assert!(e.contains("refocused") && e.contains("99"), "{e}");
    }

    #[test]
    fn without_population_stagnation_limit_nothing_is_refocused_or_written() {
        let mut pop = Population::new(frozen(None), GenomeSpec::plain(3, 1), 7).unwrap();
        for _ in 0..30 {
            pop.evaluate(|_, _| 1.0);
            pop.next_generation();
        }
        assert_eq!(pop.refocused, None);
        let json = pop.to_json().unwrap();
        assert!(!json.contains("refocused") && !json.contains("population_stagnation_limit"));
    }

    #[test]
    fn argmax_first_of_ties() {
        assert_eq!(argmax(&[1.0, 3.0, 3.0]), Some(1));
        assert_eq!(argmax(&[]), None);
    }
}

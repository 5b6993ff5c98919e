//! What a run records of its genomes: the best ever and per-generation statistics.

use serde::{Deserialize, Serialize};

use crate::genome::Genome;
use crate::stats::{self, argmax};

/// The best genome seen so far in the run (see [`Population::best_ever`](super::Population::best_ever)).
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
    /// (How every strategy keeps its best ever, one of another crate too.)
    pub fn offer(
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

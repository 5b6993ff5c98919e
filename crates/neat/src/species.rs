//! Species: groups of compatible genomes sharing fitness.

use serde::{Deserialize, Serialize};

use crate::genome::Genome;

/// A species of the current generation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Species {
    /// Unique id within the run.
    pub id: u32,
    /// Genome new offspring are compared with.
    pub representative: Genome,
    /// Indices (into the population's genomes) of the members, ascending.
    pub members: Vec<usize>,
    /// Generation in which the species appeared.
    pub created: u32,
    /// Best raw fitness any member ever reached (None before the first evaluation).
    pub best_fitness: Option<f64>,
    /// Generation in which `best_fitness` last improved.
    pub last_improved: u32,
}

impl Species {
    /// Generations since the species last improved, as of `generation`.
    pub fn stagnation(&self, generation: u32) -> u32 {
        generation.saturating_sub(self.last_improved)
    }
}

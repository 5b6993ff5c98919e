//! When a run stops, and why it stopped, as data.

use std::sync::atomic::AtomicBool;

use serde::{Deserialize, Serialize};

/// When a run stops; every criterion that is set is checked after each generation.
#[derive(Debug, Clone, Copy, Default)]
pub struct StopCriteria<'a> {
    /// Stop once this many generations of the run are done.
    pub generations: Option<u32>,
    /// Stop once a genome reaches this fitness.
    pub target_fitness: Option<f64>,
    /// Stop when the best-ever fitness has not improved for this many generations.
    pub stagnation: Option<u32>,
    /// Stop (after finishing the generation) once this flag is set, e.g. by Ctrl-C.
    pub interrupt: Option<&'a AtomicBool>,
}

impl<'a> StopCriteria<'a> {
    /// Stop after `n` generations.
    pub fn generations(n: u32) -> Self {
        StopCriteria {
            generations: Some(n),
            ..StopCriteria::default()
        }
    }

    /// Also stop once a genome reaches `fitness`.
    pub fn or_target(mut self, fitness: f64) -> Self {
        self.target_fitness = Some(fitness);
        self
    }

    /// Also stop when the best has not improved for `n` generations.
    pub fn or_stagnation(mut self, n: u32) -> Self {
        self.stagnation = Some(n);
        self
    }

    /// Also stop once `flag` is set.
    pub fn or_interrupt(mut self, flag: &'a AtomicBool) -> Self {
        self.interrupt = Some(flag);
        self
    }
}

/// Why a run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum StopReason {
    /// The requested number of generations is done.
    Generations(u32),
    /// A genome reached the target fitness.
    TargetFitness {
        /// The fitness reached.
        fitness: f64,
        /// The run's generation (1-based) in which it was reached.
        generation: u32,
    },
    /// The best-ever fitness did not improve for this many generations.
    Stagnation(u32),
    /// The interrupt flag was set.
    Interrupted,
}

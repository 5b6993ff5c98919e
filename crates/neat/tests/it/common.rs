//! A strategy that is not NEAT, for the driver tests: a (1+λ) evolution
//! strategy that mutates the best genome so far with NEAT's operators.

use rand::SeedableRng;
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::mutation::mutate;
use vivae_neat::{
    BestEver, GenerationStats, Genome, GenomeSpec, InnovationTracker, NeatError, NeatParams,
};

/// (1+λ)-ES: λ mutants of the best genome so far per generation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OnePlusLambda {
    spec: GenomeSpec,
    params: NeatParams,
    tracker: InnovationTracker,
    rng: Pcg64,
    seed: u64,
    lambda: usize,
    generation: u32,
    children: Vec<Genome>,
    fitness: Option<Vec<f64>>,
    best: Option<BestEver>,
}

impl OnePlusLambda {
    /// Generation 0: `lambda` minimal genomes.
    pub fn new(spec: GenomeSpec, lambda: usize, seed: u64) -> OnePlusLambda {
        let params = NeatParams::plain_neat();
        let mut rng = Pcg64::seed_from_u64(seed);
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        let children = (0..lambda)
            .map(|_| Genome::minimal(&spec, &params, &mut tracker, &mut rng))
            .collect();
        OnePlusLambda {
            spec,
            params,
            tracker,
            rng,
            seed,
            lambda,
            generation: 0,
            children,
            fitness: None,
            best: None,
        }
    }
}

impl Strategy for OnePlusLambda {
    fn ask(&mut self) -> Batch<'_> {
        self.prepare();
        Batch::new(&self.children, self.seed, self.generation)
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        if evaluations.len() != self.children.len() {
            return Err(NeatError::FitnessCount {
                given: evaluations.len(),
                genomes: self.children.len(),
            });
        }
        let fitness: Vec<f64> = evaluations
            .iter()
            .map(|e| {
                if e.fitness.is_finite() {
                    e.fitness
                } else {
                    0.0
                }
            })
            .collect();
        for (child, &f) in self.children.iter().zip(&fitness) {
            if self.best.as_ref().is_none_or(|b| f > b.fitness) {
                self.best = Some(BestEver {
                    genome: child.clone(),
                    fitness: f,
                    generation: self.generation,
                });
            }
        }
        self.fitness = Some(fitness);
        Ok(())
    }

    fn prepare(&mut self) {
        let (Some(_), Some(best)) = (self.fitness.take(), &self.best) else {
            return;
        };
        self.generation += 1;
        let parent = best.genome.clone();
        self.children = (0..self.lambda)
            .map(|_| {
                let mut child = parent.clone();
                mutate(
                    &mut child,
                    &self.spec,
                    &self.params,
                    &mut self.tracker,
                    &mut self.rng,
                );
                child
            })
            .collect();
    }

    fn generation(&self) -> u32 {
        self.generation
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        let fitness = self.fitness.as_ref()?;
        let i = (0..fitness.len()).reduce(|a, b| if fitness[b] > fitness[a] { b } else { a })?;
        Some((&self.children[i], fitness[i]))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.best.as_ref()
    }

    fn stats(&self) -> GenerationStats {
        let fitness = self.fitness.as_deref().unwrap_or_default();
        GenerationStats::of_batch(self.generation, &self.children, fitness)
    }
}

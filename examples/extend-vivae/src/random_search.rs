//! Random search over NEAT genomes: every generation is
//! `neat.population_size` new genomes, each a minimal one with random
//! weights mutated [`MUTATIONS`] times; the best genome ever found is kept.
//! It needs no settings section, writes no files of its own and adds no
//! columns: its entry says so.

use rand::SeedableRng;
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};
use vivae_lab::Result;
use vivae_lab::io::bad_input;
use vivae_lab::search::{Needs, RunStrategy, Search, Start, StrategyEntry};
use vivae_neat::NeatParams;
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::mutation::mutate;
use vivae_neat::stats::argmax;
use vivae_neat::{BestEver, GenerationStats, Genome, GenomeSpec, InnovationTracker, NeatError};

/// The strategy's registration (`--strategy random-search`).
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "random-search",
    needs: Needs {
        behaviour: false,
        metrics: false,
    },
    takes_population: false,
    variant: "RandomSearch",
    from_state,
    extra_columns: "",
    build,
    header_line: |c| {
        format!(
            "\n  strategy: random search, {} genomes a generation",
            c.neat.population_size
        )
    },
    report: |_, _, _| Ok(None),
    files: &[],
    settings: None,
};

/// Mutations of each new genome.
const MUTATIONS: usize = 3;

/// The search's state: what a checkpoint holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RandomSearch {
    spec: GenomeSpec,
    params: NeatParams,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    batch: Vec<Genome>,
    fitness: Vec<f64>,
    best: Option<BestEver>,
}

/// Generation 0, drawn from the run seed.
fn build(Start { config, spec, .. }: Start<'_>) -> Result<Search> {
    let params = config.neat.clone();
    let refused = |e: NeatError| bad_input(format!("strategy.kind = random-search: {e}"));
    params.validate().map_err(refused)?;
    spec.validate().map_err(refused)?;
    let seed = config.experiment.seed;
    let mut search = RandomSearch {
        tracker: InnovationTracker::new((spec.inputs + spec.outputs) as u32),
        spec,
        params,
        seed,
        generation: 0,
        rng: Pcg64::seed_from_u64(seed),
        batch: Vec::new(),
        fitness: Vec::new(),
        best: None,
    };
    search.draw();
    Ok(Search::of(search))
}

/// A checkpoint's state, checked: settings and genomes valid, the told
/// fitness one per genome of the batch.
fn from_state(text: &str) -> serde_json::Result<Search> {
    let s: RandomSearch = serde_json::from_str(text)?;
    let mut genomes = s.batch.iter().chain(s.best.as_ref().map(|b| &b.genome));
    let told = s.fitness.is_empty() || s.fitness.len() == s.batch.len();
    let valid = s.params.validate().is_ok() && s.spec.validate().is_ok();
    if told && valid && genomes.all(|g| g.check().is_ok()) {
        Ok(Search::of(s))
    } else {
        let why = "random-search state: settings, genomes or fitness amiss";
        Err(serde::de::Error::custom(why))
    }
}

impl RandomSearch {
    /// Draws a new batch.
    fn draw(&mut self) {
        let RandomSearch {
            spec,
            params,
            rng,
            tracker,
            ..
        } = self;
        self.batch = (0..params.population_size)
            .map(|_| {
                let mut g = Genome::minimal(spec, params, tracker, rng);
                (0..MUTATIONS).for_each(|_| mutate(&mut g, spec, params, tracker, rng));
                g
            })
            .collect();
    }
}

impl Strategy for RandomSearch {
    fn ask(&mut self) -> Batch<'_> {
        self.prepare();
        Batch::new(&self.batch, self.seed, self.generation)
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> std::result::Result<(), NeatError> {
        let (given, genomes) = (evaluations.len(), self.batch.len());
        if given != genomes {
            return Err(NeatError::FitnessCount { given, genomes });
        }
        self.fitness = evaluations.iter().map(Evaluation::finite_fitness).collect();
        BestEver::offer(&mut self.best, &self.batch, &self.fitness, self.generation);
        Ok(())
    }

    /// Once told: a new batch is the next generation.
    fn prepare(&mut self) {
        if !self.fitness.is_empty() {
            self.fitness.clear();
            self.generation += 1;
            self.draw();
        }
    }

    fn generation(&self) -> u32 {
        self.generation
    }

    /// The batch's first fittest genome.
    fn champion(&self) -> Option<(&Genome, f64)> {
        argmax(&self.fitness).map(|i| (&self.batch[i], self.fitness[i]))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.best.as_ref()
    }

    fn stats(&self) -> GenerationStats {
        GenerationStats::of_batch(self.generation, &self.batch, &self.fitness)
    }
}

impl RunStrategy for RandomSearch {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn batch(&self) -> Vec<Genome> {
        self.batch.clone()
    }
}

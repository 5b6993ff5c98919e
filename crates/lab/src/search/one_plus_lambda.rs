//! A (1+λ) evolution strategy over NEAT genomes: every generation, λ
//! mutants of the parent (the best genome so far); the best of them becomes
//! the parent when it is not worse. It adds the parent's fitness to
//! `generations.csv`, writes the parent (`parent.json`) with each
//! checkpoint, and reads λ from `[strategy.one_plus_lambda]`.

use std::path::Path;

use rand::SeedableRng;
use rand_pcg::Pcg64;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::mutation::mutate;
use vivae_neat::{BestEver, GenerationStats, Genome, GenomeSpec, InnovationTracker};
use vivae_neat::{NeatError, NeatParams};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{bad_input, write_atomic};
use crate::search::{Needs, RunStrategy, Search, Settings, Start, StrategyConfig, StrategyEntry};
use crate::search::{BehaviourSpace, StrategyReport, StrategySettings};

/// The (1+λ)-ES's registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "one-plus-lambda",
    needs: Needs {
        behaviour: false,
        metrics: false,
    },
    takes_population: false,
    variant: "OnePlusLambda",
    from_state,
    extra_columns: ",parent_fitness",
    build,
    header_line: |c| match StrategyConfig::of(c).settings::<OnePlusLambdaConfig>() {
        Ok(s) => format!("\n  strategy: (1+{}) evolution strategy", s.lambda),
        Err(_) => String::new(),
    },
    // The report draws its column of generations.csv under this.
    report: |_, _, _| {
        Ok(Some(StrategyReport {
            kind: STRATEGY.kind,
            heading: "(1+λ) evolution strategy".into(),
            note: "The parent's fitness per generation: the best genome so far (parent.json)."
                .into(),
            ..StrategyReport::default()
        }))
    },
    files: &[PARENT],
    settings: Some(Settings::of::<OnePlusLambdaConfig>()),
};

/// The parent and its fitness, written with each checkpoint.
const PARENT: &str = "parent.json";

/// Most mutants per generation: a batch of genomes is held in memory.
const MAX_LAMBDA: usize = 1_000_000;

/// The (1+λ) evolution strategy's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct OnePlusLambdaConfig {
    /// Mutants of the parent evaluated per generation (λ); generation 0 is
    /// λ minimal genomes.
    pub lambda: usize,
}

impl Default for OnePlusLambdaConfig {
    fn default() -> Self {
        OnePlusLambdaConfig { lambda: 10 }
    }
}

impl StrategySettings for OnePlusLambdaConfig {
    const SECTION: &'static str = "one_plus_lambda";

    fn validate(&self, _metrics: &[&str]) -> std::result::Result<(), String> {
        match self.lambda {
            1..=MAX_LAMBDA => Ok(()),
            n => Err(format!("lambda = {n}: must be in 1..={MAX_LAMBDA}")),
        }
    }
}

/// The strategy's state: what a checkpoint holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OnePlusLambda {
    spec: GenomeSpec,
    params: NeatParams,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    /// The genomes of this generation (λ of them).
    batch: Vec<Genome>,
    /// Their fitness once told (empty before).
    fitness: Vec<f64>,
    /// The best genome so far, the latest of equals, and its fitness.
    parent: Option<(Genome, f64)>,
    best: Option<BestEver>,
}

/// Generation 0: λ minimal genomes drawn from the run seed.
fn build(Start { config, spec, .. }: Start<'_>) -> Result<Search> {
    let s: OnePlusLambdaConfig = StrategyConfig::of(config).settings().map_err(bad_input)?;
    let bad = |e: String| bad_input(format!("strategy.one_plus_lambda.{e}"));
    s.validate(&[]).map_err(bad)?;
    let (params, seed) = (config.neat.clone(), config.experiment.seed);
    let refused = |e: NeatError| bad_input(format!("strategy.one-plus-lambda: {e}"));
    params.validate().map_err(refused)?;
    spec.validate().map_err(refused)?;
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
    let batch = (0..s.lambda)
        .map(|_| Genome::minimal(&spec, &params, &mut tracker, &mut rng))
        .collect();
    Ok(Search::of(OnePlusLambda {
        spec,
        params,
        seed,
        generation: 0,
        rng,
        tracker,
        batch,
        fitness: Vec::new(),
        parent: None,
        best: None,
    }))
}

/// A checkpoint's state, checked: settings, genomes, fitness and records agree.
fn from_state(text: &str) -> serde_json::Result<Search> {
    use serde::de::Error as _;
    let es: OnePlusLambda = serde_json::from_str(text)?;
    let bad = |why: String| serde_json::Error::custom(format!("one-plus-lambda state: {why}"));
    es.params.validate().map_err(|e| bad(e.to_string()))?;
    es.spec.validate().map_err(|e| bad(e.to_string()))?;
    let genomes = es.batch.iter().chain(es.parent.as_ref().map(|p| &p.0));
    for g in genomes.chain(es.best.as_ref().map(|b| &b.genome)) {
        g.check().map_err(|e| bad(e.to_string()))?;
    }
    let told_all = es.fitness.is_empty() || es.fitness.len() == es.batch.len();
    let finite = (es.fitness.iter().chain(es.parent.as_ref().map(|p| &p.1)))
        .chain(es.best.as_ref().map(|b| &b.fitness))
        .all(|f| f.is_finite());
    let parent = es.parent.is_some() || (es.generation == 0 && es.fitness.is_empty());
    let past = es.best.as_ref().is_none_or(|b| b.generation <= es.generation);
    match (es.batch.len(), told_all && finite && parent && past) {
        (1..=MAX_LAMBDA, true) => Ok(Search::of(es)),
        (n, _) => Err(bad(format!("{n} genomes, or fitness, parent or best amiss"))),
    }
}

impl Strategy for OnePlusLambda {
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
        let Some((genome, fitness)) = self.champion().map(|(g, f)| (g.clone(), f)) else {
            return Ok(());
        };
        if self.best.as_ref().is_none_or(|b| fitness > b.fitness) {
            let generation = self.generation;
            let genome = genome.clone();
            self.best = Some(BestEver {
                genome,
                fitness,
                generation,
            });
        }
        // Not worse: the search drifts across plateaus.
        if self.parent.as_ref().is_none_or(|p| fitness >= p.1) {
            self.parent = Some((genome, fitness));
        }
        Ok(())
    }

    /// Once told: λ mutants of the parent are the next generation.
    fn prepare(&mut self) {
        let Some((parent, _)) = self.parent.as_ref().filter(|_| !self.fitness.is_empty()) else {
            return;
        };
        for child in &mut self.batch {
            *child = parent.clone();
            mutate(child, &self.spec, &self.params, &mut self.tracker, &mut self.rng);
        }
        self.fitness.clear();
        self.generation += 1;
    }

    fn generation(&self) -> u32 {
        self.generation
    }

    /// The batch's first fittest genome.
    fn champion(&self) -> Option<(&Genome, f64)> {
        let first_best = |b: usize, i: usize| match self.fitness[i] > self.fitness[b] {
            true => i,
            false => b,
        };
        let best = (0..self.fitness.len()).reduce(first_best)?;
        Some((&self.batch[best], self.fitness[best]))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.best.as_ref()
    }

    fn stats(&self) -> GenerationStats {
        GenerationStats::of_batch(self.generation, &self.batch, &self.fitness)
    }
}

/// The parent as `parent.json` holds it.
#[derive(Serialize)]
struct ParentFile<'a> {
    fitness: f64,
    genome: &'a Genome,
}

impl RunStrategy for OnePlusLambda {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn batch(&self) -> Vec<Genome> {
        self.batch.clone()
    }

    fn extra_fields(&self) -> String {
        self.parent
            .as_ref()
            .map_or_else(|| ",".into(), |p| format!(",{}", p.1))
    }

    fn summary_fields(&self) -> String {
        let fitness = self.parent.as_ref().map_or(f64::NAN, |p| p.1);
        format!(" parent_fitness={fitness:.3}")
    }

    fn write_outputs(&self, dir: &Path, _config: &Config, _space: &BehaviourSpace) -> Result<()> {
        let Some((genome, fitness)) = &self.parent else {
            return Ok(());
        };
        let parent = ParentFile {
            fitness: *fitness,
            genome,
        };
        let text = serde_json::to_string(&parent).map_err(|e| Error::Serialize {
            what: "the parent",
            reason: e.to_string(),
        })?;
        write_atomic(&dir.join(PARENT), text.as_bytes())
    }
}

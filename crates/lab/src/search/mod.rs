//! The search a run holds: one [`Search`] value, whichever strategy the
//! config's `[strategy]` section names, that the driver runs and the
//! checkpoint stores. It is a [`Strategy`] by delegation to the one inside.
//!
//! Each strategy is one file here: its [`StrategyEntry`] (registered in
//! [`STRATEGIES`]: the columns it adds to `generations.csv`, how it is built
//! from the config, its header line) and its [`RunStrategy`] (its fields of
//! each row and of the summary line, the files it writes with each
//! checkpoint). The enum [`Search`] is the checkpoint's format: a variant
//! per strategy.

pub mod files;
mod map_elites;
mod neat;
mod novelty;
mod nsga2;

use std::path::Path;

use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::hyperneat::{CPPN_INPUTS, leo_seeded_genomes};
use vivae_neat::strategies::{MapElites, NoveltySearch, Nsga2};
use vivae_neat::{
    BestEver, GenerationStats, Genome, GenomeSpec, NeatError, NeatParams, Population,
};

use crate::config::Config;
use crate::config::es::ES_LEO_OUTPUT;
use crate::config::strategy::StrategyKind;
use crate::error::Result;
use crate::io::bad_input;

/// The generator stream of LEO's seeded generation 0, apart from the
/// population's own (which is seeded with the run seed itself).
const LEO_SEED_STREAM: u64 = 0x1e05_eed0;

/// Generation 0 of `substrate.es.leo_seed`: `params.population_size`
/// genomes of LEO's Gaussian locality seed along x feeding CPPN output
/// [`ES_LEO_OUTPUT`], one innovation history for all, drawn from the run
/// seed `seed` (the population built from them takes `seed` itself).
pub fn leo_seeded(spec: &GenomeSpec, params: &NeatParams, seed: u64) -> Result<Vec<Genome>> {
    if spec.inputs != CPPN_INPUTS || spec.outputs <= ES_LEO_OUTPUT {
        return Err(bad_input(format!(
            "substrate.es.leo_seed = true: the seed needs a substrate CPPN ({CPPN_INPUTS} inputs, output {ES_LEO_OUTPUT}), not {} inputs and {} outputs",
            spec.inputs, spec.outputs
        )));
    }
    Ok(leo_seeded_genomes(
        spec,
        params,
        params.population_size,
        seed ^ LEO_SEED_STREAM,
        ES_LEO_OUTPUT,
    ))
}

/// Generation 0 of a NEAT population for `config`'s substrate: LEO's
/// seeded genomes with `substrate.es.leo_seed`, minimal genomes otherwise.
pub fn initial_population(
    config: &Config,
    params: NeatParams,
    spec: GenomeSpec,
    seed: u64,
) -> Result<Population> {
    if config.substrate.es.leo_seed {
        let genomes = leo_seeded(&spec, &params, seed)?;
        Population::from_genomes(params, spec, genomes, seed)
            .map_err(|e| bad_input(format!("substrate.es.leo_seed: {e}")))
    } else {
        Population::new(params, spec, seed).map_err(|e| bad_input(format!("neat: {e}")))
    }
}

/// A run's search strategy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Search {
    /// NEAT's population (the paper's).
    Neat(Population),
    /// Novelty search over a NEAT population.
    Novelty(NoveltySearch),
    /// MAP-Elites.
    MapElites(MapElites),
    /// NSGA-II.
    Nsga2(Nsga2),
}

/// Every strategy a run can search with; `strategy.kind` names one.
pub static STRATEGIES: [&StrategyEntry; 4] = [
    &neat::STRATEGY,
    &novelty::STRATEGY,
    &map_elites::STRATEGY,
    &nsga2::STRATEGY,
];

/// Calls `$f` on the strategy inside `$search`, whichever it is.
macro_rules! each {
    ($search:expr, $s:ident => $f:expr) => {
        match $search {
            Search::Neat($s) => $f,
            Search::Novelty($s) => $f,
            Search::MapElites($s) => $f,
            Search::Nsga2($s) => $f,
        }
    };
}

/// The box (lower, upper) the behaviour descriptors lie in.
pub type Bounds = (Vec<f64>, Vec<f64>);

/// A strategy's registration: what a run needs of it before it exists.
pub struct StrategyEntry {
    /// Its `strategy.kind`.
    pub kind: StrategyKind,
    /// The columns it adds to `generations.csv` (after NEAT's), each with its
    /// leading comma.
    pub extra_columns: &'static str,
    /// Generation 0 of it for `config` over genomes of shape `spec` whose
    /// behaviour descriptors lie in `bounds`, from `init`'s genomes if given.
    pub build: fn(&Config, GenomeSpec, Bounds, Option<&Population>) -> Result<Search>,
    /// The line the run's header says of it (with its leading line break), or empty.
    pub header_line: fn(&Config) -> String,
}

impl std::fmt::Debug for StrategyEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StrategyEntry")
            .field("kind", &self.kind)
            .finish()
    }
}

/// The registration of strategy `kind`.
pub fn entry(kind: StrategyKind) -> &'static StrategyEntry {
    (STRATEGIES.iter().copied())
        .find(|e| e.kind == kind)
        .expect("every strategy kind is registered")
}

/// What a run needs of its search strategy beside ask and tell.
pub trait RunStrategy {
    /// Its registration.
    fn entry(&self) -> &'static StrategyEntry;

    /// The NEAT population inside, for strategies that breed one.
    fn population(&self) -> Option<&Population> {
        None
    }

    /// The genomes of the batch to evaluate next.
    fn batch(&self) -> Vec<Genome>;

    /// The batch's task fitnesses once told, in batch order.
    fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        evaluations.iter().map(Evaluation::finite_fitness).collect()
    }

    /// Its values of [`StrategyEntry::extra_columns`] for the generation just
    /// told, each with its leading comma.
    fn extra_fields(&self) -> String {
        String::new()
    }

    /// Its `key=value` fields of the summary line, each with a leading space.
    fn summary_fields(&self) -> String {
        String::new()
    }

    /// Writes its own files into the run directory `dir` (with each checkpoint).
    fn write_outputs(&self, _dir: &Path, _config: &Config) -> Result<()> {
        Ok(())
    }

    /// What its end-of-run figure shows after `generation`, if it has one
    /// (the program draws it).
    fn figure(&self, _config: &Config, _generation: u32) -> Option<StrategyFigure> {
        None
    }
}

/// A strategy's end-of-run figure, as data: the program draws each kind.
#[derive(Debug, Clone, PartialEq)]
pub enum StrategyFigure {
    /// An archive on a 2-D grid of cells, as a heat map of its elites' fitness.
    Grid {
        /// The figure's title.
        title: String,
        /// Names of the two behaviour coordinates (x, then y).
        axes: [String; 2],
        /// Lower bound of each coordinate.
        lower: [f64; 2],
        /// Upper bound of each coordinate.
        upper: [f64; 2],
        /// Cells along each coordinate.
        bins: [usize; 2],
        /// `(cell, fitness)` of every elite; cell = x bin × `bins[1]` + y bin.
        elites: Vec<(usize, f64)>,
    },
    /// A population scored on two objectives, and its Pareto front.
    Front {
        /// The figure's title.
        title: String,
        /// The two objectives as configs write them (`fitness`, `-contacts`).
        objectives: [String; 2],
        /// Every scored member's two objective values.
        population: Vec<[f64; 2]>,
        /// The front's members' values, fittest first (as `front.csv` numbers them).
        front: Vec<[f64; 2]>,
    },
}

/// The header line of the strategies that search on a behaviour descriptor.
pub(crate) fn behaviour_line(c: &Config) -> String {
    let s = &c.strategy;
    format!(
        "\n  strategy: {}, behaviour {}",
        s.kind.name(),
        s.behaviour.name()
    )
}

/// Generation 0 of a NEAT population for `config`: `init`'s genomes (only
/// they carry over: fitness, species and the champion were measured on
/// another substrate and mean nothing here), or [`initial_population`].
pub(crate) fn starting_population(
    config: &Config,
    spec: GenomeSpec,
    init: Option<&Population>,
) -> Result<Population> {
    let (neat, seed) = (config.neat.clone(), config.experiment.seed);
    match init {
        Some(p) => Population::from_genomes(neat, spec, p.genomes().to_vec(), seed)
            .map_err(|e| bad_input(format!("initial population: {e}"))),
        None => initial_population(config, neat, spec, seed),
    }
}

/// Refuses a starting population for a strategy that starts from minimal genomes.
pub(crate) fn refuse_init(config: &Config, init: Option<&Population>) -> Result<()> {
    match init {
        None => Ok(()),
        Some(_) => Err(bad_input(format!(
            "experiment.init_population: a {} run starts from minimal genomes (only neat and novelty runs start from a population)",
            config.strategy.kind.name()
        ))),
    }
}

impl Search {
    /// Generation 0 of the strategy of `config` over genomes of shape `spec`
    /// whose behaviour descriptors lie in the box `bounds` (lower, upper),
    /// seeded with `experiment.seed`; NEAT and novelty search may start from
    /// `init`'s genomes instead.
    pub fn new(
        config: &Config,
        spec: GenomeSpec,
        bounds: Bounds,
        init: Option<&Population>,
    ) -> Result<Search> {
        (entry(config.strategy.kind).build)(config, spec, bounds, init)
    }

    /// The strategy inside, as a run uses it.
    pub fn strategy(&self) -> &dyn RunStrategy {
        each!(self, s => s)
    }

    /// Which strategy this is.
    pub fn kind(&self) -> StrategyKind {
        self.strategy().entry().kind
    }

    /// The NEAT population, for NEAT and novelty search.
    pub fn population(&self) -> Option<&Population> {
        self.strategy().population()
    }

    /// The genomes of the batch to evaluate next.
    pub fn batch(&self) -> Vec<Genome> {
        self.strategy().batch()
    }

    /// The batch's task fitnesses once told, in batch order (NEAT's as its
    /// population holds them; novelty search's population holds novelty).
    pub fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        self.strategy().fitnesses(evaluations)
    }

    /// `[species id, members]` of each species (none without species).
    pub fn species(&self) -> Vec<(u32, usize)> {
        self.population().map_or_else(Vec::new, |p| {
            p.species()
                .iter()
                .map(|s| (s.id, s.members.len()))
                .collect()
        })
    }
}

impl Strategy for Search {
    fn ask(&mut self) -> Batch<'_> {
        each!(self, s => s.ask())
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> std::result::Result<(), NeatError> {
        each!(self, s => s.tell(evaluations))
    }

    fn prepare(&mut self) {
        each!(self, s => s.prepare())
    }

    fn generation(&self) -> u32 {
        each!(self, s => Strategy::generation(s))
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        each!(self, s => Strategy::champion(s))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        each!(self, s => Strategy::best_ever(s))
    }

    fn stats(&self) -> GenerationStats {
        each!(self, s => Strategy::stats(s))
    }
}

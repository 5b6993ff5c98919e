//! The search a run holds: one [`Search`] value, whichever strategy the
//! config's `[strategy]` section names, that the driver runs and the
//! checkpoint stores. It is a [`Strategy`] by delegation to the one inside.

pub mod files;

use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::hyperneat::{CPPN_INPUTS, leo_seeded_genomes};
use vivae_neat::strategies::{
    Cells, MapElites, MapElitesParams, NoveltySearch, Nsga2, Nsga2Params,
};
use vivae_neat::{
    BestEver, GenerationStats, Genome, GenomeSpec, NeatError, NeatParams, Population,
};

use crate::config::Config;
use crate::config::es::ES_LEO_OUTPUT;
use crate::config::strategy::{CellsKind, StrategyKind, objective_among};
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

impl Search {
    /// Generation 0 of the strategy of `config` over genomes of shape `spec`
    /// whose behaviour descriptors lie in the box `bounds` (lower, upper),
    /// seeded with `experiment.seed`; NEAT and novelty search may start from
    /// `init`'s genomes instead.
    pub fn new(
        config: &Config,
        spec: GenomeSpec,
        bounds: (Vec<f64>, Vec<f64>),
        init: Option<&Population>,
    ) -> Result<Search> {
        let (neat, seed) = (config.neat.clone(), config.experiment.seed);
        let s = &config.strategy;
        let population = || match init {
            // Only the genomes carry over: fitness, species and the champion were
            // measured on another substrate and mean nothing here.
            Some(p) => {
                Population::from_genomes(neat.clone(), spec.clone(), p.genomes().to_vec(), seed)
                    .map_err(|e| bad_input(format!("initial population: {e}")))
            }
            None => initial_population(config, neat.clone(), spec.clone(), seed),
        };
        if init.is_some() && matches!(s.kind, StrategyKind::MapElites | StrategyKind::Nsga2) {
            return Err(bad_input(format!(
                "experiment.init_population: a {} run starts from minimal genomes (only neat and novelty runs start from a population)",
                s.kind.name()
            )));
        }
        let refused = |e: NeatError| bad_input(format!("strategy.{}: {e}", s.kind.name()));
        Ok(match s.kind {
            StrategyKind::Neat => Search::Neat(population()?),
            StrategyKind::Novelty => Search::Novelty(
                NoveltySearch::new(population()?, s.novelty.params()).map_err(refused)?,
            ),
            StrategyKind::MapElites => {
                let map = MapElitesParams {
                    batch_size: neat.population_size,
                    crossover_probability: s.map_elites.crossover_probability,
                    qd_offset: s.map_elites.qd_offset,
                };
                let cells = cells(config, bounds)?;
                Search::MapElites(MapElites::new(neat, spec, map, cells, seed).map_err(refused)?)
            }
            StrategyKind::Nsga2 => {
                let nsga = Nsga2Params {
                    population_size: neat.population_size,
                    objectives: s
                        .nsga2
                        .objectives
                        .iter()
                        .filter_map(|o| objective_among(o, crate::tasks::metric_names(config)))
                        .collect(),
                    crossover_probability: s.nsga2.crossover_probability,
                };
                Search::Nsga2(Nsga2::new(neat, spec, nsga, seed).map_err(refused)?)
            }
        })
    }

    /// Which strategy this is.
    pub fn kind(&self) -> StrategyKind {
        match self {
            Search::Neat(_) => StrategyKind::Neat,
            Search::Novelty(_) => StrategyKind::Novelty,
            Search::MapElites(_) => StrategyKind::MapElites,
            Search::Nsga2(_) => StrategyKind::Nsga2,
        }
    }

    /// The NEAT population, for NEAT and novelty search.
    pub fn population(&self) -> Option<&Population> {
        match self {
            Search::Neat(p) => Some(p),
            Search::Novelty(n) => Some(n.population()),
            _ => None,
        }
    }

    /// The genomes of the batch to evaluate next.
    pub fn batch(&self) -> Vec<Genome> {
        match self {
            Search::Neat(p) => p.genomes().to_vec(),
            Search::Novelty(n) => n.population().genomes().to_vec(),
            other => other.clone().ask().genomes.to_vec(),
        }
    }

    /// The batch's task fitnesses once told, in batch order (NEAT's as its
    /// population holds them; novelty search's population holds novelty).
    pub fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        match self {
            Search::Neat(p) => p.fitnesses(),
            _ => evaluations.iter().map(Evaluation::finite_fitness).collect(),
        }
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

/// The MAP-Elites cells of `config` over the descriptor box `(lower, upper)`.
fn cells(config: &Config, (lower, upper): (Vec<f64>, Vec<f64>)) -> Result<Cells> {
    let s = &config.strategy;
    let m = &s.map_elites;
    let dims = lower.len();
    let bins = m.bins_for(dims);
    let refused = |e: NeatError| bad_input(format!("strategy.map_elites: {e}"));
    match m.cells {
        CellsKind::Grid if bins.len() != dims => Err(bad_input(format!(
            "strategy.map_elites.bins = {:?}: behaviour {} has {dims} dimensions; give one count per dimension or one for all",
            m.bins,
            s.behaviour.name()
        ))),
        CellsKind::Grid => Cells::grid(lower, upper, bins).map_err(refused),
        CellsKind::Cvt => Cells::cvt(
            &lower,
            &upper,
            m.cvt_cells,
            m.cvt_samples,
            m.cvt_iterations,
            config.experiment.seed,
        )
        .map_err(refused),
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

//! A strategy's generation 0: minimal genomes, LEO's seeded ones, or a
//! given population's genomes for the strategies that take one.

use vivae_neat::hyperneat::{CPPN_INPUTS, leo_seeded_genomes};
use vivae_neat::{Genome, GenomeSpec, NeatParams, Population};

use crate::config::Config;
use crate::config::es::ES_LEO_OUTPUT;
use crate::error::Result;
use crate::io::bad_input;
use crate::search::StrategyConfig;
use crate::search::{Start, takers};

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

/// Generation 0 of a NEAT population for `config`: `init`'s genomes (only
/// they carry over: fitness, species and the champion were measured on
/// another substrate and mean nothing here), or [`initial_population`].
pub(crate) fn starting_population(start: Start<'_>) -> Result<Population> {
    let Start {
        config, spec, init, ..
    } = start;
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
            "experiment.init_population: {} run starts from minimal genomes (only {} runs start from a population)",
            crate::error::a(StrategyConfig::of(config).kind.name()),
            takers().join(" and ")
        ))),
    }
}

//! The options that stand for config keys ([`Overrides`]) and the one
//! mapping of them onto a config ([`apply_overrides`]).

use std::path::PathBuf;

use clap::Args;
use vivae_lab::config::{Config, TaskKind};
use vivae_lab::io::bad_input;
use vivae_lab::substrate::PolarGrid;

use super::args::{Episode, Generations, Resolution, Threads, Wiring};

/// Options that override config keys.
#[derive(Args, Debug, Default)]
pub struct Overrides {
    /// Scenario SVG file, or the name of a shipped one (`vivae scenario list`;
    /// default: the embedded road scenario). Repeat it to train on several
    /// maps at once (fitness = the mean over maps).
    #[arg(long, value_name = "FILE|NAME")]
    pub scenario: Vec<PathBuf>,
    #[command(flatten)]
    pub generations: Generations,
    /// Population size.
    #[arg(long, value_name = "N")]
    pub population: Option<usize>,
    /// Random seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    #[command(flatten)]
    pub resolution: Resolution,
    #[command(flatten)]
    pub episode: Episode,
    #[command(flatten)]
    pub threads: Threads,
    /// Multi-resolution evolution: evaluate every genome at these neuron
    /// sheets (e.g. 3x3,5x5,9x9) and aggregate; --neurons stays the one reported.
    #[arg(long, value_name = "RxA,...", value_delimiter = ',')]
    pub train_neurons: Option<Vec<PolarGrid>>,
    /// Multi-resolution evolution: evaluate every genome at these sensor sheets
    /// (e.g. 3x5,3x6), with each of --train-neurons.
    #[arg(long, value_name = "RxA,...", value_delimiter = ',')]
    pub train_sensors: Option<Vec<PolarGrid>>,
    /// How the training resolutions' fitnesses combine: mean (default) or min.
    #[arg(long, value_name = "mean|min")]
    pub train_aggregate: Option<vivae_lab::config::Aggregate>,
    /// Substrate kind: polar (the dense neuron sheet, the paper's) or
    /// es-hyperneat (hidden neurons placed by the CPPN; keys in [substrate.es]).
    #[arg(long, value_name = "polar|es-hyperneat")]
    pub substrate: Option<vivae_lab::es_controller::SubstrateKind>,
    #[command(flatten)]
    pub wiring: Wiring,
    /// Search strategy (strategy.kind; default neat, the paper's).
    #[arg(long, value_name = "neat|novelty|map-elites|nsga2")]
    pub strategy: Option<vivae_lab::strategy_config::StrategyKind>,
    /// Behaviour descriptor of novelty and map-elites (strategy.behaviour).
    #[arg(long, value_name = "end-position|end-positions|side-speed|trajectory")]
    pub behaviour: Option<vivae_lab::descriptors::BehaviourKind>,
    /// Task (experiment.task): driving (default) or maze (Lehman & Stanley's
    /// maze with a plain NEAT network; default scenario hard-maze).
    #[arg(long, value_name = "driving|maze")]
    pub task: Option<TaskKind>,
}

/// Sets each config key `o` gives (the task only chooses `evolve`'s default
/// config, so it is not among them), then checks the result.
pub fn apply_overrides(config: &mut Config, o: &Overrides) -> anyhow::Result<()> {
    // Flags replace the config file's map(s): one --scenario is a single-map
    // run, several are a multi-map run.
    match o.scenario.as_slice() {
        [] => {}
        [one] => {
            config.experiment.scenario = one.to_string_lossy().into_owned();
            config.experiment.scenarios.clear();
        }
        several => {
            config.experiment.scenario.clear();
            config.experiment.scenarios = several
                .iter()
                .map(|p| p.to_string_lossy().into_owned())
                .collect();
        }
    }
    set(
        &mut config.experiment.generations,
        o.generations.generations,
    );
    set(&mut config.neat.population_size, o.population);
    set(&mut config.experiment.seed, o.seed);
    if let Some(g) = o.resolution.sensors {
        config.surface_sensors.rings = g.rings;
        config.surface_sensors.angles = g.angles;
    }
    set(&mut config.substrate.neurons, o.resolution.neurons);
    set(&mut config.experiment.steps, o.episode.steps);
    set(&mut config.experiment.robots, o.episode.robots);
    set(&mut config.run.threads, o.threads.threads);
    set(&mut config.substrate.train_neurons, o.train_neurons.clone());
    set(&mut config.substrate.train_sensors, o.train_sensors.clone());
    set(&mut config.substrate.train_aggregate, o.train_aggregate);
    set(&mut config.substrate.kind, o.substrate);
    set(&mut config.substrate.normalize_by, o.wiring.normalize_by);
    set(
        &mut config.substrate.normalize_self_loops,
        o.wiring.normalize_self_loops,
    );
    set(&mut config.substrate.recurrence, o.wiring.recurrence);
    set(&mut config.strategy.kind, o.strategy);
    set(&mut config.strategy.behaviour, o.behaviour);
    config
        .validate()
        .map_err(|e| bad_input(format!("command line: {e}")).into())
}

/// Replaces `key` by the option's value, if it was given.
fn set<T>(key: &mut T, option: Option<T>) {
    if let Some(value) = option {
        *key = value;
    }
}

/// The config's single scenario file, if it names one (none: the embedded scenario or several maps).
pub fn scenario_path(config: &Config) -> Option<PathBuf> {
    (!config.experiment.scenario.is_empty()).then(|| PathBuf::from(&config.experiment.scenario))
}

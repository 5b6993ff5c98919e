//! The options that stand for config keys ([`Overrides`]): the flags of the
//! library's one [`vivae_lab::run::prepare::Overrides`], which Python's
//! keyword arguments set too, under the same names.

use std::path::PathBuf;

use clap::Args;
use vivae_lab::config::{Config, TaskName};
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::io::bad_input;

use super::args::{EpisodeArgs, Generations, Resolution, Threads, Wiring};

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
    pub episode: EpisodeArgs,
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
    pub substrate: Option<vivae_lab::controller::es::SubstrateKind>,
    #[command(flatten)]
    pub wiring: Wiring,
    /// Search strategy (strategy.kind; default neat, the paper's).
    #[arg(long, value_name = "NAME", value_parser = strategy_names())]
    pub strategy: Option<vivae_lab::config::strategy::StrategyName>,
    /// Behaviour descriptor of the strategies that search on one
    /// (strategy.behaviour; default end-position): the task decides which of
    /// these apply, and refuses another naming its own.
    #[arg(long, value_name = "NAME", value_parser = behaviour_names())]
    pub behaviour: Option<vivae_lab::config::strategy::BehaviourName>,
    /// Task (experiment.task; default driving, the paper's); docs/howto/ has a page
    /// per task: what it evaluates and which scenario it starts from.
    #[arg(long, value_name = "NAME", value_parser = task_names())]
    pub task: Option<TaskName>,
    /// Distance rays of the second input sheet (distance_sensors.rays; 0 = none).
    #[arg(long, value_name = "N")]
    pub distance_rays: Option<usize>,
    /// The task's robot model, where it has a choice (the maze: lehman, the
    /// default, Lehman's navigator; or vivae, our robot of [physics]).
    #[arg(long, value_name = "MODEL")]
    pub robot: Option<String>,
    /// Placements per evaluation on a scenario that places obstacles or
    /// traffic per evaluation (experiment.placements; default 1): every
    /// genome is scored on N placements drawn from its evaluation's seed.
    #[arg(long, value_name = "N")]
    pub placements: Option<u32>,
    /// How the fitnesses on --placements placements combine: mean (default) or min.
    #[arg(long, value_name = "mean|min")]
    pub placements_aggregate: Option<vivae_lab::config::Aggregate>,
    /// Arithmetic of the controller step (experiment.precision): exact (the
    /// default, f64) or fast (f32 and a polynomial sigmoid: other bits, the
    /// same on every CPU). A resumed run keeps its checkpoint's.
    #[arg(long, value_name = "exact|fast")]
    pub precision: Option<vivae_neat::Precision>,
}

/// `--task NAME`: one of the registered tasks (listed by `--help`).
pub(super) fn task_names() -> impl clap::builder::TypedValueParser<Value = TaskName> {
    use clap::builder::TypedValueParser as _;
    let names = vivae_lab::tasks::names().iter().copied();
    clap::builder::PossibleValuesParser::new(names).map(TaskName)
}

/// `--behaviour NAME`: one offered by a registered task (listed by `--help`).
fn behaviour_names()
-> impl clap::builder::TypedValueParser<Value = vivae_lab::config::strategy::BehaviourName> {
    use clap::builder::TypedValueParser as _;
    let names = vivae_lab::tasks::behaviours::names();
    clap::builder::PossibleValuesParser::new(names).map(vivae_lab::config::strategy::BehaviourName)
}

/// `--strategy NAME`: one of the registered strategies (listed by `--help`).
fn strategy_names()
-> impl clap::builder::TypedValueParser<Value = vivae_lab::config::strategy::StrategyName> {
    use clap::builder::TypedValueParser as _;
    let names = vivae_lab::search::entries().into_iter().map(|e| e.kind);
    clap::builder::PossibleValuesParser::new(names).map(vivae_lab::config::strategy::StrategyName)
}

impl Overrides {
    /// The library's overrides these flags give.
    pub fn to_lab(&self) -> vivae_lab::run::prepare::Overrides {
        vivae_lab::run::prepare::Overrides {
            scenario: (self.scenario.iter())
                .map(|p| p.to_string_lossy().into_owned())
                .collect(),
            generations: self.generations.generations,
            population: self.population,
            seed: self.seed,
            sensors: self.resolution.sensors,
            neurons: self.resolution.neurons,
            steps: self.episode.steps,
            robots: self.episode.robots,
            threads: self.threads.threads,
            distance_rays: self.distance_rays,
            train_neurons: self.train_neurons.clone(),
            train_sensors: self.train_sensors.clone(),
            train_aggregate: self.train_aggregate,
            substrate: self.substrate,
            normalize_by: self.wiring.normalize_by,
            normalize_self_loops: self.wiring.normalize_self_loops,
            recurrence: self.wiring.recurrence,
            strategy: self.strategy.clone(),
            behaviour: self.behaviour.clone(),
            task: self.task.clone(),
            robot: self.robot.clone(),
            placements: self.placements,
            placements_aggregate: self.placements_aggregate,
            precision: self.precision,
        }
    }
}

/// How the command line's settings are named in the library's refusals:
/// `--flag-name`, from the command line.
pub const SPELLING: vivae_lab::run::prepare::Spelling = vivae_lab::run::prepare::Spelling {
    origin: "command line",
    key: |k| format!("--{} ", k.replace('_', "-")),
    on: |k| format!("--{}", k.replace('_', "-")),
};

/// Sets each config key `o` gives, then checks the result by every rule of
/// the config's task.
pub fn apply_overrides(config: &mut Config, o: &Overrides) -> anyhow::Result<()> {
    let refused = |e: String| anyhow::Error::from(bad_input(format!("command line: {e}")));
    o.to_lab().apply(config).map_err(refused)?;
    vivae_lab::tasks::check(config).map_err(|e| refused(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Command;

    #[test]
    fn the_flags_are_the_library_overrides_that_python_takes_too() {
        let cmd = Overrides::augment_args(Command::new("vivae"));
        let mut flags: Vec<String> = (cmd.get_arguments())
            .map(|a| a.get_id().as_str().replace('-', "_"))
            .collect();
        flags.sort();
        let mut keys: Vec<String> = (vivae_lab::run::prepare::Overrides::KEYS.iter())
            .map(|k| k.to_string())
            .collect();
        keys.sort();
        assert_eq!(flags, keys);
    }
}

//! The `gymnasium` task: plain NEAT networks controlling a Gymnasium
//! environment (Box2D, MuJoCo, any with a vector observation), whose
//! episodes are played by Python's Gymnasium. The lab knows the task's
//! shape and records its runs like any other; the episodes are played by
//! an [`Episodes`] player that the host program installs ([`set_player`]:
//! the Python package does, batching a whole generation into one call).
//! Without a player (the `vivae` program) a run of it is refused by name,
//! while its run directories read, report and export as every run's do.

pub mod section;

use std::sync::OnceLock;

use vivae_neat::driver::{Evaluation, Evaluator, EvaluatorError, Task};
use vivae_neat::{Activation, EvalContext, Genome, GenomeSpec, NeatParams};

use self::section::{GymnasiumConfig, SECTION};
use crate::config::{Config, TaskName};
use crate::error::Result;
use crate::io::bad_input;
use crate::search::{BehaviourSpace, StrategyConfig, TaskFacts};
use crate::tasks::maps::TrainingMap;
use crate::tasks::unread::first_change;
use crate::tasks::{Finished, HeaderContext, RunTask, TaskEntry};

/// The task's name in `experiment.task`.
pub const NAME: &str = "gymnasium";

/// Metrics of an evaluation: the worst episode's return, the steps played.
pub const METRICS: &[&str] = &["worst", "steps"];

/// The keys of a config the task reads; every other key stays at its default.
const READ: [&str; 7] = [
    "experiment.task",
    "experiment.seed",
    "experiment.generations",
    "neat",
    "run",
    "strategy",
    "gymnasium",
];

/// The task's registration (`experiment.task = "gymnasium"`).
pub static TASK: TaskEntry = TaskEntry {
    name: NAME,
    default_config,
    validate,
    metric_names: METRICS,
    generation_columns: "",
    behaviours: &[],
    build,
    own_driver: None,
    refuse_when_other: crate::tasks::nothing_to_refuse,
    set_robot: None,
    sections: &[SECTION],
    reads: &[],
    scenarios: &[],
    maps: false,
    check_map: crate::tasks::any_map,
    substrate: false,
    substrate_episode: None,
    stepped: None,
    reward_threshold: None,
    host: Some(HOST),
};

/// Where a run of the task is run: its entry's [`TaskEntry::host`].
pub const HOST: &str = "the Python package (vivae.gym.evolve, vivae.gym.resume)";

/// Plays a batch of evaluations of a Gymnasium environment: what the host
/// program installs with [`set_player`].
pub trait Episodes: Send + Sync {
    /// Evaluates `genomes[i]` on `env.episodes` episodes seeded from
    /// `contexts[i].seed`: fitness the mean return, metrics [`METRICS`]. The
    /// error says why the episodes could not be played.
    fn play(
        &self,
        env: &GymnasiumConfig,
        genomes: &[&Genome],
        contexts: &[EvalContext],
    ) -> std::result::Result<Vec<Evaluation>, String>;
}

static PLAYER: OnceLock<&'static dyn Episodes> = OnceLock::new();

/// Installs the player of this process's `gymnasium` runs (the first one
/// installed stays: false if one was already).
pub fn set_player(player: &'static dyn Episodes) -> bool {
    PLAYER.set(player).is_ok()
}

/// The seed of episode `k` of the evaluation of `seed` (what the player
/// resets the environment with): distinct per evaluation and episode.
pub fn episode_seed(seed: u64, k: u32) -> u64 {
    // Gymnasium's seeds are non-negative Python ints; 63 bits keep them portable to numpy.
    vivae_neat::eval::splitmix64(seed ^ u64::from(k).wrapping_mul(0x9e37_79b9_7f4a_7c15)) >> 1
}

/// The genomes of a run of `env`: bipolar sigmoids everywhere (a continuous
/// action is the output scaled to its bounds; a discrete one the largest).
pub fn spec(env: &GymnasiumConfig) -> GenomeSpec {
    GenomeSpec {
        inputs: env.inputs,
        outputs: env.outputs,
        output_activation: Activation::BipolarSigmoid,
        hidden_activations: vec![Activation::BipolarSigmoid],
        allow_recurrent: false,
    }
}

fn default_config() -> Config {
    let mut c = Config::default();
    c.experiment.task = TaskName(NAME.into());
    c.experiment.generations = 100;
    c.neat = NeatParams::plain_neat();
    c.owned.set(&GymnasiumConfig::default());
    StrategyConfig::fit(
        &mut c,
        &TaskFacts {
            metrics: Some(METRICS),
            ..TaskFacts::default()
        },
    );
    c
}

fn validate(c: &Config) -> std::result::Result<(), String> {
    let env = c.owned.get::<GymnasiumConfig>()?;
    if let Some(why) = env.problem() {
        return Err(why);
    }
    let kind = StrategyConfig::of(c).kind;
    let kind = kind.name();
    if crate::search::entry(kind).is_ok_and(|e| e.needs.behaviour) {
        return Err(format!(
            "strategy.kind = {kind}: {} run gives no behaviour descriptor, which {kind} searches on: use a strategy that selects on fitness",
            crate::error::a(NAME)
        ));
    }
    let value = |c: &Config| toml::Value::try_from(c).expect("a config is TOML");
    let read = |k: &str| {
        READ.iter()
            .any(|r| k == *r || k.starts_with(&format!("{r}.")))
            && !"strategy.behaviour".starts_with(k)
    };
    match first_change("", Some(&value(c)), Some(&value(&default_config())), &read) {
        Some((key, value, default)) => Err(format!(
            "{key} = {value}: {} run does not read it (it reads experiment.seed and generations, [neat], [run], [strategy] and [gymnasium]): leave it at {default}",
            crate::error::a(NAME)
        )),
        None => Ok(()),
    }
}

fn build(config: &Config, _maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    let env = GymnasiumConfig::of(config);
    let player = match PLAYER.get().copied() {
        Some(player) => Some(player),
        // Read, not played (exported): no player needed.
        None if crate::tasks::describe::describing() => Some(&UNPLAYED as &'static dyn Episodes),
        None => None,
    };
    let Some(player) = player else {
        return Err(bad_input(format!(
            "experiment.task = {NAME}: its episodes ({}) are played from Python: run and resume it with {HOST}; `vivae report` draws its curves",
            env.env
        )));
    };
    Ok(Box::new(GymRun { env, player }))
}

/// The player of a task built only to be read, where no host plays episodes.
struct Unplayed;

static UNPLAYED: Unplayed = Unplayed;

impl Episodes for Unplayed {
    fn play(
        &self,
        env: &GymnasiumConfig,
        _genomes: &[&Genome],
        _contexts: &[EvalContext],
    ) -> std::result::Result<Vec<Evaluation>, String> {
        Err(format!(
            "{}: its episodes are played by Gymnasium in Python (vivae.gym)",
            env.env
        ))
    }
}

/// A `gymnasium` run's task: the environment's section and the player.
#[derive(Clone)]
pub struct GymRun {
    env: GymnasiumConfig,
    player: &'static dyn Episodes,
}

impl std::fmt::Debug for GymRun {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GymRun")
            .field("env", &self.env.env)
            .finish()
    }
}

impl GymRun {
    /// The environment it plays.
    pub fn env(&self) -> &GymnasiumConfig {
        &self.env
    }

    /// An evaluator playing each generation as one batch (every genome's
    /// episodes at once), whose error stops the run.
    pub fn batch_evaluator(&self) -> Batch<'_> {
        Batch { task: self }
    }
}

/// Plays a whole generation in one call of the player.
pub struct Batch<'a> {
    task: &'a GymRun,
}

impl Evaluator for Batch<'_> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> std::result::Result<Vec<Evaluation>, EvaluatorError> {
        let genomes: Vec<&Genome> = genomes.iter().collect();
        let played = (self.task.player)
            .play(&self.task.env, &genomes, contexts)
            .map_err(EvaluatorError)?;
        EvaluatorError::unless_one_evaluation_each(&played, genomes.len())?;
        Ok(played)
    }
}

impl Task for GymRun {
    /// One genome's episodes, played alone: the same bits as in a batch
    /// (each episode's seed is its own). Played this way (a run on
    /// threads, not [`GymRun::batch_evaluator`]), an evaluation the player
    /// fails scores NaN, which the strategies count as their worst.
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        match self
            .player
            .play(&self.env, &[genome], std::slice::from_ref(ctx))
        {
            Ok(mut played) if played.len() == 1 => played.remove(0),
            _ => Evaluation {
                fitness: f64::NAN,
                metrics: vec![f64::NAN, 0.0],
                behaviour: Vec::new(),
            },
        }
    }

    fn metric_names(&self) -> &[&str] {
        METRICS
    }
}

impl RunTask for GymRun {
    fn entry(&self) -> &'static TaskEntry {
        &TASK
    }

    fn genome_spec(&self) -> GenomeSpec {
        spec(&self.env)
    }

    fn behaviour_space(&self, _config: &Config) -> BehaviourSpace {
        BehaviourSpace::default()
    }

    fn robot_steps(&self) -> u64 {
        u64::from(self.env.episodes) * u64::from(self.env.max_steps)
    }

    fn check_genome(&self, genome: &Genome) -> std::result::Result<(), String> {
        crate::tasks::check_shape(genome, &self.genome_spec(), &self.env.env)
    }

    fn describe(&self, _maps: &[TrainingMap]) -> String {
        format!("Gymnasium {}", self.env.env)
    }

    fn header(&self, c: &Config, ctx: &HeaderContext<'_>) -> String {
        let threshold = self.env.reward_threshold.map_or(String::new(), |t| {
            format!("; solved: the champion's validated mean ≥ {t}")
        });
        format!(
            "vivae {}: Gymnasium {} (task {NAME})\n\
             \x20 a plain NEAT network ({} inputs, {} outputs, feed-forward), population {}, {} generations{}, seed {}{}\n\
             \x20 fitness: the mean return of {} episodes{threshold}\n\
             \x20 {}",
            ctx.command,
            self.env.env,
            self.env.inputs,
            self.env.outputs,
            c.neat.population_size,
            c.experiment.generations,
            ctx.start,
            c.experiment.seed,
            ctx.strategy,
            self.env.episodes,
            ctx.output,
        )
    }

    fn summary(&self, f: &Finished<'_>) -> Option<(String, String)> {
        let (dir, wall, rate) = (f.dir, f.wall, f.rate);
        let person = format!(
            "done: {} generations in {wall:.1} s\n\
             champion: mean return {:.3} (generation {})\n\
             run directory: {dir}/ (config.toml, champion.json, generations.csv, report.html, checkpoints/)",
            f.generations, f.fitness, f.generation,
        );
        let line = format!(
            "evolve: generations={} best={} champion_generation={}{} evaluations_reused={} wall_s={wall:.1} env_steps_per_s={rate:.0} out={dir}",
            f.generations, f.fitness, f.generation, f.strategy_fields, f.reused,
        );
        Some((person, line))
    }

    fn network_outputs(&self) -> Option<&'static str> {
        Some(
            "one per discrete action (the action is the index of the largest, the first on a tie) \
             or one per continuous action dimension (action = low + (out + 1)/2*(high - low) \
             for the dimension's bounds); inputs the observation, then 1",
        )
    }

    /// Gymnasium's observations as they come (unbounded, as the network reads them).
    fn network_readings(&self) -> crate::controller::readings::Readings {
        crate::controller::readings::Readings::UNBOUNDED
    }

    fn report_curves(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_config_checks_and_other_keys_are_refused_by_name() {
        let c = default_config();
        crate::tasks::check(&c).unwrap();
        let mut bad = default_config();
        bad.experiment.robots = 2;
        let e = crate::tasks::check(&bad).unwrap_err().message;
        assert!(
            e.starts_with("experiment.robots = 2") && e.contains(NAME),
            "{e}"
        );
        let mut bad = default_config();
        bad.owned.update::<GymnasiumConfig>(|g| g.episodes = 0);
        let e = crate::tasks::check(&bad).unwrap_err().message;
        assert!(e.starts_with("gymnasium.episodes = 0"), "{e}");
        let mut other = Config::default();
        other.owned.set(&GymnasiumConfig {
            episodes: 5,
            ..GymnasiumConfig::default()
        });
        let e = crate::tasks::check(&other).unwrap_err().message;
        assert!(
            e.starts_with("gymnasium.episodes = 5: only a gymnasium run reads [gymnasium]"),
            "{e}"
        );
    }

    #[test]
    fn a_run_without_a_player_is_refused_by_name() {
        if PLAYER.get().is_some() {
            return;
        }
        let e = build(&default_config(), &[]).unwrap_err().to_string();
        assert!(e.contains("vivae.gym.evolve"), "{e}");
    }

    #[test]
    fn a_run_read_for_export_builds_without_a_player_and_plays_nothing() {
        let task = crate::tasks::describe::build(&default_config(), &[]).unwrap();
        assert!(task.network_outputs().is_some());
        assert_eq!(
            task.network_readings(),
            crate::controller::readings::Readings::UNBOUNDED
        );
        if PLAYER.get().is_some() {
            return;
        }
        let run = task.as_any().downcast_ref::<GymRun>().unwrap();
        let e = run.player.play(&run.env, &[], &[]).unwrap_err();
        assert!(e.contains("played by Gymnasium in Python"), "{e}");
        // Built to run, it is still refused.
        assert!(build(&default_config(), &[]).is_err());
    }

    #[test]
    fn episode_seeds_differ_by_evaluation_and_episode() {
        let seeds: std::collections::HashSet<u64> = (0..50)
            .flat_map(|s| (0..5).map(move |k| episode_seed(s, k)))
            .collect();
        assert_eq!(seeds.len(), 250);
        assert!(seeds.iter().all(|s| *s < 1 << 63));
    }
}

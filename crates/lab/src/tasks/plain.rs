//! A plain task: a genome shape and a scoring function made a full run
//! task. A task that evolves plain NEAT networks (no substrate, no robot, no
//! map) implements [`Plain`] (its shape and its `evaluate`), defines its
//! `TASK` as `entry::<Its>()` and is named once in the registry's
//! `built_in!` list ([`super::TASKS`]); this adapter gives it everything
//! else a run asks of a task: its default config (plain NEAT, the strategies
//! fitted to its metrics), the refusal by name of every setting it does not
//! read, no maps, the run directory every task writes, a header, a summary,
//! `generations.csv`'s target columns, the replay of an episode (when it
//! keeps a trace) and its network for `vivae export`.

use std::fmt::Write as _;
use std::marker::PhantomData;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{
    Activation, EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Network,
    RecurrentNetwork,
};

use crate::config::{Config, TaskName};
use crate::controller::readings::Readings;
use crate::error::{Result, a};
use crate::io::bad_input;
use crate::search::TaskFacts;
use crate::search::{BehaviourSpace, StrategyConfig};
use crate::tasks::maps::TrainingMap;
use crate::tasks::sketch::{Film, Sketch};
use crate::tasks::unread::first_change;
use crate::tasks::{
    Finished, HeaderContext, RunTask, Stepped, TargetProgress, TaskEntry, Threshold,
};

/// What a plain task is (its name, what it is, how it is scored) and
/// what its networks read and give: the part of [`Plain`] that a
/// [`super::classic::Classic`] environment states too.
pub trait Described {
    /// Its name in `experiment.task` and `--task`.
    const NAME: &'static str;
    /// What it is, for the run's header.
    const ABOUT: &'static str;
    /// How an evaluation is scored, for the run's header.
    const SCORING: &'static str;
    /// Inputs of its networks (a bias input included, if it wants one).
    const INPUTS: usize;
    /// Outputs of its networks.
    const OUTPUTS: usize;
    /// What the outputs mean (exported with the network).
    const OUTPUT_MEANING: &'static str;
}

/// A task of plain NEAT networks: its shape and how a network is scored.
pub trait Plain: Described + Send + Sync + 'static {
    /// The range its network's inputs are read in when exported: by default
    /// every finite value as it is (an observation as [`Plain::evaluate`]
    /// feeds it, so the export steps as vivae does), ±∞ as the largest
    /// finite value of its sign and NaN as 0.
    const READINGS: Readings = Readings::UNBOUNDED;
    /// Whether its networks may grow recurrent links.
    const RECURRENT: bool = false;
    /// Names of the metrics its evaluations carry; one named `steps`
    /// counts the steps an evaluation took.
    const METRICS: &'static [&'static str] = &[];
    /// Names of its behaviour descriptor's coordinates, each in [0, 1];
    /// none: novelty search and MAP-Elites are refused.
    const BEHAVIOUR: &'static [&'static str] = &[];
    /// Steps one evaluation simulates at most.
    const STEPS: u64;
    /// The fitness at which it counts as solved: the run stops there.
    const TARGET: Option<f64> = None;
    /// The mean return at which its validated champion solves it (its
    /// entry's [`TaskEntry::reward_threshold`]), for a task with [`Plain::validate`].
    const REWARD_THRESHOLD: Option<Threshold> = None;
    /// Episodes of its check ([`Plain::check`]), for the run's header; 0: none.
    const CHECK_EPISODES: u32 = 0;
    /// Whether [`Plain::evaluate`] fills a trace when given one (replay).
    const TRACES: bool = false;
    /// Its episode stepped from a given state under given actions (a
    /// classic-control task's, [`super::classic::episode`]): its entry's
    /// [`TaskEntry::stepped`]; none by default.
    const STEPPED: Option<Stepped> = None;
    /// Its settings over the adapter's defaults (population, generations…).
    fn defaults(_config: &mut Config) {}
    /// Scores `net` on the evaluation of seed `seed`; with `trace`, records
    /// every step in it.
    fn evaluate(net: &mut dyn Network, seed: u64, trace: Option<&mut Trace>) -> Evaluation;
    /// `net` validated on fresh episodes of the run seeded `run_seed` (a task
    /// whose runs are solved by a validation, not by training alone).
    fn validate(_net: &mut dyn Network, _run_seed: u64) -> Option<Validation> {
        None
    }
    /// `net`, whose evaluation reached [`Plain::TARGET`], checked on episodes
    /// of the run seeded `run_seed` that neither training nor the validation
    /// plays, and the evaluations the check counts as; the run stops only if
    /// its [`Validation::lower_bound`] reaches the target too. None (the default): reaching the
    /// target in training stops the run.
    fn check(_net: &mut dyn Network, _run_seed: u64) -> Option<(Validation, u64)> {
        None
    }
    /// Its evaluation of a feed-forward network, faster than
    /// [`Plain::evaluate`] and the same to the bit (e.g. its episodes side
    /// by side in lanes); `None`: it has none.
    fn evaluate_feed_forward(_net: &FeedForwardNetwork, _seed: u64) -> Option<Evaluation> {
        None
    }
    /// How a step of its episodes looks (report.html animates the
    /// champion's replay from its trace); `None`: not drawn.
    fn sketch() -> Option<Sketch> {
        None
    }
}

/// A champion's validation: its returns on episodes it was not trained on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Validation {
    /// The mean return.
    pub mean: f64,
    /// The worst return.
    pub worst: f64,
    /// Episodes played.
    pub episodes: u32,
    /// The best return.
    pub best: f64,
    /// The returns' standard deviation (over the episodes, as NumPy's `std`).
    pub std: f64,
    /// The seed its episodes 0, 1, … are drawn from (as a training
    /// evaluation's episodes are from the evaluation's seed).
    pub seed: u64,
}

impl Validation {
    /// Its mean less [`CHECK_STANDARD_ERRORS`] standard errors of the mean
    /// (std/√episodes): what a check's episodes must bring to the target
    /// for the run to stop.
    pub fn lower_bound(&self) -> f64 {
        let n = f64::from(self.episodes.max(1));
        self.mean - CHECK_STANDARD_ERRORS * self.std / n.sqrt()
    }
}

/// Standard errors of its mean that a check's episodes must clear the
/// target by ([`Validation::lower_bound`]). A check whose mean merely
/// reached the threshold let champions through whose 100 validation
/// episodes missed it by 0.4 to 1.2 (Acrobot, MountainCar); at 3 standard
/// errors every seed of 1–10 of the four tasks that stop validated
/// (docs/notebook/classic-control-settings.md).
pub const CHECK_STANDARD_ERRORS: f64 = 3.0;

/// An episode as a plain task's evaluation records it, for a replay.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trace {
    /// One row a step: episode, the network's inputs, its outputs, the reward.
    pub rows: Vec<(u32, Vec<f64>, Vec<f64>, f64)>,
}

impl Trace {
    /// Records one step of episode `episode`.
    pub fn step(&mut self, episode: u32, inputs: &[f64], outputs: &[f64], reward: f64) {
        (self.rows).push((episode, inputs.to_vec(), outputs.to_vec(), reward));
    }

    /// The trace as CSV: `episode,step,in0…,out0…,reward`.
    pub fn csv(&self) -> String {
        let (ni, no) = self.rows.first().map_or((0, 0), |r| (r.1.len(), r.2.len()));
        let mut out = String::from("episode,step");
        (0..ni).for_each(|i| write!(out, ",in{i}").expect("a String"));
        (0..no).for_each(|o| write!(out, ",out{o}").expect("a String"));
        out.push_str(",reward\n");
        let mut step = 0;
        for (k, (episode, inputs, outputs, reward)) in self.rows.iter().enumerate() {
            step = if k > 0 && self.rows[k - 1].0 == *episode {
                step + 1
            } else {
                0
            };
            write!(out, "{episode},{step}").expect("a String");
            for v in inputs.iter().chain(outputs) {
                write!(out, ",{v}").expect("a String");
            }
            writeln!(out, ",{reward}").expect("a String");
        }
        out
    }
}

/// The seed a replay evaluates on (training draws hashed seeds, so it is
/// one never trained on).
pub const REPLAY_SEED: u64 = 0;

/// The columns a plain task with a target adds to `generations.csv`.
pub const TARGET_COLUMNS: &str = ",solvers,evaluations";

/// The keys of a config a plain task reads; every other key must stay at
/// its default (`strategy.behaviour` is the driving task's).
const READ: [&str; 6] = [
    "experiment.task",
    "experiment.seed",
    "experiment.generations",
    "neat",
    "run",
    "strategy",
];

/// The registration of plain task `T`.
pub const fn entry<T: Plain>() -> TaskEntry {
    TaskEntry {
        name: T::NAME,
        default_config: default_config::<T>,
        validate: validate::<T>,
        metric_names: T::METRICS,
        generation_columns: if T::TARGET.is_some() {
            TARGET_COLUMNS
        } else {
            ""
        },
        // Its one descriptor, if any, is its own (`T::BEHAVIOUR`).
        behaviours: &[],
        build: build::<T>,
        own_driver: None,
        refuse_when_other: crate::tasks::nothing_to_refuse,
        set_robot: None,
        sections: &[],
        reads: &[],
        scenarios: &[],
        maps: false,
        check_map: crate::tasks::any_map,
        substrate: false,
        substrate_episode: None,
        stepped: T::STEPPED,
        reward_threshold: T::REWARD_THRESHOLD,
        host: None,
    }
}

/// The genomes of `T`: bipolar sigmoids everywhere (the step `vivae export` writes).
pub fn spec<T: Plain>() -> GenomeSpec {
    GenomeSpec {
        inputs: T::INPUTS,
        outputs: T::OUTPUTS,
        output_activation: Activation::BipolarSigmoid,
        hidden_activations: vec![Activation::BipolarSigmoid],
        allow_recurrent: T::RECURRENT,
    }
}

/// The config of a run of `T` without a config file: plain NEAT, 100
/// generations, then `T`'s own settings; the strategies fitted to its metrics.
fn default_config<T: Plain>() -> Config {
    let mut c = Config::default();
    c.experiment.task = TaskName(T::NAME.into());
    c.experiment.generations = 100;
    c.neat = NeatParams::plain_neat();
    T::defaults(&mut c);
    StrategyConfig::fit(
        &mut c,
        &TaskFacts {
            metrics: Some(T::METRICS),
            ..TaskFacts::default()
        },
    );
    c
}

/// Refuses a strategy that needs a behaviour `T` does not give, and any key
/// `T` does not read off its default; the message names the key.
fn validate<T: Plain>(c: &Config) -> std::result::Result<(), String> {
    let kind = StrategyConfig::of(c).kind;
    let kind = kind.name();
    if T::BEHAVIOUR.is_empty() && crate::search::entry(kind).is_ok_and(|e| e.needs.behaviour) {
        return Err(format!(
            "strategy.kind = {kind}: {} run gives no behaviour descriptor, which {kind} searches on: use a strategy that selects on fitness",
            a(T::NAME)
        ));
    }
    let defaults = default_config::<T>();
    match unread_change(c, &defaults) {
        Some((key, value, default)) => Err(format!(
            "{key} = {value}: {} run does not read it (it reads {}): leave it at {default}",
            a(T::NAME),
            "experiment.seed and generations, [neat], [run] and [strategy]"
        )),
        None => Ok(()),
    }
}

/// The first key of `c` that a plain task does not read and that differs
/// from `defaults`: (key, its value, the default), `unset` for a missing one.
fn unread_change(c: &Config, defaults: &Config) -> Option<(String, String, String)> {
    let value = |c: &Config| toml::Value::try_from(c).expect("a config is TOML");
    // `strategy.behaviour` is the driving task's, under a section the task reads.
    let read = |k: &str| {
        READ.iter()
            .any(|r| k == *r || k.starts_with(&format!("{r}.")))
            && !"strategy.behaviour".starts_with(k)
    };
    first_change("", Some(&value(c)), Some(&value(defaults)), &read)
}

/// The run task of plain task `T`.
fn build<T: Plain>(config: &Config, _maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    let entry = crate::tasks::entry_of(config).map_err(|e| bad_input(e.to_string()))?;
    Ok(Box::new(PlainRun::<T> {
        entry,
        run_seed: config.experiment.seed,
        task: PhantomData,
    }))
}

/// Plain task `T` as a run evaluates, records and reports it.
pub struct PlainRun<T> {
    entry: &'static TaskEntry,
    /// The run's seed, which its validation episodes are drawn from.
    run_seed: u64,
    task: PhantomData<fn() -> T>,
}

impl<T> Clone for PlainRun<T> {
    fn clone(&self) -> Self {
        PlainRun {
            entry: self.entry,
            run_seed: self.run_seed,
            task: PhantomData,
        }
    }
}

impl<T> std::fmt::Debug for PlainRun<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlainRun")
            .field("task", &self.entry.name)
            .finish()
    }
}

impl<T: Plain> PlainRun<T> {
    /// `genome`'s network scored on the evaluation of `seed`, recording into `trace`.
    fn score(genome: &Genome, seed: u64, trace: Option<&mut Trace>) -> Evaluation {
        if T::RECURRENT {
            return T::evaluate(&mut RecurrentNetwork::from_genome(genome), seed, trace);
        }
        let mut net = FeedForwardNetwork::from_genome(genome);
        match trace {
            None => T::evaluate_feed_forward(&net, seed)
                .unwrap_or_else(|| T::evaluate(&mut net, seed, None)),
            Some(t) => T::evaluate(&mut net, seed, Some(t)),
        }
    }

    /// `genome` checked for this run ([`Plain::check`]).
    fn checked(&self, genome: &Genome) -> Option<(Validation, u64)> {
        if T::RECURRENT {
            T::check(&mut RecurrentNetwork::from_genome(genome), self.run_seed)
        } else {
            T::check(&mut FeedForwardNetwork::from_genome(genome), self.run_seed)
        }
    }

    /// The validation's words for a person and its summary fields (empty without one).
    fn validation_text(&self, genome: &Genome) -> (String, String) {
        let Some((v, solved)) = self.validation(genome) else {
            return (String::new(), String::new());
        };
        let verdict = if solved { "solved" } else { "not solved" };
        let target = T::TARGET.map_or(String::new(), |t| format!(", threshold {t}"));
        (
            format!(
                "\nvalidated on {} fresh episodes: mean return {:.2}, worst {:.2}{target}: {verdict}",
                v.episodes, v.mean, v.worst
            ),
            format!(
                " validated_mean={} validated_worst={} validated={}",
                v.mean,
                v.worst,
                if solved { "yes" } else { "no" }
            ),
        )
    }

    /// `key=value` of each metric, with leading spaces.
    fn metric_fields(e: &Evaluation) -> String {
        let pairs = T::METRICS.iter().zip(&e.metrics);
        pairs.map(|(k, v)| format!(" {k}={v}")).collect()
    }
}

impl<T: Plain> Task for PlainRun<T> {
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        Self::score(genome, ctx.seed, None)
    }

    fn metric_names(&self) -> &[&str] {
        T::METRICS
    }
}

impl<T: Plain> RunTask for PlainRun<T> {
    fn entry(&self) -> &'static TaskEntry {
        self.entry
    }

    fn genome_spec(&self) -> GenomeSpec {
        spec::<T>()
    }

    fn behaviour_space(&self, _config: &Config) -> BehaviourSpace {
        let n = T::BEHAVIOUR.len();
        BehaviourSpace {
            lower: vec![0.0; n],
            upper: vec![1.0; n],
            names: T::BEHAVIOUR.iter().map(|&b| b.into()).collect(),
        }
    }

    fn robot_steps(&self) -> u64 {
        T::STEPS
    }

    fn describe(&self, _maps: &[TrainingMap]) -> String {
        T::ABOUT.into()
    }

    fn has_target(&self) -> bool {
        T::TARGET.is_some()
    }

    fn reached_target(&self, evaluation: &Evaluation) -> bool {
        T::TARGET.is_some_and(|t| evaluation.fitness >= t)
    }

    fn holds_target(&self, genome: &Genome) -> Option<(bool, u64)> {
        let (v, cost) = self.checked(genome)?;
        Some((T::TARGET.is_some_and(|t| v.lower_bound() >= t), cost))
    }

    fn validation(&self, genome: &Genome) -> Option<(Validation, bool)> {
        let v = if T::RECURRENT {
            T::validate(&mut RecurrentNetwork::from_genome(genome), self.run_seed)
        } else {
            T::validate(&mut FeedForwardNetwork::from_genome(genome), self.run_seed)
        }?;
        let threshold = T::REWARD_THRESHOLD.map(|t| t.value).or(T::TARGET);
        Some((v, threshold.is_some_and(|t| v.mean >= t)))
    }

    fn generation_fields(&self, progress: &TargetProgress, evaluations: &[Evaluation]) -> String {
        let solvers = evaluations.iter().filter(|e| self.reached_target(e));
        format!(",{},{}", solvers.count(), progress.evaluations)
    }

    fn header(&self, c: &Config, ctx: &HeaderContext<'_>) -> String {
        let stop = T::TARGET.map_or(String::new(), |t| match T::CHECK_EPISODES {
            0 => format!("; the run stops when an evaluation reaches {t}"),
            n => format!(
                "; the run stops when an evaluation reaches {t} and its genome's mean over {n} check episodes (never trained on), less {CHECK_STANDARD_ERRORS} standard errors, does too"
            ),
        });
        format!(
            "vivae {}: {} (task {})\n\
             \x20 a plain NEAT network ({} inputs, {} outputs, {}), population {}, at most {} generations{}, seed {}{}\n\
             \x20 output: {}\n\
             \x20 {}{stop}",
            ctx.command,
            T::ABOUT,
            T::NAME,
            T::INPUTS,
            T::OUTPUTS,
            if T::RECURRENT {
                "recurrent"
            } else {
                "feed-forward"
            },
            c.neat.population_size,
            c.experiment.generations,
            ctx.start,
            c.experiment.seed,
            ctx.strategy,
            ctx.output,
            T::SCORING,
        )
    }

    fn summary(&self, f: &Finished<'_>) -> Option<(String, String)> {
        let (p, dir, wall, rate) = (f.progress, f.dir, f.wall, f.rate);
        let verdict = match (T::TARGET, p.solved_at, p.solved_generation) {
            (None, ..) => String::new(),
            (Some(t), Some(n), Some(g)) if p.checked > 0 => format!(
                "; a genome reached {t} in training and held it on its check after {n} evaluations (generation {g}; checks counted as {} of them)",
                p.checked
            ),
            (Some(t), Some(n), Some(g)) => {
                format!("; an evaluation reached {t} after {n} evaluations (generation {g})")
            }
            (Some(t), ..) => format!(
                "; no evaluation reached {t} in {} evaluations",
                p.evaluations
            ),
        };
        let (validated, fields) = self.validation_text(f.champion);
        let validation_file = if validated.is_empty() {
            ""
        } else {
            ", validation.json"
        };
        let person = format!(
            "done: {} generations in {wall:.1} s{verdict}\n\
             champion: fitness {:.3} (generation {}){validated}\n\
             run directory: {dir}/ (config.toml, champion.json, generations.csv{validation_file}, report.html, checkpoints/)\n\
             its network: vivae export {dir} --format onnx|c|json --out FILE",
            f.generations, f.fitness, f.generation,
        );
        let target = if T::TARGET.is_some() {
            format!("{} evaluations={}", p.summary_fields(), p.evaluations)
        } else {
            String::new()
        };
        let line = format!(
            "evolve: generations={} best={} champion_generation={}{target}{fields}{} evaluations_reused={} wall_s={wall:.1} robot_steps_per_s={rate:.0} out={dir}",
            f.generations, f.fitness, f.generation, f.strategy_fields, f.reused,
        );
        Some((person, line))
    }

    fn replay_text(&self, genome: &Genome) -> Option<(String, String)> {
        if !T::TRACES {
            return None;
        }
        let e = Self::score(genome, REPLAY_SEED, None);
        let (validated, fields) = self.validation_text(genome);
        let line = format!("fitness={}{}{fields}", e.fitness, Self::metric_fields(&e));
        let note = format!(
            "{}: the evaluation of seed {REPLAY_SEED} (training used others); its steps in episode.csv{validated}",
            T::NAME
        );
        Some((line, note))
    }

    fn episode_csv(&self, genome: &Genome) -> Option<String> {
        let mut trace = Trace::default();
        Self::score(genome, REPLAY_SEED, T::TRACES.then_some(&mut trace));
        T::TRACES.then(|| trace.csv())
    }

    fn film(&self, genome: &Genome) -> Option<Film> {
        let sketch = T::sketch().filter(|_| T::TRACES)?;
        let mut trace = Trace::default();
        Self::score(genome, REPLAY_SEED, Some(&mut trace));
        Some(Film::of(&sketch, &trace.rows))
    }

    fn network_outputs(&self) -> Option<&'static str> {
        Some(T::OUTPUT_MEANING)
    }

    fn network_readings(&self) -> Readings {
        T::READINGS
    }

    fn report_curves(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::StepNet;
    use crate::tasks::cartpole::CartPole;
    use vivae_neat::Population;

    #[test]
    fn a_check_clears_the_target_by_three_standard_errors() {
        // Acrobot-like returns: mean −95, std 20 over 100 episodes: the
        // standard error is 2, so the bound is −101 and −100 is not cleared.
        let v = Validation {
            mean: -95.0,
            worst: -300.0,
            episodes: 100,
            best: -70.0,
            std: 20.0,
            seed: 1,
        };
        assert_eq!(v.lower_bound(), -101.0);
        let steady = Validation { std: 10.0, ..v };
        assert_eq!(steady.lower_bound(), -98.0);
        assert_eq!(Validation { std: 0.0, ..v }.lower_bound(), -95.0);
    }

    /// Genomes of `spec` grown by 30 generations of a made-up fitness
    /// (hidden nodes, disabled links, recurrent links when allowed).
    fn grown(spec: GenomeSpec) -> Vec<Genome> {
        let params = NeatParams {
            add_node_probability: 0.3,
            add_link_probability: 0.5,
            population_size: 30,
            ..NeatParams::plain_neat()
        };
        let mut pop = Population::new(params, spec, 3).unwrap();
        for _ in 0..30 {
            pop.evaluate(|g, ctx| g.links().len() as f64 + (ctx.seed % 7) as f64);
            pop.next_generation();
        }
        pop.genomes().to_vec()
    }

    #[test]
    fn the_exported_step_is_the_network_bit_for_bit() {
        // Any number of outputs (classic control's 1 to 3, Gymnasium's up to 6).
        for (recurrent, outputs) in [(false, 2), (true, 2), (false, 1), (true, 3), (false, 6)] {
            let spec = GenomeSpec {
                allow_recurrent: recurrent,
                outputs,
                ..spec::<CartPole>()
            };
            let genomes = grown(spec);
            assert!(
                genomes.iter().any(|g| g.nodes().len() > 5 + outputs),
                "hidden nodes grew"
            );
            let (mut out, mut got) = (vec![0.0; outputs], vec![0.0; outputs]);
            for g in &genomes {
                let mut step = StepNet::from_genome(g, recurrent).unwrap();
                assert_eq!(step.outputs.len(), outputs);
                step.readings = CartPole::READINGS;
                let mut net: Box<dyn Network> = if recurrent {
                    Box::new(RecurrentNetwork::from_genome(g))
                } else {
                    Box::new(FeedForwardNetwork::from_genome(g))
                };
                let mut state = vec![0.0; step.nodes];
                let mut scratch = vec![0.0; step.nodes];
                for t in 0..5 {
                    // Raw observations, far outside the sensors' [0, 1]: the
                    // task's declared range reads them as they are.
                    let inputs = [-2.4 * f64::from(t), 7.5, -0.9, 1e6 * f64::from(t), 1.0];
                    net.activate(&inputs, &mut out);
                    step.step(&inputs, &mut state, &mut scratch, &mut got);
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&got), bits(&out), "{g:?}");
                }
            }
        }
    }

    #[test]
    fn a_setting_the_task_does_not_read_is_refused_by_its_key() {
        let ok = default_config::<CartPole>();
        crate::tasks::check(&ok).unwrap();
        let refused = |edit: &dyn Fn(&mut Config), key: &str| {
            let mut c = default_config::<CartPole>();
            edit(&mut c);
            let e = crate::tasks::check(&c).unwrap_err().message;
            assert!(e.starts_with(key) && e.contains("cartpole"), "{key}: {e}");
        };
        refused(
            &|c| c.surface_sensors.rings = 5,
            "surface_sensors.rings = 5",
        );
        refused(&|c| c.experiment.robots = 2, "experiment.robots = 2");
        refused(
            &|c| c.experiment.scenario = "oval".into(),
            "experiment.scenario",
        );
        refused(&|c| c.physics.v_max = 3.0, "physics.v_max");
        refused(
            &|c| StrategyConfig::update(c, |s| s.behaviour = "side-speed".into()),
            "strategy.behaviour",
        );
        let mut read = default_config::<CartPole>();
        read.neat.population_size = 20;
        read.experiment.seed = 9;
        StrategyConfig::update(&mut read, |s| s.kind = "nsga2".into());
        crate::tasks::check(&read).unwrap();
    }
}

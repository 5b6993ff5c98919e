//! The task seam: what a run asks of its task ([`RunTask`]) and what it
//! knows of a task before building it ([`TaskEntry`]), and reading and
//! checking a config by its task's defaults and rules. The tasks themselves
//! are listed in [`super::TASKS`] or [`super::register`]ed.

use std::any::Any;
use std::fmt;
use std::path::Path;
use std::sync::atomic::AtomicBool;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{Genome, GenomeSpec};

use super::TargetProgress;
use super::behaviours::BehaviourEntry;
use super::maps::TrainingMap;
use super::plain::Validation;
use super::sketch::Film;
use super::substrate::SubstrateEpisodeOf;
use crate::config::{Config, ConfigError, Section, SharedSection, TaskName};
use crate::error::{Error, Result};
use crate::io::read_text;
use crate::search::BehaviourSpace;
use crate::shipped::Shipped;
use crate::tasks::scenarios::resolve_map;

/// How a task with a choice of robot models sets one by name.
pub type SetRobot = fn(&mut Config, &str) -> std::result::Result<(), String>;

/// How a task is built from a config and its maps.
pub type BuildTask = fn(&Config, &[TrainingMap]) -> Result<Box<dyn RunTask>>;

/// A task's episode stepped from a given state under given actions, until
/// it terminates, is truncated or the actions run out; the error says what is
/// wrong with the input (see [`TaskEntry::stepped`]).
pub type Stepped = fn(&[f64], &[f64]) -> std::result::Result<Vec<Step>, String>;

/// One step of an episode as Gymnasium's `env.step` returns it, with the
/// state it leaves in `env.unwrapped.state`.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// `env.unwrapped.state` after the step.
    pub state: Vec<f64>,
    /// The observation (float32 values).
    pub observation: Vec<f64>,
    /// The reward.
    pub reward: f64,
    /// Whether the episode terminated.
    pub terminated: bool,
    /// Whether it was truncated (its `max_episode_steps` reached).
    pub truncated: bool,
}

/// A task's registration: what a run needs to know of it before it is built.
pub struct TaskEntry {
    /// Its name in `experiment.task` and `--task`.
    pub name: &'static str,
    /// The config a run of it starts from without a config file; a config
    /// file's unset keys are taken from it too.
    pub default_config: fn() -> Config,
    /// The rules the task adds to [`Config::validate`]'s (the message names the key).
    pub validate: fn(&Config) -> std::result::Result<(), String>,
    /// Names of the metrics its evaluations carry (objectives a strategy may select on besides fitness).
    pub metric_names: &'static [&'static str],
    /// The columns it adds to `generations.csv`, each with its leading comma.
    pub generation_columns: &'static str,
    /// The behaviour descriptors `strategy.behaviour` may name for its runs
    /// (novelty search and MAP-Elites search on them); empty for a task
    /// with one descriptor of its own (the key stays at its default) or none.
    pub behaviours: &'static [BehaviourEntry],
    /// Builds the task of `config` on `maps` (from [`crate::tasks::maps::load`]).
    pub build: BuildTask,
    /// For a task that runs on a driver of its own (two populations) rather
    /// than [`crate::run::Run`]: that driver. `None` for one population.
    pub own_driver: Option<OwnDriver>,
    /// What its own config sections must be when another task runs (e.g.
    /// at their defaults: they would be ignored); the message names the key.
    pub refuse_when_other: fn(&Config) -> std::result::Result<(), String>,
    /// Sets its robot model by name (`--robot`), for a task with a choice of them.
    pub set_robot: Option<SetRobot>,
    /// Its own config sections (each a table beside the shared ones, left
    /// out of a run's config while at its defaults).
    pub sections: &'static [Section],
    /// The shared sections of a robot and its world that it reads (all of
    /// them for a robot task, none for a plain one): its runs' `config.toml`
    /// holds only these of them, and a key set in another is refused.
    pub reads: &'static [SharedSection],
    /// The scenarios shipped for it (`--scenario NAME`; [`crate::tasks::scenarios::all`]).
    pub scenarios: &'static [Shipped],
    /// Whether its runs train on scenario maps (`experiment.scenario(s)`,
    /// copied into the run); a task without (a [`super::plain`] task)
    /// loads none and its run directory has no `scenario.svg`.
    pub maps: bool,
    /// Refuses a map its runs cannot use (the message names the file and
    /// what is wrong): every map a config names is checked by it when
    /// loaded ([`crate::tasks::maps::load`]), by `vivae config check` as by a run.
    pub check_map: fn(&vivae_sim::Scenario) -> std::result::Result<(), String>,
    /// Whether its controller is a robot's substrate network decoded from a
    /// CPPN (the driving experiment's): what `vivae view`, `retrain`,
    /// `drive-image`, the report's episodes and the export of a substrate
    /// need; `vivae compare` groups its runs by substrate.
    pub substrate: bool,
    /// For a task whose controller is a robot's substrate network
    /// ([`TaskEntry::substrate`]): its episode on one map at a config's
    /// resolution, what export, `drive-image` and a recorded episode read
    /// ([`super::substrate::SubstrateEpisode`]); `None` otherwise.
    pub substrate_episode: Option<SubstrateEpisodeOf>,
    /// For a task whose episode can be stepped from a given state (a
    /// classic-control task, compared step by step with Gymnasium's by the
    /// Python package): that episode; `None` otherwise.
    pub stepped: Option<Stepped>,
    /// For a task whose runs end in a validation of their champion on fresh
    /// episodes (a classic-control task): the mean return that solves it
    /// there; the `gym-classic` pack runs every task that declares one.
    pub reward_threshold: Option<Threshold>,
    /// For a task whose episodes a host program plays (the `gymnasium`
    /// task's, played by Gymnasium in Python): where its runs are run, which
    /// the `vivae` program names instead of running it; `None`: any program
    /// runs it.
    pub host: Option<&'static str>,
}

/// The mean return at which a validated champion solves its task, and
/// where that bar comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Threshold {
    /// The mean return.
    pub value: f64,
    /// Where it comes from (e.g. Gymnasium's `reward_threshold`), for a table's source column.
    pub source: &'static str,
}

/// [`TaskEntry::check_map`] of a task that can use any map that loads.
pub fn any_map(_: &vivae_sim::Scenario) -> std::result::Result<(), String> {
    Ok(())
}

/// What a running task's own driver tells the program: lines for a person
/// (the header, a line per generation, the closing lines) and whether the
/// user asked it to stop.
pub struct Session<'a> {
    /// Set when the user asks the run to stop after the generation.
    pub interrupted: &'a AtomicBool,
    /// Says a line to a person (the program prints it on stderr unless quiet).
    pub say: &'a (dyn Fn(&str) + Sync),
    /// Who plays the task's batches (e.g. the predator–prey task's meetings)
    /// when not this process's threads (`None`): the program's players
    /// across an MPI job's ranks, of a type the task's driver knows (it
    /// built them for the program: the program's tools of the task).
    pub players: Option<&'a (dyn Any + Sync)>,
}

/// How a task's own driver stopped: its run's machine-readable summary
/// line, or where it was interrupted (its checkpoint written), or that the
/// run it was asked to resume had nothing left to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stopped {
    /// The run reached its last generation: the summary line.
    Finished(String),
    /// [`Session::interrupted`] stopped it after this many generations, each
    /// checkpointed: `vivae resume` continues it.
    Interrupted(u32),
    /// A resumed run that was already finished.
    AlreadyFinished {
        /// Its number of generations, all done (a resume to more extends it).
        generations: u32,
        /// Its summary line, as when it finished.
        line: String,
    },
}

impl Stopped {
    /// The summary line of a finished run (none for an interrupted one).
    pub fn line(&self) -> Option<&str> {
        match self {
            Stopped::Finished(line) | Stopped::AlreadyFinished { line, .. } => Some(line),
            Stopped::Interrupted(_) => None,
        }
    }
}

/// The driver of a task that runs on its own: it creates, resumes and runs
/// its run directories and says how it stopped.
#[derive(Debug, Clone, Copy)]
pub struct OwnDriver {
    /// Creates a run of `config` in `dir` (replacing a run there with
    /// `force`) and runs it to its end or an interruption.
    pub evolve:
        fn(dir: &Path, config: Config, force: bool, session: &Session<'_>) -> Result<Stopped>,
    /// Resumes the run in `dir`, to `generations` generations in all when given.
    pub resume: fn(dir: &Path, generations: Option<u32>, session: &Session<'_>) -> Result<Stopped>,
}

/// The driver of the run in `dir`, when its task (in its `config.toml`) runs on its own.
pub fn own_driver_of_run(dir: &Path) -> Option<OwnDriver> {
    entry_of_run(dir)?.own_driver
}

/// [`TaskEntry::refuse_when_other`] of a task whose sections the registry
/// refuses for it ([`check`] refuses every section a task does not read).
pub fn nothing_to_refuse(_: &Config) -> std::result::Result<(), String> {
    Ok(())
}

/// The entry of the task that the run in `dir` names in its `config.toml`
/// (read only that far: the config may be refused whole).
pub fn entry_of_run(dir: &Path) -> Option<&'static TaskEntry> {
    let text = std::fs::read_to_string(dir.join(crate::rundir::files::CONFIG)).ok()?;
    entry(task_of_text(&text)?.name()).ok()
}

impl fmt::Debug for TaskEntry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TaskEntry")
            .field("name", &self.name)
            .finish()
    }
}

/// The registered task called `name`; the error lists the ones there are.
pub fn entry(name: &str) -> std::result::Result<&'static TaskEntry, String> {
    let all = super::entries();
    all.iter().copied().find(|t| t.name == name).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|t| t.name).collect();
        format!("'{name}': expected {}", names.join(" or "))
    })
}

/// The names of the registered tasks that have `capability` (e.g.
/// [`TaskEntry::substrate`]), for a message saying which tasks a command
/// works on.
pub fn names_with(capability: fn(&TaskEntry) -> bool) -> String {
    let all = super::entries().into_iter().filter(|t| capability(t));
    all.map(|t| t.name).collect::<Vec<_>>().join(", ")
}

/// Whether `config`'s task controls a robot by a substrate network
/// ([`TaskEntry::substrate`]); false for a task not registered.
pub fn has_substrate(config: &Config) -> bool {
    entry_of(config).is_ok_and(|t| t.substrate)
}

/// The entry of `config`'s task (checked by [`check`]).
pub fn entry_of(config: &Config) -> std::result::Result<&'static TaskEntry, ConfigError> {
    entry(config.experiment.task.name())
        .map_err(|why| ConfigError::new(format!("experiment.task = {why}")))
}

/// The config a run of `task` starts from without a config file (the
/// paper's driving experiment when no task is named).
pub fn default_config(task: Option<&TaskName>) -> std::result::Result<Config, String> {
    match task {
        Some(t) => entry(t.name()).map(|e| (e.default_config)()),
        None => Ok(Config::default()),
    }
}

/// Sets `config`'s robot model to `robot` (`--robot`) by its task's
/// [`TaskEntry::set_robot`]; refused for a task without a choice.
pub fn set_robot(config: &mut Config, robot: &str) -> std::result::Result<(), String> {
    let task = entry(config.experiment.task.name())?;
    let Some(set) = task.set_robot else {
        let with: Vec<&str> = (super::entries().into_iter())
            .filter(|t| t.set_robot.is_some())
            .map(|t| t.name)
            .collect();
        return Err(format!(
            "robot = {robot}: {} run has one robot model (tasks with a choice: {})",
            crate::error::a(task.name),
            with.join(", ")
        ));
    };
    set(config, robot).map_err(|e| format!("robot = {e}"))
}

/// Checks `config` by the shared rules and by its task's: the one validation
/// of a config that a run starts from.
pub fn check(config: &Config) -> std::result::Result<(), ConfigError> {
    let task = entry_of(config)?;
    config.validate()?;
    // Every table beside the shared sections is a registered section that reads.
    let mut settled = config.clone();
    crate::config::owned::settle(&mut settled.owned, &sections()).map_err(ConfigError::new)?;
    super::unread::refuse_unread(&settled, task).map_err(ConfigError::new)?;
    crate::search::check(config, task.metric_names).map_err(ConfigError::new)?;
    super::behaviours::check(config, task).map_err(ConfigError::new)?;
    for other in super::entries().iter().filter(|t| t.name != task.name) {
        (other.refuse_when_other)(config).map_err(ConfigError::new)?;
    }
    (task.validate)(config).map_err(ConfigError::new)
}

/// Parses a config's TOML text: unset keys take the defaults of the task it
/// names, and it is [`check`]ed; errors are one line naming the line and key.
pub fn config_from_toml(text: &str) -> std::result::Result<Config, ConfigError> {
    let sections = sections();
    let named = Config::from_toml_with(text, None, &sections);
    // The shared rules may refuse a value that the task's defaults would set
    // differently: the task comes from the text whatever they say.
    let task: TaskName = match &named {
        Ok(c) => c.experiment.task.clone(),
        Err(_) => task_of_text(text).unwrap_or_default(),
    };
    let entry =
        entry(task.name()).map_err(|why| ConfigError::new(format!("experiment.task = {why}")))?;
    let defaults = (entry.default_config)();
    let config = if defaults == Config::default() {
        named?
    } else {
        Config::from_toml_with(text, Some(&defaults), &sections)?
    };
    check(&config).map_err(|e| e.at_line_of_key(text))?;
    Ok(config)
}

/// Reads a config file with its task's defaults and checks it; relative paths in it (scenario, initial
/// population) become relative to the file's folder (a bare shipped name with no such file there stays shipped).
pub fn read_config(path: &Path) -> Result<Config> {
    let text = read_text(path)?;
    let mut config = config_from_toml(&text).map_err(|error| Error::Config {
        path: path.to_path_buf(),
        error,
    })?;
    let base = path.parent().unwrap_or(Path::new(""));
    // A bare shipped name (a task's default arena) with no such file there stays shipped.
    if !config.experiment.scenario.is_empty() {
        config.experiment.scenario = resolve_map(base, &config.experiment.scenario);
    }
    let p = &mut config.experiment.init_population;
    if !p.is_empty() && Path::new(p.as_str()).is_relative() {
        *p = base.join(&*p).to_string_lossy().into_owned();
    }
    for p in &mut config.experiment.scenarios {
        *p = resolve_map(base, p);
    }
    Ok(config)
}

/// `config` as its run's `config.toml` holds it: of the shared sections only
/// those its task reads ([`TaskEntry::reads`]; all of them for a task that
/// is not registered).
pub fn config_text(config: &Config) -> String {
    let reads = entry_of(config).map_or(&SharedSection::ALL[..], |t| t.reads);
    config.to_toml_reading(reads)
}

/// `experiment.task` as `text` sets it, if it parses that far.
fn task_of_text(text: &str) -> Option<TaskName> {
    let value: toml::Value = toml::from_str(text).ok()?;
    let task = value.get("experiment")?.get("task")?.as_str()?;
    Some(TaskName(task.to_string()))
}

/// The config sections beside the shared ones: the search strategies'
/// `[strategy]`, then every task's own in the order of [`super::entries`].
pub fn sections() -> Vec<Section> {
    let tasks = super::entries()
        .into_iter()
        .flat_map(|t| t.sections.iter().copied());
    std::iter::once(crate::search::SECTION)
        .chain(tasks)
        .collect()
}

/// The names of the tasks that read the config section `name` (a
/// top-level table): a shared section of a robot by those listing it in
/// [`TaskEntry::reads`], a task's own section by the tasks registering it,
/// the others (`[experiment]`, `[neat]`, `[run]`, `[strategy]`) by every task.
pub fn readers(name: &str) -> Vec<&'static str> {
    let all = super::entries().into_iter();
    let reads = |t: &TaskEntry| match SharedSection::named(name) {
        Some(s) => t.reads.contains(&s),
        None if sections()
            .iter()
            .any(|s| s.name == name && s.name != crate::search::SECTION.name) =>
        {
            t.sections.iter().any(|s| s.name == name)
        }
        None => true,
    };
    all.filter(|t| reads(t)).map(|t| t.name).collect()
}

/// Who reads the config section `name` ([`readers`]), for a person:
/// `every task` or the tasks' names.
pub fn read_by(name: &str) -> String {
    let readers = readers(name);
    if readers.len() == super::entries().len() {
        "every task".into()
    } else {
        readers.join(", ")
    }
}

/// The commented default config of task `name` (`vivae config default
/// --task`): its defaults, only the sections it reads.
pub fn default_commented(name: &str) -> std::result::Result<String, String> {
    let task = entry(name)?;
    let owned: Vec<Section> = std::iter::once(crate::search::SECTION)
        .chain(task.sections.iter().copied())
        .collect();
    Ok((task.default_config)().default_commented_for(task.reads, &owned))
}

/// Metric names of `config`'s task (none for a task that is not registered).
pub fn metric_names(config: &Config) -> &'static [&'static str] {
    entry(config.experiment.task.name()).map_or(&[], |e| e.metric_names)
}

/// The task of `config` on `maps` (from [`crate::tasks::maps::load`]).
pub fn build(config: &Config, maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    let task = entry(config.experiment.task.name()).map_err(crate::io::bad_input)?;
    (task.build)(config, maps)
}

/// What the program tells a task for its [`RunTask::header`].
#[derive(Debug, Clone, Copy)]
pub struct HeaderContext<'a> {
    /// The command running the run (`evolve`, `resume`, …).
    pub command: &'a str,
    /// What it trains on ([`RunTask::describe`]).
    pub scenario: &'a str,
    /// ` (resuming after generation N)`, or empty for a new run.
    pub start: &'a str,
    /// The evaluation threads, as a person reads them.
    pub threads: &'a str,
    /// The line on the search strategy (with its leading line break), or empty.
    pub strategy: &'a str,
    /// The run directory.
    pub output: &'a str,
}

/// A finished run, for [`RunTask::summary`].
#[derive(Debug, Clone, Copy)]
pub struct Finished<'a> {
    /// The champion genome.
    pub champion: &'a Genome,
    /// Its fitness.
    pub fitness: f64,
    /// The run-relative generation it was found in.
    pub generation: u32,
    /// Progress towards the task's target (default for a task without one).
    pub progress: TargetProgress,
    /// Generations done.
    pub generations: u32,
    /// Wall-clock seconds of this invocation.
    pub wall: f64,
    /// Robot-steps per second.
    pub rate: f64,
    /// Evaluations of this invocation copied from an equal genome's instead of run.
    pub reused: u64,
    /// The run directory.
    pub dir: &'a str,
    /// The strategy's summary fields (leading spaces included).
    pub strategy_fields: &'a str,
}

/// What every [`RunTask`] that is `Clone` has without writing it: its
/// concrete type for a downcast and a boxed copy.
pub trait RunTaskBase {
    /// The task as [`Any`], for code that knows a task's concrete type.
    fn as_any(&self) -> &dyn Any;

    /// A boxed copy (each evaluator holds its own).
    fn clone_box(&self) -> Box<dyn RunTask>;
}

impl<T: RunTask + Clone + 'static> RunTaskBase for T {
    fn as_any(&self) -> &dyn Any {
        self
    }

    fn clone_box(&self) -> Box<dyn RunTask> {
        Box::new(self.clone())
    }
}

/// A task as a run evaluates, records and reports it.
pub trait RunTask: RunTaskBase + Task + fmt::Debug + Send + Sync {
    /// Its registration.
    fn entry(&self) -> &'static TaskEntry;

    /// The shape of the genomes the run evolves.
    fn genome_spec(&self) -> GenomeSpec;

    /// The behaviour descriptors it gives for `config`'s `strategy.behaviour`
    /// (checked to be one it offers): their box, which a grid archive's
    /// cells cover, and their coordinates' names; empty if it gives none.
    fn behaviour_space(&self, config: &Config) -> BehaviourSpace;

    /// Robot-steps one evaluation simulates at most.
    fn robot_steps(&self) -> u64;

    /// Robot-steps a generation's `evaluations` simulated: by default the
    /// sum of a metric named `steps` (a task whose episodes end early counts
    /// the steps they took), else [`RunTask::robot_steps`] each.
    fn robot_steps_of(&self, evaluations: &[Evaluation]) -> f64 {
        match self.metric_names().iter().position(|m| *m == "steps") {
            Some(k) => evaluations.iter().filter_map(|e| e.metrics.get(k)).sum(),
            None => evaluations.len() as f64 * self.robot_steps() as f64,
        }
    }

    /// Why `genome` does not fit the task, if it does not: by default,
    /// unless it has [`RunTask::genome_spec`]'s inputs and outputs.
    fn check_genome(&self, genome: &Genome) -> std::result::Result<(), String> {
        check_shape(genome, &self.genome_spec(), self.entry().name)
    }

    /// The links `genome`'s network expresses and could express
    /// (`generations.csv`'s `best_substrate_links`, `possible_substrate_links`):
    /// by default the network is the genome, its enabled links of all its link genes.
    fn links(&self, genome: &Genome) -> Result<(usize, usize)> {
        Ok((genome.num_enabled_links(), genome.links().len()))
    }

    /// What the run trains on, for the run's header line.
    fn describe(&self, maps: &[TrainingMap]) -> String;

    /// Settings of a config left at the task's defaults that the task fits
    /// to itself (e.g. a grid archive to its arena).
    fn fit_defaults(&self, _config: &mut Config) {}

    /// Whether a run stops once an evaluation reaches the task's target; its
    /// progress towards it is then kept in the checkpoints.
    fn has_target(&self) -> bool {
        false
    }

    /// Whether `evaluation` reached the task's target.
    fn reached_target(&self, _evaluation: &Evaluation) -> bool {
        false
    }

    /// Whether `genome`, whose evaluation reached the target, holds it on
    /// the task's check episodes (the run stops only then), and the
    /// evaluations the check counts as; none: reaching it is enough.
    fn holds_target(&self, _genome: &Genome) -> Option<(bool, u64)> {
        None
    }

    /// `genome` validated on fresh episodes of the run (for a task with a
    /// [`TaskEntry::reward_threshold`]), and whether its mean reaches that
    /// threshold: the run solved the task; `None` for a task without validation.
    fn validation(&self, _genome: &Genome) -> Option<(Validation, bool)> {
        None
    }

    /// The task's own fields of a `generations.csv` row (its
    /// [`TaskEntry::generation_columns`]), with their leading commas.
    fn generation_fields(&self, _progress: &TargetProgress, _evaluations: &[Evaluation]) -> String {
        String::new()
    }

    /// The lines that open a run in the terminal: what is evolved, on what,
    /// how it is scored.
    fn header(&self, config: &Config, ctx: &HeaderContext<'_>) -> String;

    /// A finished run's closing text for a task that draws no figures: the
    /// lines for a person and the machine-readable summary line; `None` for
    /// the driving experiment, whose figures and report the program draws.
    fn summary(&self, _finished: &Finished<'_>) -> Option<(String, String)> {
        None
    }

    /// A replay of `genome` for a task that draws no figures: the episode's
    /// end (for stdout) and a note (for stderr); `None` for driving.
    fn replay_text(&self, _genome: &Genome) -> Option<(String, String)> {
        None
    }

    /// A replay's episode of `genome`, step by step, as CSV (written as
    /// `episode.csv`), for a task that records its episodes.
    fn episode_csv(&self, _genome: &Genome) -> Option<String> {
        None
    }

    /// A replay's episodes of `genome` as pictures, step by step (report.html
    /// animates them), for a task that draws its steps.
    fn film(&self, _genome: &Genome) -> Option<Film> {
        None
    }

    /// For a task whose genome is its controller (a plain NEAT network, as
    /// `vivae export` writes it), what the network's outputs mean; `None` otherwise.
    fn network_outputs(&self) -> Option<&'static str> {
        None
    }

    /// The range the inputs of its exported network are read in (with
    /// [`RunTask::network_outputs`]): by default the robot sensors' [0, 1].
    fn network_readings(&self) -> crate::controller::readings::Readings {
        crate::controller::readings::Readings::SENSORS
    }

    /// Whether the end of a run writes `report.html` with the run's curves
    /// alone (a task that draws no figures of its own).
    fn report_curves(&self) -> bool {
        false
    }
}

/// Why `genome` is not a network of `spec`'s inputs and outputs, which
/// `who` (a task, an environment) needs, if it is not.
pub fn check_shape(
    genome: &Genome,
    spec: &GenomeSpec,
    who: &str,
) -> std::result::Result<(), String> {
    let (inputs, outputs) = (genome.num_inputs(), genome.num_outputs());
    if (inputs, outputs) == (spec.inputs, spec.outputs) {
        return Ok(());
    }
    Err(format!(
        "network has {inputs} inputs and {outputs} outputs, {who} needs {} and {}",
        spec.inputs, spec.outputs
    ))
}

impl Clone for Box<dyn RunTask> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

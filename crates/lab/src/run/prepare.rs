//! One preparation of a new run, shared by the command line and Python: a
//! config file (or the task's defaults), the settings given beside it
//! ([`Overrides`]: the CLI's flags and Python's keyword arguments, one name
//! each), checked; then the run's maps, task and starting population.

use std::path::Path;
use std::str::FromStr;

use vivae_neat::{Population, Precision};

use super::population_from_checkpoint;
use crate::config::es::SubstrateKind;
use crate::config::strategy::{BehaviourName, StrategyName};
use crate::config::{Aggregate, Config, NormalizeBy, Recurrence, TaskName};
use crate::controller::polar::PolarGrid;
use crate::error::Result;
use crate::io::bad_input;
use crate::search::StrategyConfig;
use crate::tasks::maps::{self, TrainingMap};
use crate::tasks::{self, RunTask};

mod table;
pub use table::{SETTINGS, Setting, ValueKind, setting};

/// Settings given over a config: each is a config key under the name that
/// the CLI's flag (`--train-neurons`) and Python's keyword (`train_neurons=`)
/// both use. Unset ones leave the config as it is.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// Scenario files or shipped names: one is a single-map run, several a
    /// multi-map run (`experiment.scenario` / `experiment.scenarios`).
    pub scenario: Vec<String>,
    /// `experiment.generations`.
    pub generations: Option<u32>,
    /// `neat.population_size`.
    pub population: Option<usize>,
    /// `experiment.seed`.
    pub seed: Option<u64>,
    /// `surface_sensors.rings` × `angles`.
    pub sensors: Option<PolarGrid>,
    /// `substrate.neurons`.
    pub neurons: Option<PolarGrid>,
    /// `experiment.steps`.
    pub steps: Option<u32>,
    /// `experiment.robots` (0 = all of the scenario's).
    pub robots: Option<usize>,
    /// `run.threads` (0 = one per core).
    pub threads: Option<usize>,
    /// `distance_sensors.rays`.
    pub distance_rays: Option<usize>,
    /// `substrate.train_neurons`.
    pub train_neurons: Option<Vec<PolarGrid>>,
    /// `substrate.train_sensors`.
    pub train_sensors: Option<Vec<PolarGrid>>,
    /// `substrate.train_aggregate`.
    pub train_aggregate: Option<Aggregate>,
    /// `substrate.kind`.
    pub substrate: Option<SubstrateKind>,
    /// `substrate.normalize_by`.
    pub normalize_by: Option<NormalizeBy>,
    /// `substrate.normalize_self_loops`.
    pub normalize_self_loops: Option<bool>,
    /// `substrate.recurrence`.
    pub recurrence: Option<Recurrence>,
    /// `strategy.kind`.
    pub strategy: Option<StrategyName>,
    /// `strategy.behaviour`.
    pub behaviour: Option<BehaviourName>,
    /// `experiment.task` (a registered task).
    pub task: Option<TaskName>,
    /// The task's robot model, where it has a choice (its entry's
    /// [`crate::tasks::TaskEntry::set_robot`]).
    pub robot: Option<String>,
    /// `experiment.placements`.
    pub placements: Option<u32>,
    /// `experiment.placements_aggregate`.
    pub placements_aggregate: Option<Aggregate>,
    /// `experiment.precision`.
    pub precision: Option<Precision>,
}

impl Overrides {
    /// Every override's name, in the order of [`SETTINGS`].
    pub const KEYS: [&'static str; SETTINGS.len()] = {
        let mut keys = [""; SETTINGS.len()];
        let mut i = 0;
        while i < keys.len() {
            keys[i] = SETTINGS[i].key;
            i += 1;
        }
        keys
    };

    /// Sets override `key` from its text as a command line writes it (lists
    /// comma-separated; `scenario` adds one map per call); the error names
    /// the key, the value and what it takes.
    pub fn set(&mut self, key: &str, text: &str) -> std::result::Result<(), String> {
        let what = |e: String| format!("{key} = {text:?}: {e}");
        let Some(setting) = setting(key) else {
            return Err(format!(
                "unknown setting {key:?}; expected one of {}",
                Self::KEYS.join(", ")
            ));
        };
        if let ValueKind::Whole { max } = setting.kind {
            whole(text, max).map_err(what)?;
        }
        match key {
            "scenario" => self.scenario.push(text.to_string()),
            "generations" => self.generations = Some(number(text).map_err(what)?),
            "population" => self.population = Some(number(text).map_err(what)?),
            "seed" => self.seed = Some(number(text).map_err(what)?),
            "sensors" => self.sensors = Some(parse(text).map_err(what)?),
            "neurons" => self.neurons = Some(parse(text).map_err(what)?),
            "steps" => self.steps = Some(number(text).map_err(what)?),
            "robots" => self.robots = Some(number(text).map_err(what)?),
            "threads" => self.threads = Some(number(text).map_err(what)?),
            "distance_rays" => self.distance_rays = Some(number(text).map_err(what)?),
            "train_neurons" => self.train_neurons = Some(grids(text).map_err(what)?),
            "train_sensors" => self.train_sensors = Some(grids(text).map_err(what)?),
            "train_aggregate" => self.train_aggregate = Some(parse(text).map_err(what)?),
            "substrate" => self.substrate = Some(parse(text).map_err(what)?),
            "normalize_by" => self.normalize_by = Some(parse(text).map_err(what)?),
            "normalize_self_loops" => {
                self.normalize_self_loops = Some(boolean(text).map_err(what)?)
            }
            "recurrence" => self.recurrence = Some(parse(text).map_err(what)?),
            "strategy" => self.strategy = Some(parse(text).map_err(what)?),
            "behaviour" => self.behaviour = Some(parse(text).map_err(what)?),
            "robot" => self.robot = Some(text.trim().to_string()),
            "placements" => self.placements = Some(number(text).map_err(what)?),
            "placements_aggregate" => self.placements_aggregate = Some(parse(text).map_err(what)?),
            "precision" => self.precision = Some(parse(text).map_err(what)?),
            "task" => {
                tasks::entry(text).map_err(|e| format!("{key} = {e}"))?;
                self.task = Some(TaskName(text.to_string()));
            }
            // A row of SETTINGS without its arm here is a bug the tests catch.
            other => return Err(format!("setting {other:?} is not read")),
        }
        Ok(())
    }

    /// Whether `text` is a value setting `key` takes: the error says what
    /// it takes, without naming the setting (which a front end names its way).
    pub fn check(key: &str, text: &str) -> std::result::Result<(), String> {
        let e = match Overrides::default().set(key, text) {
            Ok(()) => return Ok(()),
            Err(e) => e,
        };
        let named = format!("{key} = {text:?}: ");
        let rest = (e.strip_prefix(&named)).or_else(|| e.strip_prefix(&format!("{key} = ")));
        Err(rest.unwrap_or(&e).to_string())
    }

    /// Writes the overrides that are set into `config` (unchecked: see [`config`]).
    pub fn apply(&self, c: &mut Config) -> std::result::Result<(), String> {
        // Given maps replace the config's: one is a single-map run, several a multi-map run.
        match self.scenario.as_slice() {
            [] => {}
            [one] => {
                c.experiment.scenario = one.clone();
                c.experiment.scenarios.clear();
            }
            several => {
                c.experiment.scenario.clear();
                c.experiment.scenarios = several.to_vec();
            }
        }
        let e = &mut c.experiment;
        set(&mut e.generations, self.generations);
        set(&mut e.seed, self.seed);
        set(&mut e.steps, self.steps);
        set(&mut e.robots, self.robots);
        set(&mut e.task, self.task.clone());
        set(&mut e.placements, self.placements);
        set(&mut e.placements_aggregate, self.placements_aggregate);
        set(&mut e.precision, self.precision);
        set(&mut c.neat.population_size, self.population);
        if let Some(g) = self.sensors {
            (c.surface_sensors.rings, c.surface_sensors.angles) = (g.rings, g.angles);
        }
        set(&mut c.run.threads, self.threads);
        set(&mut c.distance_sensors.rays, self.distance_rays);
        let s = &mut c.substrate;
        set(&mut s.neurons, self.neurons);
        set(&mut s.train_neurons, self.train_neurons.clone());
        set(&mut s.train_sensors, self.train_sensors.clone());
        set(&mut s.train_aggregate, self.train_aggregate);
        set(&mut s.kind, self.substrate);
        set(&mut s.normalize_by, self.normalize_by);
        set(&mut s.normalize_self_loops, self.normalize_self_loops);
        set(&mut s.recurrence, self.recurrence);
        StrategyConfig::update(c, |s| {
            set(&mut s.kind, self.strategy.clone());
            set(&mut s.behaviour, self.behaviour.clone());
        });
        match &self.robot {
            Some(robot) => tasks::set_robot(c, robot),
            None => Ok(()),
        }
    }
}

/// `*slot = value` when a value is given.
fn set<T>(slot: &mut T, value: Option<T>) {
    if let Some(v) = value {
        *slot = v;
    }
}

fn number<T: FromStr>(text: &str) -> std::result::Result<T, String> {
    text.trim()
        .parse()
        .map_err(|_| "expected a whole number of the key's range".to_string())
}

/// `text` is a whole number from 0 to `max`.
fn whole(text: &str, max: u64) -> std::result::Result<(), String> {
    match text.trim().parse::<u64>() {
        Ok(n) if n <= max => Ok(()),
        Ok(_) => Err(format!("at most {max}")),
        _ => Err(format!("expected a whole number from 0 to {max}")),
    }
}

fn boolean(text: &str) -> std::result::Result<bool, String> {
    text.trim()
        .parse()
        .map_err(|_| "expected true or false".to_string())
}

fn parse<T: FromStr>(text: &str) -> std::result::Result<T, String>
where
    T::Err: std::fmt::Display,
{
    text.parse().map_err(|e: T::Err| e.to_string())
}

fn grids(text: &str) -> std::result::Result<Vec<PolarGrid>, String> {
    text.split(',').map(parse).collect()
}

/// How a front end names its settings in messages: the library's refusals
/// of a setting say where it came from and spell its key as the user wrote it.
#[derive(Debug, Clone, Copy)]
pub struct Spelling {
    /// Where the settings came from (`command line`, `arguments`).
    pub origin: &'static str,
    /// A setting's name as the front end writes it, from its [`Overrides`]
    /// key (`--train-neurons`, `train_neurons=`).
    pub key: fn(&str) -> String,
    /// A switch turned on as the front end writes it (`--force`, `force=True`).
    pub on: fn(&str) -> String,
}

impl Spelling {
    /// The library's own spelling: settings named by their [`Overrides`] key.
    pub const KEYS: Spelling = Spelling {
        origin: "settings",
        key: |k| format!("{k} = "),
        on: |k| format!("{k} = true"),
    };

    /// `e`'s message, the settings a [`crate::Error::Refused`] names spelled
    /// as the front end writes them (`--out`, `out=`); any other error as it is.
    pub fn error(&self, e: &crate::Error) -> String {
        match e {
            crate::Error::Refused(r) => r.spelled(self.key, self.on),
            e => e.to_string(),
        }
    }

    /// `message` (a refusal of [`Overrides`] that opens with `key = `) with
    /// its key spelled as the front end writes it.
    pub fn spell(&self, message: &str) -> String {
        for key in Overrides::KEYS {
            if let Some(rest) = message.strip_prefix(&format!("{key} = ")) {
                return format!("{}{rest}", (self.key)(key));
            }
        }
        message.to_string()
    }
}

/// The config a new run starts from before its overrides: `file` (its task
/// named there), or the defaults of `task` (the paper's driving experiment
/// when none is named). A task named beside a file that names another is
/// refused, the setting spelled by `spelling`: the file says which task it is.
pub fn base_config(
    file: Option<&Path>,
    task: Option<&TaskName>,
    spelling: &Spelling,
) -> Result<Config> {
    match file {
        Some(p) => {
            let c = tasks::read_config(p)?;
            match c.task_mismatch(task) {
                Some(why) => {
                    let t = task.map_or("", TaskName::name);
                    Err(bad_input(format!("{}{t}: {why}", (spelling.key)("task"))))
                }
                None => Ok(c),
            }
        }
        None => tasks::default_config(task).map_err(bad_input),
    }
}

/// The task a new run names: the overrides' `task`, else (without a config
/// file) the task its shipped scenarios are drawn for (`hard-maze`: the maze).
pub fn task_named(file: Option<&Path>, overrides: &Overrides) -> Option<TaskName> {
    let drawn_for = (file.is_none() && overrides.task.is_none())
        .then(|| crate::tasks::scenarios::task_of(&overrides.scenario))
        .flatten()
        .map(|t| TaskName(t.to_string()));
    overrides.task.clone().or(drawn_for)
}

/// A new run's settings resolved: the config it runs and whether it was
/// built from its task's defaults (no config file), so that the task may
/// fit the settings it fits to itself ([`RunTask::fit_defaults`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// The checked config.
    pub config: Config,
    /// No config file: the task's own defaults, which [`prepare`] fits.
    pub task_defaults: bool,
}

/// The one resolution of a new run's settings, for the command line and
/// Python alike: `file` (or the defaults of the task the overrides name or
/// their shipped scenario is drawn for) with `overrides` applied, checked by
/// every rule of its task; refusals are spelled by `spelling`.
pub fn resolve(
    file: Option<&Path>,
    overrides: &Overrides,
    spelling: &Spelling,
) -> Result<Resolved> {
    let task = task_named(file, overrides);
    let mut config = base_config(file, task.as_ref(), spelling)?;
    let refused = |e: String| bad_input(format!("{}: {e}", spelling.origin));
    (overrides.apply(&mut config)).map_err(|e| refused(spelling.spell(&e)))?;
    tasks::check(&config).map_err(|e| refused(e.to_string()))?;
    Ok(Resolved {
        config,
        task_defaults: file.is_none(),
    })
}

impl Resolved {
    /// Loads what the config names ([`prepare`]), fitting the task's
    /// defaults when there was no config file.
    pub fn prepare(self) -> Result<Prepared> {
        prepare(self.config, self.task_defaults)
    }
}

/// [`resolve`]'s config alone, refusals spelled by [`Spelling::KEYS`] with
/// `what` as their origin.
pub fn config(file: Option<&Path>, overrides: &Overrides, what: &'static str) -> Result<Config> {
    let spelling = Spelling {
        origin: what,
        ..Spelling::KEYS
    };
    Ok(resolve(file, overrides, &spelling)?.config)
}

/// A new run, prepared: its config, maps, task and starting population.
#[derive(Debug)]
pub struct Prepared {
    /// The resolved config.
    pub config: Config,
    /// The training maps as loaded (one for a single-map run).
    pub maps: Vec<TrainingMap>,
    /// What genomes are evaluated on.
    pub task: Box<dyn RunTask>,
    /// The population to start from (`experiment.init_population`), if any.
    pub init: Option<Population>,
}

/// Loads what `config` names: its maps, its task, its starting population;
/// with `task_defaults` (no config file: the task's own defaults), settings
/// the task fits to its scenario ([`RunTask::fit_defaults`]) are fitted.
pub fn prepare(mut config: Config, task_defaults: bool) -> Result<Prepared> {
    let maps = maps::load(&config)?;
    let task = tasks::build(&config, &maps)?;
    let init = match config.experiment.init_population.as_str() {
        "" => None,
        path => Some(population_from_checkpoint(Path::new(path))?.1),
    };
    if task_defaults {
        task.fit_defaults(&mut config);
    }
    Ok(Prepared {
        config,
        maps,
        task,
        init,
    })
}

impl Prepared {
    /// Creates the run in `dir` (see [`crate::run::Run::create_task`]).
    pub fn create(self, dir: &Path, force: bool) -> Result<crate::run::Run> {
        let Prepared {
            config,
            maps,
            task,
            init,
        } = self;
        // A task without maps has no first map: its run has no scenario.svg.
        let first = maps.first().map(|m| m.loaded.text.clone());
        if first.is_none() && maps::uses_maps(&config) {
            return Err(bad_input("no scenario"));
        }
        let maps = if maps::is_multi_map(&config) {
            maps
        } else {
            Vec::new()
        };
        crate::run::Run::create_task(dir, config, task, first.as_deref(), &maps, init, force)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_can_be_set_from_text_and_unknown_keys_are_named() {
        let mut o = Overrides::default();
        let samples = [
            ("scenario", "oval"),
            ("generations", "3"),
            ("population", "10"),
            ("seed", "9"),
            ("sensors", "3x6"),
            ("neurons", "5x5"),
            ("steps", "50"),
            ("robots", "2"),
            ("threads", "1"),
            ("distance_rays", "5"),
            ("train_neurons", "3x3,5x5"),
            ("train_sensors", "3x5"),
            ("train_aggregate", "min"),
            ("substrate", "polar"),
            ("normalize_by", "area"),
            ("normalize_self_loops", "false"),
            ("recurrence", "self"),
            ("strategy", "neat"),
            ("behaviour", "end-position"),
            ("task", "driving"),
            ("robot", "khepera"),
            ("placements", "1"),
            ("placements_aggregate", "mean"),
            ("precision", "exact"),
        ];
        for (key, text) in samples {
            o.set(key, text).unwrap_or_else(|e| panic!("{key}: {e}"));
        }
        // Every row of the table is sampled here, once.
        let mut sampled: Vec<&str> = samples.iter().map(|(k, _)| *k).collect();
        let mut keys = Overrides::KEYS.to_vec();
        sampled.sort();
        keys.sort();
        keys.dedup();
        assert_eq!(sampled, keys);
        assert_eq!(keys.len(), SETTINGS.len(), "one row per key");
        // A robot model is the task's to read (the tasks with a choice test
        // theirs): refused by a task without a choice.
        let e = o.apply(&mut Config::default()).unwrap_err();
        assert!(e.contains("a driving run has one robot model"), "{e}");
        o.robot = None;
        let mut c = Config::default();
        o.apply(&mut c).unwrap();
        assert_eq!((c.experiment.generations, c.neat.population_size), (3, 10));
        assert_eq!(c.substrate.train_neurons.len(), 2);
        assert_eq!(c.experiment.scenario, "oval");
        let e = o.set("popsize", "3").unwrap_err();
        assert!(e.contains("popsize") && e.contains("population"), "{e}");
        let e = o.set("steps", "-5").unwrap_err();
        assert!(e.starts_with("steps = \"-5\""), "{e}");
        let e = o.set("precision", "half").unwrap_err();
        assert!(e.contains("expected exact or fast"), "{e}");
        let e = o.set("task", "chess").unwrap_err();
        assert!(e.contains("chess") && e.contains("driving"), "{e}");
    }

    #[test]
    fn a_whole_number_setting_takes_its_rows_range_and_no_more() {
        for s in SETTINGS {
            let ValueKind::Whole { max } = s.kind else {
                continue;
            };
            Overrides::default()
                .set(s.key, &max.to_string())
                .unwrap_or_else(|e| panic!("{}: {e}", s.key));
            let over = u128::from(max) + 1;
            let e = Overrides::check(s.key, &over.to_string()).unwrap_err();
            assert!(e.contains(&max.to_string()), "{}: {e}", s.key);
        }
        assert_eq!(
            Overrides::check("threads", "2000").unwrap_err(),
            "at most 1024"
        );
        let e = Overrides::check("steps", "-5").unwrap_err();
        assert_eq!(e, "expected a whole number from 0 to 4294967295");
        let e = Overrides::check("precision", "half").unwrap_err();
        assert!(
            !e.starts_with("precision") && e.contains("expected exact or fast"),
            "{e}"
        );
        assert!(Overrides::check("train_neurons", "3x3,5x5").is_ok());
        assert!(
            Overrides::check("popsize", "3")
                .unwrap_err()
                .contains("unknown")
        );
    }

    #[test]
    fn refusals_of_a_setting_are_spelled_as_the_front_end_writes_it() {
        let o = Overrides {
            robot: Some("vivae".into()),
            ..Overrides::default()
        };
        let cli = Spelling {
            origin: "command line",
            key: |k| format!("--{} ", k.replace('_', "-")),
            on: |k| format!("--{}", k.replace('_', "-")),
        };
        let e = resolve(None, &o, &cli).unwrap_err().to_string();
        assert!(
            e.starts_with("command line: --robot vivae: a driving run"),
            "{e}"
        );
        let e = resolve(None, &o, &Spelling::KEYS).unwrap_err().to_string();
        assert!(
            e.starts_with("settings: robot = vivae: a driving run"),
            "{e}"
        );
        // A shipped scenario drawn for a task names that task: its defaults.
        let maze = Overrides {
            scenario: vec!["hard-maze".into()],
            ..Overrides::default()
        };
        let r = resolve(None, &maze, &cli).unwrap();
        assert_eq!(r.config.experiment.task.name(), "maze");
        assert!(r.task_defaults);
    }

    #[test]
    fn a_named_task_starts_from_its_defaults_and_a_file_of_another_task_is_refused() {
        // Every task but the default one: none is named here.
        let others = crate::tasks::TASKS
            .iter()
            .filter(|t| t.name != TaskName::DRIVING);
        let mut o = Overrides::default();
        for task in others {
            o.task = Some(TaskName(task.name.into()));
            let c = config(None, &o, "test").unwrap();
            assert_eq!(c, (task.default_config)(), "{}", task.name);
        }
        assert!(o.task.is_some(), "a second task is registered");
        let dir = std::env::temp_dir().join(format!("vivae-prepare-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("driving.toml");
        std::fs::write(&file, "[experiment]\nseed = 4\n").unwrap();
        let e = config(Some(&file), &o, "test").unwrap_err().to_string();
        assert!(e.contains("experiment.task is driving"), "{e}");
        let c = config(Some(&file), &Overrides::default(), "test").unwrap();
        assert_eq!(c.experiment.seed, 4);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

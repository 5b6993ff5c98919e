//! The settings a front end gives over a config, one row each: the CLI
//! builds its flags from these rows and Python converts its keyword
//! arguments by their kind, so that a new setting is one row here (and its
//! field, parsed and applied, in [`super::Overrides`]).

/// The kind of value a setting takes, which says how a front end writes it
/// as the text [`super::Overrides::set`] parses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueKind {
    /// A whole number from 0 to `max`.
    Whole {
        /// The largest value taken.
        max: u64,
    },
    /// A sheet's resolution, `RINGSxANGLES`.
    Grid,
    /// Sheets' resolutions, comma-separated.
    Grids,
    /// `true` or `false`.
    Bool,
    /// A name or other text, read by the setting's own type.
    Name,
    /// A scenario file or shipped name, one per map: the setting repeats.
    Scenarios,
}

/// One setting given over a config.
#[derive(Debug, Clone, Copy)]
pub struct Setting {
    /// Its name: the [`super::Overrides`] key, the CLI's flag
    /// (`--train-neurons`) and Python's keyword (`train_neurons=`).
    pub key: &'static str,
    /// The config key (or keys) it sets.
    pub config_key: &'static str,
    /// The kind of value it takes.
    pub kind: ValueKind,
    /// Its value as help shows it (`N`, `RxA`, `mean|min`).
    pub value_name: &'static str,
    /// What it does, in one line.
    pub help: &'static str,
    /// The registered names it takes (tasks, strategies), where a registry
    /// lists them; `None`: its type says which values it takes.
    pub choices: Option<fn() -> Vec<&'static str>>,
}

impl Setting {
    /// A setting whose values its type checks (no registry lists them).
    const fn new(
        key: &'static str,
        config_key: &'static str,
        kind: ValueKind,
        value_name: &'static str,
        help: &'static str,
    ) -> Setting {
        Setting {
            key,
            config_key,
            kind,
            value_name,
            help,
            choices: None,
        }
    }

    /// This setting taking one of the names `choices` lists.
    const fn choices(self, choices: fn() -> Vec<&'static str>) -> Setting {
        Setting {
            choices: Some(choices),
            ..self
        }
    }
}

/// A whole number of type `u32`, `u64` or `usize`, up to its largest.
const fn whole(max: u64) -> ValueKind {
    ValueKind::Whole { max }
}

const U32: u64 = u32::MAX as u64;
const USIZE: u64 = usize::MAX as u64;

use ValueKind::{Bool, Grid, Grids, Name, Scenarios};

/// Every setting given over a config, in the order help lists them.
pub const SETTINGS: &[Setting] = &[
    Setting::new(
        "scenario",
        "experiment.scenario, experiment.scenarios",
        Scenarios,
        "FILE|NAME",
        "Scenario SVG file, or the name of a shipped one (`vivae scenario list`; default: the embedded road scenario). Repeat it to train on several maps at once (fitness = the mean over maps)",
    ),
    Setting::new(
        "generations",
        "experiment.generations",
        whole(U32),
        "N",
        "Generations to evolve",
    ),
    Setting::new(
        "population",
        "neat.population_size",
        whole(USIZE),
        "N",
        "Population size",
    ),
    Setting::new(
        "seed",
        "experiment.seed",
        whole(u64::MAX),
        "N",
        "Random seed",
    ),
    Setting::new(
        "sensors",
        "surface_sensors.rings, surface_sensors.angles",
        Grid,
        "RxA",
        "Surface sensors as RINGSxANGLES (default: the run's, or the config's; paper: 3x5); a run's genomes are re-sampled onto it",
    ),
    Setting::new(
        "neurons",
        "substrate.neurons",
        Grid,
        "RxA",
        "Output neurons as RINGSxANGLES (default: the run's, or the config's; paper: 3x3); a run's genomes are re-sampled onto it",
    ),
    Setting::new(
        "steps",
        "experiment.steps",
        whole(U32),
        "N",
        "Simulation steps per evaluation",
    ),
    Setting::new(
        "robots",
        "experiment.robots",
        whole(USIZE),
        "N",
        "Robots: the scenario's first N (0 = all of them; paper: 5)",
    ),
    Setting::new(
        "threads",
        "run.threads",
        whole(crate::config::MAX_THREADS as u64),
        "N",
        "Evaluation threads (0 = one per core, at most 1024); results do not depend on it",
    ),
    Setting::new(
        "train_neurons",
        "substrate.train_neurons",
        Grids,
        "RxA,...",
        "Multi-resolution evolution: evaluate every genome at these neuron sheets (e.g. 3x3,5x5,9x9) and aggregate; --neurons stays the one reported",
    ),
    Setting::new(
        "train_sensors",
        "substrate.train_sensors",
        Grids,
        "RxA,...",
        "Multi-resolution evolution: evaluate every genome at these sensor sheets (e.g. 3x5,3x6), with each of --train-neurons",
    ),
    Setting::new(
        "train_aggregate",
        "substrate.train_aggregate",
        Name,
        "mean|min",
        "How the training resolutions' fitnesses combine: mean (default) or min",
    ),
    Setting::new(
        "substrate",
        "substrate.kind",
        Name,
        "polar|es-hyperneat",
        "Substrate kind: polar (the dense neuron sheet, the paper's) or es-hyperneat (hidden neurons placed by the CPPN; keys in [substrate.es])",
    ),
    Setting::new(
        "normalize_by",
        "substrate.normalize_by",
        Name,
        "count|area",
        "With substrate.normalize: count (the paper's) or area (each node by its share of the sheet's polar area)",
    ),
    Setting::new(
        "normalize_self_loops",
        "substrate.normalize_self_loops",
        Bool,
        "true|false",
        "With substrate.normalize: false keeps self-loops at the CPPN's weight at any neuron resolution (default true, the paper's)",
    ),
    Setting::new(
        "recurrence",
        "substrate.recurrence",
        Name,
        "full|self|none",
        "Neuron→neuron links kept: full (the paper's), self (self-loops only, no lateral links) or none",
    ),
    Setting::new(
        "strategy",
        "strategy.kind",
        Name,
        "NAME",
        "Search strategy (strategy.kind; default neat, the paper's)",
    )
    .choices(strategy_names),
    Setting::new(
        "behaviour",
        "strategy.behaviour",
        Name,
        "NAME",
        "Behaviour descriptor of the strategies that search on one (strategy.behaviour; default end-position): the task decides which of these apply, and refuses another naming its own",
    )
    .choices(behaviour_names),
    Setting::new(
        "task",
        "experiment.task",
        Name,
        "NAME",
        "Task (experiment.task; default driving, the paper's); docs/howto/ has a page per task: what it evaluates and which scenario it starts from",
    )
    .choices(task_names),
    Setting::new(
        "distance_rays",
        "distance_sensors.rays",
        whole(USIZE),
        "N",
        "Distance rays of the second input sheet (distance_sensors.rays; 0 = none)",
    ),
    Setting::new(
        "robot",
        "the task's robot model (maze.robot)",
        Name,
        "MODEL",
        "The task's robot model, where it has a choice (the maze: lehman, the default, Lehman's navigator; or vivae, our robot of [physics])",
    ),
    Setting::new(
        "placements",
        "experiment.placements",
        whole(U32),
        "N",
        "Placements per evaluation on a scenario that places obstacles or traffic per evaluation (experiment.placements; default 1): every genome is scored on N placements drawn from its evaluation's seed",
    ),
    Setting::new(
        "placements_aggregate",
        "experiment.placements_aggregate",
        Name,
        "mean|min",
        "How the fitnesses on --placements placements combine: mean (default) or min",
    ),
    Setting::new(
        "precision",
        "experiment.precision",
        Name,
        "exact|fast",
        "Arithmetic of the controller step (experiment.precision): exact (the default, f64) or fast (f32 and a polynomial sigmoid: other bits, the same on every CPU). A resumed run keeps its checkpoint's",
    ),
];

/// The registered tasks' names.
fn task_names() -> Vec<&'static str> {
    crate::tasks::names().to_vec()
}

/// The behaviour descriptors' names the registered tasks offer.
fn behaviour_names() -> Vec<&'static str> {
    crate::tasks::behaviours::names()
}

/// The registered strategies' names.
fn strategy_names() -> Vec<&'static str> {
    (crate::search::entries().iter()).map(|e| e.kind).collect()
}

/// The setting called `key`.
pub fn setting(key: &str) -> Option<&'static Setting> {
    SETTINGS.iter().find(|s| s.key == key)
}

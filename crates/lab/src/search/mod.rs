//! The search a run holds: one [`Search`] value, whichever strategy the
//! config's `[strategy]` section names, that the driver runs and the
//! checkpoint stores. It is a [`Strategy`](vivae_neat::driver::Strategy) by
//! delegation to the one inside.
//!
//! Each strategy is one file here: its [`StrategyEntry`] (registered in
//! [`STRATEGIES`]: the columns it adds to `generations.csv`, how it is built
//! from the config, its header line, its part of the report, the files it
//! writes with each checkpoint, its settings section), its [`RunStrategy`]
//! (its fields of each row and of the summary line, how it writes its
//! files, its figure as one of the shapes the program draws). [`Search`]
//! holds any of them as a trait object and stores it in a checkpoint as
//! `{"Name": state}`, read back by the entry whose `variant` is `Name`.
//! This file is where strategies are registered: a new strategy is its file
//! and its line in `built_in!` below. Its settings are a
//! [`StrategySettings`] type registered with its entry ([`Settings::of`]),
//! kept in [`StrategyConfig::sections`]; the first four strategies' settings
//! are fields of [`StrategyConfig`] (with their lines in `validate` and
//! `fit_to`), so that their configs keep their bytes.
//!
//! The seam itself is in `registry.rs` (entries, registration and the
//! config's check), `run_strategy.rs` (what a run and the program need of a
//! strategy), `dynamic.rs` (the trait object a run holds), `sections.rs`
//! (the registered settings sections and the `[strategy]` section's serde
//! form) and `start.rs` (generation 0).

mod dynamic;
pub mod files;
mod registry;
mod run_strategy;
mod sections;
mod start;

pub use dynamic::{DynStrategy, Search};
pub use map_elites::{CellsKind, MapElitesConfig};
pub use novelty::novelty_defaults;
pub use nsga2::{Nsga2Config, front_objective_names, objective_among};
pub use registry::{
    BehaviourSpace, Needs, ReportOf, Settings, Start, StrategyEntry, StrategySettings, check,
    entries, entry, entry_of, register, state_of,
};
pub(crate) use registry::{behaviour_line, takers};
pub use run_strategy::{
    FrontFigure, GridFigure, GridReport, RunStrategy, StrategyFigure, StrategyReport,
};
pub use sections::Sections;
pub use start::{initial_population, leo_seeded};
pub(crate) use start::{refuse_init, starting_population};

use schemars::JsonSchema;
use serde::Deserialize;
use vivae_neat::strategies::NoveltyParams;

use crate::config::strategy::{BehaviourName, StrategyName};
use crate::config::{Config, OwnedSection, Section};

/// Declares each built-in strategy's file (a module of this folder) and
/// lists its entry in [`STRATEGIES`]: one line per strategy.
macro_rules! built_in {
    ($($file:ident),* $(,)?) => {
        $(mod $file;)*

        /// The strategies built in; `strategy.kind` names one of them or
        /// one [`register`]ed by a program.
        pub static STRATEGIES: &[&StrategyEntry] = &[$(&$file::STRATEGY),*];
    };
}

built_in! {
    neat,
    novelty,
    map_elites,
    nsga2,
    one_plus_lambda,
}

/// The search strategy (NEAT by default) and its settings.
// Serialised by hand (`sections.rs`): the fields in order, then the
// registered sections a config sets or its strategy reads. The config
// holds it as the search layer's own section ([`SECTION`]).
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(default)]
pub struct StrategyConfig {
    /// Search algorithm: neat, novelty, map-elites, nsga2 or any other
    /// registered strategy.
    ///
    /// Paper: neat.
    pub kind: StrategyName,
    /// Behaviour descriptor for novelty and map-elites: one the task offers
    /// (a run of another is refused with the names it offers; the
    /// strategies guide describes each); a task with a descriptor of its own
    /// and no choice of them leaves it at end-position.
    pub behaviour: BehaviourName,
    /// Novelty search (unit of the thresholds: behaviour units, e.g. arena
    /// sizes for end positions).
    pub novelty: NoveltyParams,
    /// MAP-Elites.
    pub map_elites: MapElitesConfig,
    /// NSGA-II.
    pub nsga2: Nsga2Config,
    /// The sections of the strategies that register their settings with
    /// their entry ([`Settings`]), by name; any other key is refused.
    #[serde(flatten)]
    pub sections: Sections,
}

impl Default for StrategyConfig {
    fn default() -> Self {
        StrategyConfig {
            kind: StrategyName::default(),
            behaviour: BehaviourName::default(),
            novelty: novelty_defaults(),
            map_elites: MapElitesConfig::default(),
            nsga2: Nsga2Config::default(),
            sections: Sections::default(),
        }
    }
}

impl OwnedSection for StrategyConfig {
    const NAME: &'static str = "strategy";
}

/// The `[strategy]` section's registration: the config holds it beside the
/// tasks' own sections ([`crate::tasks::sections`]).
pub const SECTION: Section = Section {
    defaults: documented_defaults,
    ..Section::of::<StrategyConfig>()
};

/// `[strategy]` as the config reference documents it: every key at its
/// default (`novelty.metric` too, written only when set) and every
/// registered strategy's settings section.
fn documented_defaults() -> toml::Table {
    let mut strategy = match toml::Value::try_from(StrategyConfig::default()) {
        Ok(toml::Value::Table(t)) => t,
        _ => unreachable!("[strategy] is a table"),
    };
    if let Some(novelty) = strategy.get_mut("novelty").and_then(|s| s.as_table_mut()) {
        novelty.insert("metric".into(), toml::Value::String("euclidean".into()));
    }
    let sections = Sections::documented().into_iter();
    strategy.extend(sections.map(|(name, s)| (name.to_string(), toml::Value::Table(s))));
    strategy
}

impl StrategyConfig {
    /// The section as `config` sets it.
    pub fn of(config: &Config) -> StrategyConfig {
        config.owned.of()
    }

    /// Fits `config`'s strategy settings to what a task says of itself
    /// ([`StrategyConfig::fit_to`]).
    pub fn fit(config: &mut Config, task: &TaskFacts<'_>) {
        config.owned.update(|s: &mut StrategyConfig| s.fit_to(task));
    }

    /// Changes `config`'s strategy settings by `change`.
    pub fn update(config: &mut Config, change: impl FnOnce(&mut StrategyConfig)) {
        config.owned.update(change);
    }

    /// Whether this is the default (NEAT, every setting at its default): a
    /// config that is written without its `[strategy]` section.
    pub fn is_default(&self) -> bool {
        *self == StrategyConfig::default()
    }

    /// Checks every strategy's settings for a task whose evaluations carry
    /// `metrics` (sizes that depend on the robots are checked when the run
    /// starts; the strategy's name and what it asks of the run, by
    /// [`check`]); the error names the key.
    pub fn validate(&self, metrics: &[&str]) -> Result<(), String> {
        novelty::validate(&self.novelty)?;
        map_elites::validate(&self.map_elites)?;
        nsga2::validate(&self.nsga2, metrics)?;
        self.sections.validate(metrics)
    }

    /// The settings `T` of a registered section (`[strategy.NAME]`), its
    /// keys left out at their defaults; the error names the section.
    pub fn settings<T: StrategySettings>(&self) -> std::result::Result<T, String> {
        self.sections.settings()
    }

    /// Fits every strategy's settings to what a task says of itself, for the
    /// task's default config (each strategy's file says what it reads).
    pub fn fit_to(&mut self, task: &TaskFacts<'_>) {
        novelty::fit_to(&mut self.novelty, task);
        map_elites::fit_to(&mut self.map_elites, task);
        nsga2::fit_to(&mut self.nsga2, task);
    }
}

/// What a task says of itself for the strategies to fit their settings in
/// its default config to it, in its own terms (the defaults suit descriptors
/// in the unit box and the driving task's metrics); `None` or empty leaves
/// the settings that read it as they are.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TaskFacts<'a> {
    /// The metrics its evaluations carry, which objectives may select on
    /// beside fitness.
    pub metrics: Option<&'a [&'a str]>,
    /// How far apart (in descriptor units) two of its behaviours are to
    /// count as different.
    pub distinct: Option<f64>,
    /// The least that distance may adapt down to.
    pub distinct_floor: Option<f64>,
    /// The width (in descriptor units) of a cell of its behaviour space
    /// worth one elite.
    pub cell: Option<f64>,
    /// How far each dimension of its behaviour space spans from its lower
    /// bound (one for all dimensions, or one per dimension), for `cell`.
    pub extent: &'a [f64],
}

/// The message of a bad setting `strategy.{key} = value`: why it is bad.
pub(crate) fn bad_setting(key: &str, value: &dyn std::fmt::Debug, why: &str) -> String {
    format!("strategy.{key} = {value:?}: {why}")
}

#[cfg(test)]
mod tests {
    use super::*;
    /// A task's metrics (the driving task's).
    const METRICS: [&str; 2] = ["contacts", "on_road"];

    #[test]
    fn bad_settings_name_their_key() {
        let validate = |s: &StrategyConfig| s.validate(&METRICS);
        let mut s = StrategyConfig::default();
        s.nsga2.objectives = vec!["speed".into()];
        let e = validate(&s).unwrap_err();
        assert!(
            e.starts_with("strategy.nsga2.objectives = \"speed\""),
            "{e}"
        );
        let mut s = StrategyConfig::default();
        s.novelty.k = 0;
        assert!(validate(&s).unwrap_err().starts_with("strategy.novelty.k"));
        s = StrategyConfig::default();
        s.map_elites.bins = vec![4, 0];
        let e = validate(&s).unwrap_err();
        assert!(
            e.starts_with("strategy.map_elites.bins = [4, 0]: one count"),
            "{e}"
        );
        s = StrategyConfig::default();
        s.map_elites.cvt_samples = 10;
        let e = validate(&s).unwrap_err();
        assert_eq!(
            e,
            "strategy.map_elites.cvt_cells = 100: need 1 ≤ cvt_cells ≤ cvt_samples"
        );
        assert!(validate(&StrategyConfig::default()).is_ok());
    }

    #[test]
    fn fitting_to_a_task_reads_only_what_it_says() {
        let mut s = StrategyConfig::default();
        s.fit_to(&TaskFacts::default());
        assert!(s.is_default());
        s.fit_to(&TaskFacts {
            metrics: Some(&["contacts"]),
            ..TaskFacts::default()
        });
        assert!(s.is_default());
        s.fit_to(&TaskFacts {
            metrics: Some(&[]),
            distinct: Some(6.0),
            cell: Some(10.0),
            extent: &[300.0, 131.0],
            ..TaskFacts::default()
        });
        assert_eq!(s.nsga2.objectives, ["fitness"]);
        assert_eq!(s.novelty.threshold, 6.0);
        assert_eq!(
            s.novelty.threshold_floor,
            novelty_defaults().threshold_floor
        );
        assert_eq!(s.map_elites.bins, [30, 14]);
    }
}

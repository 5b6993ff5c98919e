//! A strategy's registration: its [`StrategyEntry`], the built-in ones
//! and those a program [`register`]s, and the check of a config's
//! `[strategy]` section against the one it names.

use std::path::Path;

use schemars::JsonSchema;
use serde::{Serialize, de::DeserializeOwned};
use vivae_neat::{GenomeSpec, Population};

use crate::config::Config;
use crate::error::Result;
use crate::io::bad_input;
use crate::search::StrategyConfig;
use crate::search::{DynStrategy, STRATEGIES, Search, StrategyReport, sections};

/// The behaviour descriptors a task gives for a run's `strategy.behaviour`:
/// the box they lie in (a grid archive's cells cover it) and their
/// coordinates' names (the archive's columns, its figure's axes). Empty for
/// a task that gives none.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BehaviourSpace {
    /// Each coordinate's least value.
    pub lower: Vec<f64>,
    /// Each coordinate's greatest value.
    pub upper: Vec<f64>,
    /// Each coordinate's name.
    pub names: Vec<String>,
}

impl BehaviourSpace {
    /// How many coordinates a descriptor has.
    pub fn dims(&self) -> usize {
        self.lower.len()
    }
}

/// A strategy's registration: what a run needs of it before it exists.
pub struct StrategyEntry {
    /// Its `strategy.kind`.
    pub kind: &'static str,
    /// What it selects on beside fitness, which the task then measures.
    pub needs: Needs,
    /// Whether it can start from given genomes (`experiment.init_population`,
    /// LEO's seeded generation 0) rather than minimal ones.
    pub takes_population: bool,
    /// Its name in a checkpoint's `search` field (`{"Name": state}`).
    pub variant: &'static str,
    /// The strategy of a checkpoint's state (its JSON text).
    pub from_state: fn(&str) -> serde_json::Result<Search>,
    /// The columns it adds to `generations.csv` (after NEAT's), each with its
    /// leading comma.
    pub extra_columns: &'static str,
    /// Its generation 0.
    pub build: fn(Start<'_>) -> Result<Search>,
    /// The line the run's header says of it (with its leading line break), or empty.
    pub header_line: fn(&Config) -> String,
    /// What the report of the run in a directory shows of it, read from the
    /// files it wrote (`None`: nothing, as for NEAT); the task's behaviour
    /// descriptors given.
    pub report: ReportOf,
    /// The files it writes into the run directory with each checkpoint
    /// ([`RunStrategy::write_outputs`](crate::search::RunStrategy::write_outputs)):
    /// `--force` replaces a run folder holding them, the viewer watches them.
    pub files: &'static [&'static str],
    /// Its own settings section `[strategy.NAME]`, if it has one registered
    /// here ([`Settings::of`]); the built-in ones' sections are fields of
    /// [`StrategyConfig`](crate::search::StrategyConfig).
    pub settings: Option<Settings>,
}

/// A strategy's own settings, `[strategy.NAME]`: its type says the keys,
/// their defaults ([`Default`]), their documentation (doc comments, through
/// [`JsonSchema`], for the config reference) and their checks
/// ([`StrategySettings::validate`]). Register it with [`Settings::of`] in
/// the strategy's entry; the strategy reads it with
/// [`StrategyConfig::settings`](crate::search::StrategyConfig::settings).
pub trait StrategySettings: Default + Serialize + DeserializeOwned + JsonSchema {
    /// The section's name under `[strategy]` (a TOML key: `one_plus_lambda`).
    const SECTION: &'static str;

    /// Checks the settings for a task whose evaluations carry `metrics`;
    /// the error is `key = value: why`, the key within the section.
    fn validate(&self, _metrics: &[&str]) -> std::result::Result<(), String> {
        Ok(())
    }
}

/// A settings section as an entry registers it: [`Settings::of`] a
/// [`StrategySettings`] type.
#[derive(Clone, Copy)]
pub struct Settings {
    /// The section's name under `[strategy]`.
    pub section: &'static str,
    /// The section as written (keys left out take their defaults) with
    /// every key; the error names the section and says what is wrong.
    pub read: fn(&toml::Table) -> std::result::Result<toml::Table, String>,
    /// Checks the section as written for a task measuring these metrics;
    /// the error names the key (`strategy.NAME.key = value: why`).
    pub validate: fn(&toml::Table, &[&str]) -> std::result::Result<(), String>,
    /// The section's JSON schema (its doc comments, for the config reference).
    pub schema: fn(&mut schemars::SchemaGenerator) -> schemars::Schema,
}

impl Settings {
    /// The registration of settings type `T`.
    pub const fn of<T: StrategySettings>() -> Settings {
        Settings {
            section: T::SECTION,
            read: read_section::<T>,
            validate: validate_section::<T>,
            schema: T::json_schema,
        }
    }
}

/// [`Settings::read`] of `T`.
fn read_section<T: StrategySettings>(
    table: &toml::Table,
) -> std::result::Result<toml::Table, String> {
    let settings = sections::parse_section::<T>(table)?;
    match toml::Value::try_from(settings) {
        Ok(toml::Value::Table(t)) => Ok(t),
        Ok(_) => Err(format!("strategy.{}: not a table", T::SECTION)),
        Err(e) => Err(format!("strategy.{}: {e}", T::SECTION)),
    }
}

/// [`Settings::validate`] of `T`.
fn validate_section<T: StrategySettings>(
    table: &toml::Table,
    metrics: &[&str],
) -> std::result::Result<(), String> {
    (sections::parse_section::<T>(table)?.validate(metrics))
        .map_err(|why| format!("strategy.{}.{why}", T::SECTION))
}

/// What a strategy's generation 0 is built from.
pub struct Start<'a> {
    /// The run's config.
    pub config: &'a Config,
    /// The shape of the genomes.
    pub spec: GenomeSpec,
    /// The behaviour descriptors the task gives.
    pub space: &'a BehaviourSpace,
    /// The genomes to start from, if given (only to an entry that
    /// [`StrategyEntry::takes_population`]).
    pub init: Option<&'a Population>,
    /// Names of the metrics the task's evaluations carry (objectives a
    /// strategy may select on beside fitness).
    pub metrics: &'a [&'a str],
}

/// What a strategy selects on beside fitness: the task measures it only then.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Needs {
    /// A behaviour descriptor (`strategy.behaviour`).
    pub behaviour: bool,
    /// The task's metrics (contacts, on-road share, …).
    pub metrics: bool,
}

/// [`StrategyEntry::from_state`] of a strategy whose checkpointed state is
/// its serde form.
pub fn state_of<T>(state: &str) -> serde_json::Result<Search>
where
    T: DynStrategy + serde::de::DeserializeOwned + 'static,
{
    Ok(Search::of(serde_json::from_str::<T>(state)?))
}

/// How a strategy's part of a run's report is read from the run directory.
pub type ReportOf = fn(&Path, &Config, &BehaviourSpace) -> Result<Option<StrategyReport>>;

impl std::fmt::Debug for StrategyEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StrategyEntry")
            .field("kind", &self.kind)
            .finish()
    }
}

/// The strategies programs added with [`register`].
static REGISTERED: std::sync::RwLock<Vec<&'static StrategyEntry>> =
    std::sync::RwLock::new(Vec::new());

/// Adds a strategy to those a config can name (`strategy.kind = "its kind"`),
/// beside the built-in [`STRATEGIES`]; the error says why not (a name taken).
pub fn register(entry: &'static StrategyEntry) -> std::result::Result<(), String> {
    let mut added = REGISTERED.write().unwrap_or_else(|e| e.into_inner());
    let taken = |e: &&StrategyEntry| e.kind == entry.kind || e.variant == entry.variant;
    if STRATEGIES.iter().chain(added.iter()).any(taken) {
        // Registering the same entry twice is harmless (tests, re-imports).
        if STRATEGIES
            .iter()
            .chain(added.iter())
            .any(|e| std::ptr::eq(*e, entry))
        {
            return Ok(());
        }
        return Err(format!(
            "a strategy called '{}' ({}) is registered already",
            entry.kind, entry.variant
        ));
    }
    let section = entry.settings.map(|s| s.section);
    let holds = |e: &&StrategyEntry| e.settings.is_some_and(|s| Some(s.section) == section);
    if let Some(name) = section
        && (sections::FIELDS.contains(&name) || STRATEGIES.iter().chain(added.iter()).any(holds))
    {
        return Err(format!(
            "a strategy's settings section called '{name}' ([strategy.{name}]) is registered already"
        ));
    }
    added.push(entry);
    Ok(())
}

/// Every strategy a config can name: the built-in ones, then the registered.
pub fn entries() -> Vec<&'static StrategyEntry> {
    let added = REGISTERED.read().unwrap_or_else(|e| e.into_inner());
    STRATEGIES.iter().chain(added.iter()).copied().collect()
}

/// The strategy called `kind`; the error lists the ones there are.
pub fn entry(kind: &str) -> std::result::Result<&'static StrategyEntry, String> {
    let all = entries();
    all.iter().copied().find(|e| e.kind == kind).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|e| e.kind).collect();
        format!("'{kind}': expected {}", names.join(", "))
    })
}

/// The strategy `config` names (checked by [`check`]).
pub fn entry_of(config: &Config) -> Result<&'static StrategyEntry> {
    entry(StrategyConfig::of(config).kind.name())
        .map_err(|why| bad_input(format!("strategy.kind = {why}")))
}

/// Checks `config`'s `[strategy]` section for a task measuring `metrics`:
/// the strategy is registered, what it needs fits the run, its settings are
/// valid; the error names the key.
pub fn check(config: &Config, metrics: &[&str]) -> std::result::Result<(), String> {
    let s = &StrategyConfig::of(config);
    let e = entry(s.kind.name()).map_err(|why| format!("strategy.kind = {why}"))?;
    if config.substrate.es.leo_seed && !e.takes_population {
        return Err(format!(
            "substrate.es.leo_seed = true: {} run starts from minimal genomes (only {} runs start from the seed)",
            crate::error::a(e.kind),
            takers().join(" and ")
        ));
    }
    s.validate(metrics)
}

/// The strategies that can start from given genomes.
pub(crate) fn takers() -> Vec<&'static str> {
    entries()
        .into_iter()
        .filter(|e| e.takes_population)
        .map(|e| e.kind)
        .collect()
}

/// The header line of the strategies that search on a behaviour descriptor.
pub(crate) fn behaviour_line(c: &Config) -> String {
    let s = &StrategyConfig::of(c);
    format!("\n  strategy: {}, behaviour {}", s.kind.name(), s.behaviour)
}

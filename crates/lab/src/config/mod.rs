//! The experiment configuration: one TOML file holding every parameter.
//!
//! Sections map one-to-one onto the library parameter structs, so a key is
//! exactly the field the library reads, and the field's doc comment is the
//! key's documentation: [`reference()`] reads them (through the structs'
//! `schemars::JsonSchema` derive) for `vivae config default`, `vivae config
//! reference` and the guide's table, so there is no second copy to drift. A
//! test fails when a key lacks a doc comment or the guide's table is stale.

mod form;
pub mod owned;
mod reference;
mod shared;
mod toml_error;
mod validate;

pub mod es;
pub mod strategy;

pub use owned::{OwnedSection, OwnedSections, Section};
pub use reference::{KeyDoc, SectionDoc, key_doc, reference};
pub use shared::SharedSection;
use toml_error::{describe_toml_error, line_of_key, over_defaults};

use std::fmt::Write as _;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::hyperneat::HyperParams;
use vivae_neat::{NeatParams, Precision};
use vivae_sim::{DistanceSensors, PhysicsParams, SurfaceSensors};

use crate::config::es::{EsConfig, SubstrateKind};
use crate::polar::{CoordMode, PolarGrid};

/// Most simulation steps per evaluation (`experiment.steps`, `replay --steps`).
pub const MAX_STEPS: u32 = 1_000_000;
/// Most output neurons (`substrate.neurons` rings × angles).
pub const MAX_NEURONS: usize = 4_096;
/// Most surface sensors (`surface_sensors` rings × angles).
pub const MAX_SENSORS: usize = 65_536;
/// Most distance-sensor rays.
pub const MAX_RAYS: usize = 1_024;
/// Largest substrate weight matrix (possible links × 8 bytes) one thread may hold.
pub const MAX_SUBSTRATE_BYTES: u64 = 256 << 20;

/// Every parameter of a run (its serde form by hand, in `form.rs`).
#[derive(Debug, Clone, PartialEq, Default, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    /// What is run: scenario, seed, generations, steps, robots.
    pub experiment: ExperimentConfig,
    /// The output neuron sheet and the coordinate mode.
    pub substrate: SubstrateConfig,
    /// CPPN → substrate expression.
    pub hyperneat: HyperParams,
    /// The surface sensors (the input sheet).
    pub surface_sensors: SurfaceSensors,
    /// Optional distance sensors (a second input sheet).
    pub distance_sensors: DistanceConfig,
    /// Opponent radar: pie slices pointing at the nearest robot of another
    /// team (`data-team` in the scenario); off unless `slices > 0`.
    #[serde(default, skip_serializing_if = "OpponentConfig::is_off_by_default")]
    pub opponent_sensors: OpponentConfig,
    /// Physics constants of the simulator.
    pub physics: PhysicsParams,
    /// NEAT hyper-parameters for the CPPNs.
    pub neat: NeatParams,
    /// Threads and checkpoints: how a run is executed, not what it computes.
    pub run: RunConfig,
    /// The sections the search strategies (`[strategy]`) and the tasks
    /// own, each registered with its entry, by name; written after the
    /// shared ones (`[strategy]` after `[run]`).
    #[schemars(skip)]
    pub owned: OwnedSections,
}

/// What is run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ExperimentConfig {
    /// Scenario SVG file; empty = the embedded default (a relative path is
    /// relative to the config file's folder).
    ///
    /// Unit: path. Paper: the road scenario of Fig. 1.
    pub scenario: String,
    /// Training on several maps: scenario SVG files or shipped names; every
    /// genome is evaluated on each (with that map's own robots) and its fitness
    /// is the mean over maps. Unset = `scenario` only; setting both is refused.
    ///
    /// Example: ["roads", "oval", "figure8"].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub scenarios: Vec<String>,
    /// Seed of the run's random number generator.
    pub seed: u64,
    /// Generations to evolve.
    ///
    /// Paper: 400.
    pub generations: u32,
    /// Simulation steps per evaluation.
    ///
    /// Unit: steps. Paper: 1000.
    pub steps: u32,
    /// Robots driven by copies of the controller: the scenario's first N; 0 = all of them.
    ///
    /// Paper: 5.
    pub robots: usize,
    /// Checkpoint whose population the run starts from (set by `vivae retrain`);
    /// empty = a fresh population.
    ///
    /// Unit: path.
    pub init_population: String,
    /// What genomes are evaluated on: a registered task (docs/howto/ has a page
    /// per task); unset = driving (HyperNEAT substrates driving on roads, the paper's).
    ///
    /// Example: "driving".
    #[serde(default, skip_serializing_if = "TaskName::is_driving")]
    pub task: TaskName,
    /// Placements per evaluation on a scenario that places obstacles or
    /// traffic per evaluation (`obstacles-random`, `oncoming`): every genome
    /// is evaluated on this many placements, the evaluation's seed s and
    /// splitmix64(s ^ k) for k = 1 … N−1, its fitness combined by
    /// `placements_aggregate` and its metrics and behaviour the mean over
    /// them. 1 = one placement (the seed s); more than 1 is refused when no
    /// training map places anything per evaluation.
    ///
    /// Example: 4.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub placements: u32,
    /// How the fitnesses on `placements` placements combine: `mean` (unset) or `min`.
    ///
    /// Example: "min".
    #[serde(default, skip_serializing_if = "Aggregate::is_mean")]
    pub placements_aggregate: Aggregate,
    /// Arithmetic of the controller step: `exact` (unset; f64, the bits of
    /// every recorded run) or `fast` (f32 weights, states and a polynomial
    /// sigmoid within 2e-7 of the exact one: other bits, again the same on
    /// every CPU, SIMD level and thread count). A checkpoint keeps it;
    /// resuming in the other precision is refused. Only the dense polar
    /// substrate of the driving task has a fast step: elsewhere `fast` is refused.
    ///
    /// Example: "fast".
    #[serde(default, skip_serializing_if = "Precision::is_exact")]
    pub precision: Precision,
}

fn one() -> u32 {
    1
}

fn is_one(n: &u32) -> bool {
    *n == 1
}

/// The name of the task a run evolves controllers for (`experiment.task`):
/// one of the tasks registered in [`crate::tasks`], which checks it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct TaskName(pub String);

impl TaskName {
    /// The default task's name: robots driving on roads, the paper's.
    pub const DRIVING: &'static str = "driving";

    /// Whether this is the default task, [`TaskName::DRIVING`].
    pub fn is_driving(&self) -> bool {
        self.0 == Self::DRIVING
    }

    /// The name as configs and the command line write it.
    pub fn name(&self) -> &str {
        &self.0
    }
}

impl Default for TaskName {
    fn default() -> Self {
        TaskName(Self::DRIVING.into())
    }
}

impl std::fmt::Display for TaskName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::str::FromStr for TaskName {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Ok(TaskName(s.to_string()))
    }
}

impl Default for ExperimentConfig {
    fn default() -> Self {
        ExperimentConfig {
            scenario: String::new(),
            scenarios: Vec::new(),
            seed: 1,
            generations: 400,
            steps: 1000,
            robots: 5,
            init_population: String::new(),
            task: TaskName::default(),
            placements: 1,
            placements_aggregate: Aggregate::Mean,
            precision: Precision::Exact,
        }
    }
}

/// The neuron sheet of the substrate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SubstrateConfig {
    /// Output neuron sheet as RINGSxANGLES; the wheel neurons L and R sit at the
    /// outer angles of the ring nearest radius 2/3 (the middle ring of 3).
    ///
    /// Paper: 3x3, re-sampled to 9x9.
    #[schemars(with = "String")]
    pub neurons: PolarGrid,
    /// CPPN coordinates of a node at ring radius r and angle a:
    /// `cartesian` = (r sin a, r cos a), `polar` = (r, a/pi).
    ///
    /// Paper: cartesian.
    pub coordinates: CoordMode,
    /// Scale each sheet's outgoing weights by (its node count in the paper: 15
    /// sensors, 9 neurons, 5 rays) / (its node count here), so a re-sampled
    /// substrate drives its neurons as strongly; exactly 1 at the paper's resolution.
    pub normalize: bool,
    /// With `normalize`: `count` (the paper's: every node of a sheet weighs
    /// reference/count) or `area` (each node weighs reference × its share of
    /// the sheet's polar area, ∝ its ring radius; see docs/explanation/normalisation.md). Unset = count.
    ///
    /// Example: "area".
    #[serde(default, skip_serializing_if = "NormalizeBy::is_count")]
    pub normalize_by: NormalizeBy,
    /// With `normalize`: whether self-loops are scaled with the neuron sheet
    /// (the paper's setting); `false` keeps each neuron's self-loop at the
    /// CPPN's weight at any resolution. Unset = true.
    ///
    /// Example: false.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub normalize_self_loops: bool,
    /// Which neuron→neuron links the substrate keeps: `full` (every pair, the
    /// paper's fully recurrent sheet), `self` (each neuron's self-loop only:
    /// no lateral links) or `none` (a reactive sheet). Unset = full.
    ///
    /// Example: "self".
    #[serde(default, skip_serializing_if = "Recurrence::is_full")]
    pub recurrence: Recurrence,
    /// Neuron sheets (RINGSxANGLES) every genome is
    /// evaluated at during evolution, its fitness aggregating them
    /// (multi-resolution evolution); unset = `neurons` only. `neurons` stays
    /// the resolution reported and drawn.
    ///
    /// Example: ["3x3", "5x5", "9x9"].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    #[schemars(with = "Vec<String>")]
    pub train_neurons: Vec<PolarGrid>,
    /// Surface-sensor sheets (RINGSxANGLES) every genome is evaluated at during
    /// evolution, each with every one of `train_neurons`; unset = the
    /// `surface_sensors` sheet only.
    ///
    /// Example: ["3x5", "3x6"].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    #[schemars(with = "Vec<String>")]
    pub train_sensors: Vec<PolarGrid>,
    /// How the fitnesses at the training resolutions combine: `mean` (unset) or `min`.
    ///
    /// Example: "min".
    #[serde(default, skip_serializing_if = "Aggregate::is_mean")]
    pub train_aggregate: Aggregate,
    /// Which substrate the CPPN is decoded into: `polar` (the dense neuron
    /// sheet, the paper's) or `es-hyperneat` (hidden neurons placed by the
    /// CPPN between the sensors and the two wheel neurons; keys in
    /// `[substrate.es]`; docs/howto/substrates.md).
    ///
    /// Example: "es-hyperneat".
    #[serde(default, skip_serializing_if = "SubstrateKind::is_polar")]
    pub kind: SubstrateKind,
    /// ES-HyperNEAT parameters, used with `kind = "es-hyperneat"`.
    #[serde(default, skip_serializing_if = "EsConfig::is_default")]
    pub es: EsConfig,
}

/// Which share of a re-sampled sheet's drive each of its nodes carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum NormalizeBy {
    /// Every node the same: reference / count (the paper's).
    #[default]
    Count,
    /// Each node by its share of the sheet's polar area.
    Area,
}

impl NormalizeBy {
    /// Whether this is the default, [`NormalizeBy::Count`].
    pub fn is_count(&self) -> bool {
        *self == NormalizeBy::Count
    }
}

impl std::str::FromStr for NormalizeBy {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "count" => Ok(NormalizeBy::Count),
            "area" => Ok(NormalizeBy::Area),
            other => Err(format!("'{other}': expected count or area")),
        }
    }
}

/// Which neuron→neuron links of the fully recurrent neuron sheet a controller keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Recurrence {
    /// Every neuron listens to every neuron, itself included (the paper's).
    #[default]
    Full,
    /// Each neuron listens only to itself: no lateral links.
    #[serde(rename = "self")]
    SelfLoops,
    /// No neuron→neuron links at all.
    None,
}

impl Recurrence {
    /// Whether this is the default, [`Recurrence::Full`].
    pub fn is_full(&self) -> bool {
        *self == Recurrence::Full
    }
}

impl std::str::FromStr for Recurrence {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "full" => Ok(Recurrence::Full),
            "self" => Ok(Recurrence::SelfLoops),
            "none" => Ok(Recurrence::None),
            other => Err(format!("'{other}': expected full, self or none")),
        }
    }
}

fn yes() -> bool {
    true
}

fn is_true(b: &bool) -> bool {
    *b
}

/// How a genome's fitnesses at several training resolutions (or on several
/// placements) combine into one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Aggregate {
    /// The arithmetic mean (in the listed order).
    #[default]
    Mean,
    /// The worst of them.
    Min,
}

impl Aggregate {
    /// Whether this is the default, [`Aggregate::Mean`].
    pub fn is_mean(&self) -> bool {
        *self == Aggregate::Mean
    }

    /// Combines `values` (at least one).
    pub fn combine(&self, values: &[f64]) -> f64 {
        match self {
            Aggregate::Mean => values.iter().sum::<f64>() / values.len() as f64,
            Aggregate::Min => values.iter().copied().fold(f64::INFINITY, f64::min),
        }
    }
}

impl std::str::FromStr for Aggregate {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "mean" => Ok(Aggregate::Mean),
            "min" => Ok(Aggregate::Min),
            other => Err(format!("'{other}': expected mean or min")),
        }
    }
}

/// Most resolutions one genome may be evaluated at (neurons × sensors).
pub const MAX_TRAINING_RESOLUTIONS: usize = 16;
/// Most training maps (`experiment.scenarios`).
pub const MAX_MAPS: usize = 64;
/// Most placements per evaluation (`experiment.placements`).
pub const MAX_PLACEMENTS: u32 = 64;

impl Default for SubstrateConfig {
    fn default() -> Self {
        SubstrateConfig {
            neurons: PolarGrid {
                rings: 3,
                angles: 3,
            },
            coordinates: CoordMode::default(),
            normalize: true,
            normalize_by: NormalizeBy::Count,
            recurrence: Recurrence::Full,
            normalize_self_loops: true,
            train_neurons: Vec::new(),
            train_sensors: Vec::new(),
            train_aggregate: Aggregate::Mean,
            kind: SubstrateKind::Polar,
            es: EsConfig::default(),
        }
    }
}

/// Distance sensors: off unless `rays > 0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DistanceConfig {
    /// Distance-sensor rays, a second input sheet; 0 switches the distance sensors off.
    ///
    /// Paper: none (future work).
    pub rays: usize,
    /// Field of view of the distance sensors, centred ahead.
    ///
    /// Unit: degrees.
    pub fov: f64,
    /// Ray length from the robot's rim; a ray reads 1 - d/range for the
    /// nearest obstacle at distance d, 0 when none is in range.
    ///
    /// Unit: px.
    pub range: f64,
}

impl Default for DistanceConfig {
    fn default() -> Self {
        let d = DistanceSensors::default();
        DistanceConfig {
            rays: 0,
            fov: d.fov,
            range: d.range,
        }
    }
}

impl DistanceConfig {
    /// The simulator layout, or `None` when switched off.
    pub fn layout(&self) -> Option<DistanceSensors> {
        (self.rays > 0).then_some(DistanceSensors {
            rays: self.rays,
            fov: self.fov,
            range: self.range,
        })
    }
}

/// The opponent radar (`vivae_sim::OpponentRadar`): off unless `slices > 0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct OpponentConfig {
    /// Pie slices of the full circle around the robot, left to right, the
    /// last centred behind; the slice holding the nearest robot of another
    /// team reads 1 - d/range, the others 0. An input sheet of its own (CPPN
    /// output 4); 0 switches the sensor off.
    pub slices: usize,
    /// How far the radar sees (centre to centre); beyond it the slice reads 0.
    ///
    /// Unit: px.
    pub range: f64,
}

impl Default for OpponentConfig {
    fn default() -> Self {
        OpponentConfig {
            slices: 0,
            range: 300.0,
        }
    }
}

impl OpponentConfig {
    /// Whether this is the default (off): a config written without the section.
    pub fn is_off_by_default(&self) -> bool {
        *self == OpponentConfig::default()
    }

    /// The simulator's radar, or `None` when switched off (or invalid: [`Config::validate`] refuses that).
    pub fn radar(&self) -> Option<vivae_sim::OpponentRadar> {
        (self.slices > 0)
            .then(|| vivae_sim::OpponentRadar::new(self.slices, self.range).ok())
            .flatten()
    }
}

/// How a run is executed.
/// Most evaluation threads a run may ask for (`run.threads`).
pub const MAX_THREADS: usize = 1024;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RunConfig {
    /// Evaluation threads; 0 = one per core (results do not depend on it).
    pub threads: usize,
    /// Write a checkpoint every this many generations (and always after the last).
    ///
    /// Unit: generations.
    pub checkpoint_interval: u32,
    /// Checkpoints kept on disk; older ones are pruned.
    pub checkpoint_keep: usize,
}

impl Default for RunConfig {
    fn default() -> Self {
        RunConfig {
            threads: 0,
            checkpoint_interval: 1,
            checkpoint_keep: 3,
        }
    }
}

/// A configuration problem: the key and what is wrong with it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct ConfigError {
    /// One-line description naming the key (and line, when parsed from text).
    pub message: String,
}

impl ConfigError {
    /// The error `e`, reported at the line of `text` that sets the key it
    /// names, as parse errors are.
    pub fn at_line_of_key(self, text: &str) -> ConfigError {
        let key = self.message.split(" = ").next().unwrap_or_default();
        match line_of_key(text, key) {
            Some(line) => ConfigError::new(format!("line {line}: {}", self.message)),
            None => self,
        }
    }

    /// An error saying `message`.
    pub fn new(message: impl Into<String>) -> Self {
        ConfigError {
            message: message.into(),
        }
    }
}

impl Config {
    /// Parses TOML text; errors are one line naming the line, key and reason.
    ///
    /// Unset keys take the driving task's defaults and only the rules every
    /// task shares are checked: [`crate::tasks::config_from_toml`] reads a
    /// config with its task's defaults and rules.
    pub fn from_toml(text: &str) -> Result<Config, ConfigError> {
        Config::from_toml_over(text, None)
    }

    /// [`Config::from_toml`] with the keys `text` leaves unset taken from
    /// `base` (a task's defaults) instead of [`Config::default`].
    pub fn from_toml_over(text: &str, base: Option<&Config>) -> Result<Config, ConfigError> {
        Config::parse(text, base, None)
    }

    /// [`Config::from_toml_over`] with the sections tasks own read by their
    /// registrations `sections` (each with every key, or left out at its
    /// defaults) and any other table refused.
    pub fn from_toml_with(
        text: &str,
        base: Option<&Config>,
        sections: &[Section],
    ) -> Result<Config, ConfigError> {
        Config::parse(text, base, Some(sections))
    }

    fn parse(
        text: &str,
        base: Option<&Config>,
        sections: Option<&[Section]>,
    ) -> Result<Config, ConfigError> {
        // The strict parses (the shared sections, then each registered
        // one) say where the text is wrong; the overlay gives unset keys the
        // defaults of the config, which for a sub-table of an owned section
        // (`[strategy.novelty]`, the library's params type) are its section's.
        toml::from_str::<Config>(text).map_err(|e| describe_toml_error(text, &e))?;
        for s in sections.unwrap_or_default() {
            (s.check_text)(text)?;
        }
        let mut config = over_defaults(text, base.unwrap_or(&Config::default()))?;
        if let Some(sections) = sections {
            owned::settle(&mut config.owned, sections)
                .map_err(|e| owned::at_line_of_table(ConfigError::new(e), text))?;
        }
        config.validate().map_err(|e| e.at_line_of_key(text))?;
        Ok(config)
    }

    /// The config as TOML (every key, no comments).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("config serialises to TOML")
    }

    /// Why a task named beside this config file does not fit it (`None` when
    /// it does): the file's `experiment.task` decides.
    pub fn task_mismatch(&self, task: Option<&TaskName>) -> Option<String> {
        let t = task.filter(|t| **t != self.experiment.task)?;
        Some(format!(
            "the config file's experiment.task is {}: set `task = \"{}\"` under [experiment] in the file instead",
            self.experiment.task.name(),
            t.name()
        ))
    }

    /// The configs of the resolutions every genome is evaluated at during
    /// evolution (`substrate.train_neurons` × `train_sensors`, neurons first);
    /// empty when training uses this config's own resolution only. Each has
    /// empty training lists.
    pub fn training_configs(&self) -> Vec<Config> {
        let sub = &self.substrate;
        if sub.train_neurons.is_empty() && sub.train_sensors.is_empty() {
            return Vec::new();
        }
        let own_sensors = PolarGrid {
            rings: self.surface_sensors.rings,
            angles: self.surface_sensors.angles,
        };
        let neurons = if sub.train_neurons.is_empty() {
            vec![sub.neurons]
        } else {
            sub.train_neurons.clone()
        };
        let sensors = if sub.train_sensors.is_empty() {
            vec![own_sensors]
        } else {
            sub.train_sensors.clone()
        };
        let mut out = Vec::with_capacity(neurons.len() * sensors.len());
        for n in &neurons {
            for s in &sensors {
                let mut c = self.clone();
                c.substrate.neurons = *n;
                c.surface_sensors.rings = s.rings;
                c.surface_sensors.angles = s.angles;
                c.substrate.train_neurons.clear();
                c.substrate.train_sensors.clear();
                out.push(c);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    /// The paths of every table in `value` (`["strategy", "novelty"]`, …).
    fn table_paths(value: &toml::Value, path: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
        if let toml::Value::Table(t) = value {
            if !path.is_empty() {
                out.push(path.clone());
            }
            for (k, v) in t {
                path.push(k.clone());
                table_paths(v, path, out);
                path.pop();
            }
        }
    }

    #[test]
    fn an_empty_or_partial_section_takes_the_configs_defaults() {
        let default = super::Config::default();
        let mut paths = Vec::new();
        table_paths(
            &toml::Value::try_from(&default).unwrap(),
            &mut Vec::new(),
            &mut paths,
        );
        assert!(paths.len() > 8, "{paths:?}");
        for path in paths {
            let text = format!("[{}]\n", path.join("."));
            assert_eq!(super::Config::from_toml(&text).unwrap(), default, "{text}");
            // Every section but the library's novelty params has the
            // config's defaults as its own serde defaults too.
            if path != ["strategy", "novelty"] {
                assert_eq!(
                    toml::from_str::<super::Config>(&text).unwrap(),
                    default,
                    "{text}"
                );
            }
        }
        let c = super::Config::from_toml("[strategy.novelty]\nk = 9\n").unwrap();
        let n = &crate::search::StrategyConfig::of(&c).novelty;
        assert_eq!((n.k, n.threshold, n.threshold_floor), (9, 0.05, 0.005));
    }

    use super::reference::{ParsedDoc, documented_defaults, sentence_fragment};
    use super::*;

    #[test]
    fn default_validates_and_roundtrips() {
        let c = Config::default();
        c.validate().unwrap();
        let back = Config::from_toml(&c.to_toml()).unwrap();
        assert_eq!(back, c);
    }

    #[test]
    fn commented_default_parses_back_to_default() {
        let sections = crate::tasks::sections();
        let text = Config::default_commented(&sections);
        let back = Config::from_toml_with(&text, None, &sections).unwrap();
        assert_eq!(back, Config::default());
    }

    /// Every leaf key of a TOML value as (dotted key, value as TOML text).
    fn flatten(value: &toml::Value) -> Vec<(String, String)> {
        fn walk(prefix: &str, value: &toml::Value, out: &mut Vec<(String, String)>) {
            match value {
                toml::Value::Table(t) => {
                    for (k, v) in t {
                        let key = if prefix.is_empty() {
                            k.clone()
                        } else {
                            format!("{prefix}.{k}")
                        };
                        walk(&key, v, out);
                    }
                }
                other => out.push((prefix.to_string(), other.to_string())),
            }
        }
        let mut out = Vec::new();
        walk("", value, &mut out);
        out
    }

    #[test]
    fn every_key_and_section_is_documented_and_every_doc_is_a_key() {
        let owned = crate::tasks::sections();
        let defaults = flatten(&documented_defaults(&owned));
        let sections = reference(&owned);
        let docs: Vec<&KeyDoc> = sections.iter().flat_map(|s| &s.keys).collect();
        for s in &sections {
            assert!(
                !s.what.is_empty(),
                "section [{}] has no doc comment",
                s.path
            );
        }
        for (key, default) in &defaults {
            let doc = docs
                .iter()
                .find(|d| &d.key == key)
                .unwrap_or_else(|| panic!("{key} is missing from the reference"));
            assert!(!doc.what.is_empty(), "{key} has no doc comment");
            assert_eq!(doc.default.as_ref(), Some(default), "{key}");
        }
        for d in &docs {
            assert_eq!(
                docs.iter().filter(|o| o.key == d.key).count(),
                1,
                "{}",
                d.key
            );
            if d.default.is_none() {
                assert!(!d.what.is_empty(), "{} has no doc comment", d.key);
                let (section, key) = d.key.rsplit_once('.').unwrap();
                let text = format!("[{section}]\n{key} = {}\n", d.example);
                Config::from_toml_with(&text, None, &owned).unwrap_or_else(|e| {
                    panic!("unset key {}: its Example: note is rejected: {e}", d.key)
                });
            } else {
                assert!(defaults.iter().any(|(k, _)| k == &d.key), "{}", d.key);
            }
        }
    }

    #[test]
    fn doc_comments_are_the_reference() {
        let doc = key_doc("neat.population_size", &[]).unwrap();
        assert_eq!(doc.what, "genomes per generation");
        assert_eq!(doc.paper, "100");
        assert_eq!(doc.default.as_deref(), Some("100"));
        let doc = key_doc("physics.v_max", &[]).unwrap();
        assert_eq!(
            (doc.what.as_str(), doc.unit.as_str()),
            ("top forward speed", "px/step")
        );
        assert_eq!(doc.comment(), "top forward speed [px/step]; default: 5.0");
        let doc = key_doc("neat.target_species", &[]).unwrap();
        assert_eq!((doc.default.as_deref(), doc.example.as_str()), (None, "10"));
        assert!(key_doc("neat.no_such_key", &[]).is_none());
    }

    #[test]
    fn notes_are_split_from_the_meaning() {
        let d = ParsedDoc::new(
            "CPPN link weights are clamped.\n\nMore text here.\n\nUnit: px/step. Paper: 0.75 (Stanley).\nExample: 10.",
        );
        assert_eq!(d.what, "CPPN link weights are clamped. More text here.");
        assert_eq!(
            (d.unit.as_str(), d.paper.as_str(), d.example.as_str()),
            ("px/step", "0.75 (Stanley)", "10")
        );
        assert_eq!(ParsedDoc::new("Paper: 3.5.").paper, "3.5");
        assert_eq!(sentence_fragment("C1: coefficient."), "C1: coefficient");
        assert_eq!(sentence_fragment("Robot disc radius."), "robot disc radius");
        assert_eq!(sentence_fragment("A gene stays."), "a gene stays");
        assert_eq!(
            sentence_fragment("C_ACT: coefficient"),
            "C_ACT: coefficient"
        );
        assert_eq!(sentence_fragment("CPPN weights."), "CPPN weights");
        assert_eq!(sentence_fragment(""), "");
    }

    #[test]
    fn markdown_reference_escapes_table_pipes() {
        let table = Config::markdown_reference(&crate::tasks::sections());
        let columns = |line: &str| line.replace("\\|", "").matches('|').count();
        for line in table.lines() {
            assert_eq!(columns(line), 6, "{line}");
        }
        assert!(table.contains("`neat.target_species` | unset |"), "{table}");
    }

    #[test]
    fn commented_default_shows_unset_keys_and_section_docs() {
        let text = Config::default_commented(&crate::tasks::sections());
        assert!(text.contains("\n# target_species = 10\n"), "{text}");
        assert!(text.contains("[physics.friction]\n"), "{text}");
        let before_neat = text.split("\n[neat]\n").next().unwrap();
        assert!(
            before_neat.ends_with("\n# NEAT hyper-parameters for the CPPNs."),
            "{before_neat}"
        );
    }

    #[test]
    fn unknown_key_is_named_with_its_line() {
        let err = Config::from_toml("[neat]\npopulation_size = 10\npopsize = 3\n").unwrap_err();
        assert!(err.message.contains("line 3"), "{}", err.message);
        assert!(err.message.contains("neat.popsize"), "{}", err.message);
        assert!(!err.message.contains('\n'));
    }

    #[test]
    fn invalid_values_read_cleanly_with_their_line() {
        let err = Config::from_toml("[experiment]\nseed = 3\n\n[hyperneat]\nthreshold = 1.5\n")
            .unwrap_err();
        assert!(
            err.message
                .starts_with("line 5: hyperneat.threshold = 1.5: must satisfy"),
            "{}",
            err.message
        );
        let err = Config::from_toml("[neat]\n population_size = 1\n").unwrap_err();
        assert_eq!(
            err.message,
            "line 2: neat.population_size = 1: must be at least 2 (NEAT breeds from pairs)"
        );
    }

    #[test]
    fn wrong_type_is_named() {
        let err = Config::from_toml("[experiment]\nsteps = \"many\"\n").unwrap_err();
        assert!(err.message.contains("experiment.steps"), "{}", err.message);
    }

    #[test]
    fn negative_population_is_rejected() {
        let err = Config::from_toml("[neat]\npopulation_size = -5\n").unwrap_err();
        assert!(
            err.message.contains("neat.population_size"),
            "{}",
            err.message
        );
    }

    #[test]
    fn invalid_values_name_the_key() {
        let err = Config::from_toml("[neat]\npopulation_size = 0\n").unwrap_err();
        assert!(err.message.contains("population_size"), "{}", err.message);
        let err = Config::from_toml("[neat]\nadd_node_probability = 1.5\n").unwrap_err();
        assert!(
            err.message.contains("add_node_probability"),
            "{}",
            err.message
        );
        let err = Config::from_toml("[physics]\nv_max = -1.0\n").unwrap_err();
        assert!(err.message.contains("physics.v_max"), "{}", err.message);
        let err = Config::from_toml("[run]\ncheckpoint_keep = 0\n").unwrap_err();
        assert!(
            err.message.contains("run.checkpoint_keep"),
            "{}",
            err.message
        );
    }
}

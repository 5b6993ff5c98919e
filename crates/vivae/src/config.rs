//! The experiment configuration: one TOML file holding every parameter.
//!
//! Sections map one-to-one onto the library parameter structs, so a key
//! documented here is exactly the field the library reads. Every key has an
//! entry in [`KEY_DOCS`]; a test walks the serialised default and fails when a
//! key lacks documentation, so `vivae config default` and the guide's table
//! cannot drift from the code.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};
use vivae_neat::NeatParams;
use vivae_neat::hyperneat::HyperParams;
use vivae_sim::{DistanceSensors, PhysicsParams, SurfaceSensors};

use crate::substrate::{CoordMode, PolarGrid};

/// Every parameter of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
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
    /// Physics constants of the simulator.
    pub physics: PhysicsParams,
    /// NEAT hyper-parameters for the CPPNs.
    pub neat: NeatParams,
    /// Threads and checkpoints: how a run is executed, not what it computes.
    pub run: RunConfig,
}

/// What is run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExperimentConfig {
    /// Scenario SVG file; empty = the embedded default. Relative paths are
    /// resolved against the directory of the config file.
    pub scenario: String,
    /// Seed of the run's random number generator.
    pub seed: u64,
    /// Generations to evolve.
    pub generations: u32,
    /// Simulation steps per evaluation.
    pub steps: u32,
    /// Robots driven by copies of the controller; 0 = every robot of the scenario.
    pub robots: usize,
    /// Checkpoint whose population the run starts from instead of a fresh one
    /// (set by `vivae retrain`); empty = a fresh population.
    pub init_population: String,
}

impl Default for ExperimentConfig {
    fn default() -> Self {
        ExperimentConfig {
            scenario: String::new(),
            seed: 1,
            generations: 400,
            steps: 1000,
            robots: 5,
            init_population: String::new(),
        }
    }
}

/// The neuron sheet of the substrate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SubstrateConfig {
    /// Output neuron sheet, rings × angles.
    pub neurons: PolarGrid,
    /// CPPN coordinates of substrate nodes.
    pub coordinates: CoordMode,
    /// Scale each sheet's outgoing weights by (nodes of the paper's sheet) /
    /// (nodes of this sheet), so a re-sampled sheet drives the neurons as strongly.
    pub normalize: bool,
}

impl Default for SubstrateConfig {
    fn default() -> Self {
        SubstrateConfig {
            neurons: PolarGrid {
                rings: 3,
                angles: 3,
            },
            coordinates: CoordMode::default(),
            normalize: true,
        }
    }
}

/// Distance sensors: off unless `rays > 0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DistanceConfig {
    /// Number of rays; 0 switches the distance sensors off.
    pub rays: usize,
    /// Field of view in degrees.
    pub fov: f64,
    /// Ray length from the robot's rim, px.
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

/// How a run is executed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunConfig {
    /// Worker threads for evaluation; 0 = one per core. Results do not depend on it.
    pub threads: usize,
    /// Write a checkpoint every this many generations (the last generation always gets one).
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
    fn new(message: impl Into<String>) -> Self {
        ConfigError {
            message: message.into(),
        }
    }
}

impl Config {
    /// Parses TOML text; errors are one line naming the line, key and reason.
    pub fn from_toml(text: &str) -> Result<Config, ConfigError> {
        let config: Config = toml::from_str(text).map_err(|e| describe_toml_error(text, &e))?;
        config.validate()?;
        Ok(config)
    }

    /// The config as TOML (every key, no comments).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("config serialises to TOML")
    }

    /// Checks every value; the error names the key and the reason.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let e = &self.experiment;
        if e.generations == 0 {
            return Err(ConfigError::new(
                "experiment.generations = 0: must be at least 1",
            ));
        }
        if e.steps == 0 {
            return Err(ConfigError::new("experiment.steps = 0: must be at least 1"));
        }
        self.neat
            .validate()
            .map_err(|err| ConfigError::new(format!("neat.{err}")))?;
        self.hyperneat
            .validate()
            .map_err(|err| ConfigError::new(format!("hyperneat.{err}")))?;
        self.physics
            .validate()
            .map_err(|err| ConfigError::new(format!("physics.{}", param_message(&err))))?;
        self.surface_sensors
            .validate()
            .map_err(|err| ConfigError::new(format!("surface_sensors.{}", param_message(&err))))?;
        if let Some(d) = self.distance_sensors.layout() {
            d.validate().map_err(|err| {
                ConfigError::new(format!("distance_sensors.{}", param_message(&err)))
            })?;
        }
        let r = &self.run;
        if r.checkpoint_interval == 0 {
            return Err(ConfigError::new(
                "run.checkpoint_interval = 0: must be at least 1",
            ));
        }
        if r.checkpoint_keep == 0 {
            return Err(ConfigError::new(
                "run.checkpoint_keep = 0: must be at least 1",
            ));
        }
        if r.threads > 1024 {
            return Err(ConfigError::new(format!(
                "run.threads = {}: must be at most 1024",
                r.threads
            )));
        }
        Ok(())
    }

    /// The default config as TOML with a comment on every key.
    pub fn default_commented() -> String {
        let value = toml::Value::try_from(Config::default()).expect("default config is TOML");
        let mut out = String::from(
            "# vivae configuration: every parameter of a run.\n\
             # Keys left out take their defaults; command-line flags override the file.\n\
             # Each comment gives: what the key is [unit]; its default; the paper's value where it has one.\n",
        );
        let table = value.as_table().expect("config is a table");
        for (section, sub) in table {
            let sub = sub.as_table().expect("every section is a table");
            write_section(&mut out, section, sub);
        }
        out
    }

    /// A Markdown table of every key: name, default, unit, paper's value, meaning.
    pub fn markdown_reference() -> String {
        let value = toml::Value::try_from(Config::default()).expect("default config is TOML");
        let mut out = String::from(
            "| key | default | unit | paper | meaning |\n| --- | --- | --- | --- | --- |\n",
        );
        for (key, default) in flatten(&value) {
            let doc = key_doc(&key).unwrap_or(&MISSING);
            let _ = writeln!(
                out,
                "| `{key}` | `{default}` | {} | {} | {} |",
                doc.unit, doc.paper, doc.what
            );
        }
        for doc in KEY_DOCS.iter().filter(|d| d.optional) {
            let _ = writeln!(
                out,
                "| `{}` | unset | {} | {} | {} |",
                doc.key, doc.unit, doc.paper, doc.what
            );
        }
        out
    }
}

fn param_message(err: &vivae_sim::ParamError) -> String {
    format!("{} = {}: {}", err.field, err.value, err.reason)
}

fn write_section(out: &mut String, path: &str, table: &toml::map::Map<String, toml::Value>) {
    let _ = writeln!(out, "\n[{path}]");
    let mut subtables = Vec::new();
    for (key, value) in table {
        if let toml::Value::Table(t) = value {
            subtables.push((format!("{path}.{key}"), t));
            continue;
        }
        let full = format!("{path}.{key}");
        write_doc(out, &full, Some(&value.to_string()));
        let _ = writeln!(out, "{key} = {value}");
    }
    // Optional keys have no value by default: show them commented out.
    for doc in KEY_DOCS.iter().filter(|d| d.optional) {
        if let Some((section, key)) = doc.key.rsplit_once('.')
            && section == path
        {
            write_doc(out, doc.key, None);
            let _ = writeln!(out, "# {key} = {}", doc.example);
        }
    }
    for (sub_path, sub) in subtables {
        write_section(out, &sub_path, sub);
    }
}

fn write_doc(out: &mut String, key: &str, default: Option<&str>) {
    let doc = key_doc(key).unwrap_or(&MISSING);
    let mut parts = vec![if doc.unit.is_empty() {
        doc.what.to_string()
    } else {
        format!("{} [{}]", doc.what, doc.unit)
    }];
    parts.push(format!("default: {}", default.unwrap_or("unset")));
    if !doc.paper.is_empty() {
        parts.push(format!("paper: {}", doc.paper));
    }
    let _ = writeln!(out, "# {}", parts.join("; "));
}

/// Every leaf key of a TOML value as (dotted key, value as TOML text).
pub fn flatten(value: &toml::Value) -> Vec<(String, String)> {
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

/// Documentation of one config key.
#[derive(Debug, Clone, Copy)]
pub struct KeyDoc {
    /// Dotted key, e.g. `neat.population_size`.
    pub key: &'static str,
    /// What the key is.
    pub what: &'static str,
    /// Unit, empty when dimensionless.
    pub unit: &'static str,
    /// The paper's value, empty when the paper does not give one.
    pub paper: &'static str,
    /// Whether the key is unset by default (an `Option`).
    pub optional: bool,
    /// Example value shown for optional keys.
    pub example: &'static str,
}

const MISSING: KeyDoc = doc("?", "UNDOCUMENTED", "", "");

const fn doc(
    key: &'static str,
    what: &'static str,
    unit: &'static str,
    paper: &'static str,
) -> KeyDoc {
    KeyDoc {
        key,
        what,
        unit,
        paper,
        optional: false,
        example: "",
    }
}

/// Documentation of the key `key`, if any.
pub fn key_doc(key: &str) -> Option<&'static KeyDoc> {
    KEY_DOCS.iter().find(|d| d.key == key)
}

/// Documentation of every config key.
pub static KEY_DOCS: &[KeyDoc] = &[
    doc(
        "experiment.scenario",
        "scenario SVG file; empty = the embedded default (relative to this file)",
        "path",
        "the road scenario of Fig. 1",
    ),
    doc(
        "experiment.seed",
        "seed of the run's random number generator",
        "",
        "",
    ),
    doc("experiment.generations", "generations to evolve", "", "400"),
    doc(
        "experiment.steps",
        "simulation steps per evaluation",
        "steps",
        "1000",
    ),
    doc(
        "experiment.robots",
        "robots sharing the controller (first N of the scenario; 0 = all)",
        "",
        "5",
    ),
    doc(
        "experiment.init_population",
        "checkpoint whose population the run starts from (set by retrain); empty = fresh population",
        "path",
        "",
    ),
    doc(
        "substrate.neurons",
        "output neuron sheet as RINGSxANGLES; the wheel neurons L/R sit at the outer angles of the ring nearest radius 2/3 (the middle ring of 3)",
        "",
        "3x3, re-sampled to 9x9",
    ),
    doc(
        "substrate.coordinates",
        "CPPN coordinates of a node at ring radius r and angle a: cartesian = (r sin a, r cos a), polar = (r, a/pi)",
        "",
        "cartesian",
    ),
    doc(
        "substrate.normalize",
        "scale each sheet's outgoing weights by (its node count in the paper: 15 sensors, 9 neurons, 5 rays) / (its node count here), so a re-sampled substrate drives its neurons as strongly; exactly 1 at the paper's resolution",
        "",
        "",
    ),
    doc(
        "hyperneat.threshold",
        "CPPN outputs with |o| <= threshold express no connection",
        "",
        "0.2",
    ),
    doc(
        "hyperneat.amplitude",
        "largest controller weight: w = sign(o)(|o| - t)/(1 - t) * amplitude",
        "",
        "3.0",
    ),
    doc(
        "surface_sensors.rings",
        "surface sensor rings (distances) of the input sheet",
        "",
        "3, re-sampled to 3",
    ),
    doc(
        "surface_sensors.angles",
        "surface sensor angles per ring",
        "",
        "5, re-sampled to 6",
    ),
    doc(
        "surface_sensors.fov",
        "field of view of the surface sensors, centred ahead",
        "degrees",
        "180",
    ),
    doc(
        "surface_sensors.d_min",
        "distance of the nearest sensor ring from the robot centre",
        "px",
        "",
    ),
    doc(
        "surface_sensors.d_max",
        "distance of the farthest sensor ring",
        "px",
        "",
    ),
    doc(
        "distance_sensors.rays",
        "distance-sensor rays, a second input sheet; 0 = off",
        "",
        "none (future work)",
    ),
    doc(
        "distance_sensors.fov",
        "field of view of the distance sensors",
        "degrees",
        "",
    ),
    doc(
        "distance_sensors.range",
        "ray length from the robot's rim; a reading is 1 - d/range",
        "px",
        "",
    ),
    doc("physics.robot_radius", "robot disc radius", "px", ""),
    doc("physics.v_max", "top forward speed", "px/step", ""),
    doc(
        "physics.a_max",
        "acceleration at full throttle",
        "px/step^2",
        "",
    ),
    doc(
        "physics.omega_max",
        "turn rate at full wheel difference and standstill",
        "rad/step",
        "",
    ),
    doc(
        "physics.k",
        "drag factor: speed loses k * friction * v per step",
        "1/step",
        "",
    ),
    doc(
        "physics.robot_mass",
        "robot mass, for pushing movable objects",
        "",
        "",
    ),
    doc(
        "physics.puck_density",
        "puck mass per unit area",
        "1/px^2",
        "",
    ),
    doc(
        "physics.puck_damping",
        "fraction of a puck's velocity lost per step",
        "",
        "",
    ),
    doc(
        "physics.obstacle_density",
        "movable obstacle mass per unit area",
        "1/px^2",
        "",
    ),
    doc(
        "physics.obstacle_damping",
        "fraction of a movable obstacle's velocity lost per step",
        "",
        "",
    ),
    doc(
        "physics.collision_iterations",
        "contact-resolution passes per step",
        "",
        "",
    ),
    doc("physics.friction.road", "friction of road", "", "1 (ViVAE)"),
    doc(
        "physics.friction.grass",
        "friction of grass (also the background)",
        "",
        "10 (ViVAE)",
    ),
    doc(
        "physics.friction.sand",
        "friction of sand",
        "",
        "3.5 (ViVAE)",
    ),
    doc(
        "physics.friction.water",
        "friction of water",
        "",
        "6.5 (ViVAE)",
    ),
    doc("neat.population_size", "genomes per generation", "", "100"),
    doc(
        "neat.weight_amplitude",
        "CPPN link weights are clamped to [-a, a]",
        "",
        "3.0",
    ),
    doc(
        "neat.initial_weight_range",
        "initial and replacement weights are uniform in [-r, r]",
        "",
        "",
    ),
    doc(
        "neat.compatibility_threshold",
        "compatibility distance below which a genome joins a species",
        "",
        "15.0",
    ),
    doc(
        "neat.c_excess",
        "C1: coefficient of excess genes",
        "",
        "2.0",
    ),
    doc(
        "neat.c_disjoint",
        "C2: coefficient of disjoint genes",
        "",
        "2.0",
    ),
    doc(
        "neat.c_weight",
        "C3: coefficient of the mean weight difference of matching genes",
        "",
        "0.5",
    ),
    doc(
        "neat.c_activation",
        "C_ACT: coefficient of matching links whose target nodes' functions differ",
        "",
        "1.0",
    ),
    doc(
        "neat.normalize_distance",
        "divide excess, disjoint and activation terms by the larger genome's size",
        "",
        "",
    ),
    doc(
        "neat.normalize_min_genes",
        "genomes smaller than this are not normalised",
        "links",
        "",
    ),
    KeyDoc {
        optional: true,
        example: "10",
        ..doc(
            "neat.target_species",
            "when set, the threshold moves each generation towards this many species",
            "species",
            "",
        )
    },
    doc(
        "neat.threshold_step",
        "step of the dynamic compatibility threshold",
        "",
        "",
    ),
    doc(
        "neat.threshold_min",
        "lower bound of the dynamic compatibility threshold",
        "",
        "",
    ),
    doc(
        "neat.mating_probability",
        "probability that an offspring comes from crossover",
        "",
        "0.75",
    ),
    doc(
        "neat.interspecies_mating_probability",
        "probability that the second parent comes from another species",
        "",
        "",
    ),
    doc(
        "neat.mate_only_probability",
        "probability that a crossover child is not mutated",
        "",
        "",
    ),
    doc(
        "neat.add_link_probability",
        "probability of the add-link mutation",
        "",
        "0.3",
    ),
    doc(
        "neat.add_node_probability",
        "probability of the add-node mutation",
        "",
        "0.1",
    ),
    doc(
        "neat.weight_mutation_probability",
        "probability that an offspring's weights are mutated",
        "",
        "",
    ),
    doc(
        "neat.weight_link_probability",
        "per-link probability of changing its weight in a weight mutation",
        "",
        "",
    ),
    doc(
        "neat.weight_replace_probability",
        "per-changed-link probability of replacing instead of perturbing",
        "",
        "",
    ),
    doc(
        "neat.weight_perturb_power",
        "standard deviation of the Gaussian weight perturbation",
        "",
        "",
    ),
    doc(
        "neat.toggle_enable_probability",
        "probability of toggling one link's enabled flag",
        "",
        "",
    ),
    doc(
        "neat.activation_mutation_probability",
        "probability of changing one hidden node's function",
        "",
        "",
    ),
    doc(
        "neat.disabled_inherit_probability",
        "a gene disabled in either parent stays disabled with this probability",
        "",
        "0.75 (Stanley)",
    ),
    doc(
        "neat.add_link_attempts",
        "attempts to find an unconnected node pair for add-link",
        "",
        "",
    ),
    doc(
        "neat.survival_threshold",
        "fraction of each species (best first) allowed to reproduce",
        "",
        "",
    ),
    doc(
        "neat.elitism_fraction",
        "fraction of each species copied unchanged into the next generation",
        "",
        "0.05",
    ),
    doc(
        "neat.elitism_min_species_size",
        "species smaller than this keep no elites (the champion's always keeps one)",
        "genomes",
        "",
    ),
    doc(
        "neat.stagnation_limit",
        "generations without improvement after which a species gets no offspring",
        "generations",
        "15 (Stanley)",
    ),
    doc(
        "run.threads",
        "evaluation threads; 0 = one per core (results do not depend on it)",
        "",
        "",
    ),
    doc(
        "run.checkpoint_interval",
        "write a checkpoint every N generations (and always after the last)",
        "generations",
        "",
    ),
    doc(
        "run.checkpoint_keep",
        "checkpoints kept on disk; older ones are pruned",
        "",
        "",
    ),
];

/// Turns a toml parse error into one line: `line L: key K: reason`.
fn describe_toml_error(text: &str, err: &toml::de::Error) -> ConfigError {
    let reason = err.message().trim().replace('\n', " ");
    let Some(span) = err.span() else {
        return ConfigError::new(reason);
    };
    let line_no = text[..span.start.min(text.len())].matches('\n').count() + 1;
    let key = key_at(text, span.start);
    match key {
        Some(key) => ConfigError::new(format!("line {line_no}: key {key}: {reason}")),
        None => ConfigError::new(format!("line {line_no}: {reason}")),
    }
}

/// The dotted key whose assignment contains byte offset `pos`, if any.
fn key_at(text: &str, pos: usize) -> Option<String> {
    let mut section = String::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim();
        let end = offset + line.len();
        if let Some(header) = trimmed.strip_prefix('[') {
            let name = header
                .trim_start_matches('[')
                .split(']')
                .next()
                .unwrap_or("")
                .trim();
            if pos >= offset && pos < end {
                return Some(name.to_string());
            }
            section = name.to_string();
        } else if pos >= offset
            && pos < end
            && let Some((key, _)) = trimmed.split_once('=')
        {
            let key = key.trim().trim_matches('"');
            return Some(if section.is_empty() {
                key.to_string()
            } else {
                format!("{section}.{key}")
            });
        }
        offset = end;
    }
    (!section.is_empty()).then_some(section)
}

#[cfg(test)]
mod tests {
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
        let text = Config::default_commented();
        assert_eq!(Config::from_toml(&text).unwrap(), Config::default());
    }

    #[test]
    fn every_key_is_documented_and_every_doc_is_a_key() {
        let value = toml::Value::try_from(Config::default()).unwrap();
        let keys: Vec<String> = flatten(&value).into_iter().map(|(k, _)| k).collect();
        let undocumented: Vec<&String> = keys.iter().filter(|k| key_doc(k).is_none()).collect();
        assert!(
            undocumented.is_empty(),
            "undocumented keys: {undocumented:?}"
        );
        for d in KEY_DOCS {
            if d.optional {
                let (section, key) = d.key.rsplit_once('.').unwrap();
                let text = format!("[{section}]\n{key} = {}\n", d.example);
                Config::from_toml(&text)
                    .unwrap_or_else(|e| panic!("optional key {} example rejected: {e}", d.key));
            } else {
                assert!(
                    keys.iter().any(|k| k == d.key),
                    "doc for missing key {}",
                    d.key
                );
            }
        }
        assert!(!Config::default_commented().contains("UNDOCUMENTED"));
    }

    #[test]
    fn unknown_key_is_named_with_its_line() {
        let err = Config::from_toml("[neat]\npopulation_size = 10\npopsize = 3\n").unwrap_err();
        assert!(err.message.contains("line 3"), "{}", err.message);
        assert!(err.message.contains("neat.popsize"), "{}", err.message);
        assert!(!err.message.contains('\n'));
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

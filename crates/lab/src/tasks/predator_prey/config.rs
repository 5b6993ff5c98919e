//! The predator–prey task's config: its defaults and the keys it cannot honour.

use vivae_neat::NeatParams;

use crate::config::{Config, DistanceConfig, OpponentConfig, SubstrateConfig, TaskName};
use crate::search::{StrategyConfig, TaskFacts};
use crate::tasks::predator_prey::section::{CoevolutionConfig, Opponents, SideController};
use crate::tasks::predator_prey::{NAME, STEPS};
use crate::tasks::robot;

impl Config {
    /// The config of a predator–prey run: the open arena, 500 steps, the
    /// maze's robot for both sides, plain NEAT with populations of 100,
    /// 50 generations, opponents = the other side's previous best.
    pub fn predator_prey() -> Config {
        let mut c = Config::default();
        c.experiment.task = TaskName(NAME.into());
        c.experiment.scenario = "predator-prey".into();
        c.experiment.steps = STEPS;
        c.experiment.robots = 2;
        c.experiment.generations = 50;
        c.physics = robot::physics();
        c.neat = NeatParams {
            population_size: 100,
            ..NeatParams::plain_neat()
        };
        // The defaults select on a metric this task has not: it has none.
        StrategyConfig::fit(
            &mut c,
            &TaskFacts {
                metrics: Some(&[]),
                ..TaskFacts::default()
            },
        );
        c
    }
}

/// With `experiment.task = "predator-prey"`: refuses the keys such a run
/// cannot honour; the message names the key.
pub(super) fn validate(c: &Config) -> Result<(), String> {
    let e = &c.experiment;
    let refuse = |key: &str, why: &str| {
        Err(format!(
            "{key}: {why} (experiment.task = \"predator-prey\")"
        ))
    };
    if !e.scenarios.is_empty() {
        return refuse(
            "experiment.scenarios",
            "a predator-prey run has one arena: name it with experiment.scenario",
        );
    }
    if e.scenario.is_empty() {
        return refuse(
            "experiment.scenario",
            "name the arena: predator-prey, predator-prey-obstacles or an SVG file with a hunter and a prey",
        );
    }
    if e.robots != 2 {
        return refuse(
            &format!("experiment.robots = {}", e.robots),
            "the arena has a hunter and a prey: use 2",
        );
    }
    if !e.init_population.is_empty() {
        return refuse(
            "experiment.init_population",
            "both populations start from minimal networks",
        );
    }
    if e.steps == 0 {
        return refuse("experiment.steps = 0", "an episode needs at least one step");
    }
    validate_coevolution(c)
        .map_err(|(key, why)| format!("{key}: {why} (experiment.task = \"predator-prey\")"))?;
    let hyper = [
        CoevolutionConfig::of(c).hunter,
        CoevolutionConfig::of(c).prey,
    ]
    .contains(&SideController::Hyperneat);
    let unused = [
        ("substrate", c.substrate == SubstrateConfig::default()),
        (
            "surface_sensors",
            c.surface_sensors == vivae_sim::SurfaceSensors::default(),
        ),
        (
            "distance_sensors",
            c.distance_sensors == DistanceConfig::default(),
        ),
        (
            "opponent_sensors",
            c.opponent_sensors == OpponentConfig::default(),
        ),
        (
            "hyperneat",
            hyper || c.hyperneat == vivae_neat::hyperneat::HyperParams::default(),
        ),
        (
            "strategy",
            StrategyConfig::of(c).kind == StrategyConfig::default().kind,
        ),
    ];
    match unused.iter().find(|(_, default)| !default) {
        Some((section, _)) => refuse(
            &format!("[{section}]"),
            "both sides are NEAT networks (or, with coevolution.hunter/prey = \"hyperneat\", CPPNs on a fixed substrate) of 4 opponent radar slices, 6 rangefinders and a bias, evolved by NEAT: leave this section at its defaults",
        ),
        None => Ok(()),
    }
}

/// Most opponents a genome meets a generation (`coevolution.sample`).
pub const MAX_SAMPLE: usize = 1000;

/// The `[coevolution]` and `[hyperneat]` keys: the key and why it is refused.
fn validate_coevolution(c: &Config) -> Result<(), (String, String)> {
    let refuse = |key: &str, why: &str| Err((key.to_string(), why.to_string()));
    if CoevolutionConfig::of(c).sample == 0 {
        return refuse("coevolution.sample = 0", "draw at least one opponent");
    }
    if CoevolutionConfig::of(c).sample > MAX_SAMPLE {
        return refuse(
            &format!("coevolution.sample = {}", CoevolutionConfig::of(c).sample),
            &format!(
                "at most {MAX_SAMPLE} opponents: every genome meets each of them every generation"
            ),
        );
    }
    let fixed = CoevolutionConfig::of(c).opponents == Opponents::Fixed;
    if fixed && CoevolutionConfig::of(c).fixed_prey.is_empty() {
        return refuse(
            "coevolution.opponents = \"fixed\"",
            "name the prey with coevolution.fixed_prey (a predator-prey run directory or its champions.json)",
        );
    }
    if !fixed && !CoevolutionConfig::of(c).fixed_prey.is_empty() {
        return refuse(
            "coevolution.fixed_prey",
            "only with coevolution.opponents = \"fixed\"",
        );
    }
    match c.hyperneat.validate() {
        Err(e) => refuse("[hyperneat]", &e.to_string()),
        Ok(()) => Ok(()),
    }
}

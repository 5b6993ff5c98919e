//! The maze task's config: its `[maze]` section (which robot model, which
//! walls), its defaults and the keys a maze run cannot honour.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::NeatParams;

use crate::config::{Config, DistanceConfig, SubstrateConfig, TaskName};

impl Config {
    /// The config of a maze run with the example's settings: the hard maze,
    /// 400 steps, the paper's robot, plain NEAT with a population of 250,
    /// novelty search's ρ_min = 6 px, NSGA-II on fitness alone.
    pub fn maze() -> Config {
        let mut c = Config::default();
        c.experiment.task = TaskName(super::NAME.into());
        c.experiment.scenario = "hard-maze".into();
        c.experiment.steps = crate::tasks::maze::STEPS;
        c.experiment.robots = 1;
        // 50,000 evaluations.
        c.experiment.generations = 200;
        c.physics = crate::tasks::maze::MazeTask::physics();
        c.neat = NeatParams {
            population_size: 250,
            ..NeatParams::plain_neat()
        };
        let novelty = vivae_neat::strategies::NoveltyParams::default();
        // ρ_min in px (Lehman's maze code, via goNEAT_NS): the behaviour is in px.
        c.strategy.novelty.threshold = 6.0;
        c.strategy.novelty.threshold_floor = novelty.threshold_floor;
        c.strategy.nsga2.objectives = vec!["fitness".into()];
        // 10 px cells over the hard maze (205 × 205); `vivae evolve --task maze` fits them to its maze.
        c.strategy.map_elites.bins = vec![21];
        c
    }
}

/// A maze run's robot model and its details (`[maze]`; docs/guide.md, "The maze").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MazeConfig {
    /// The robot: `lehman` (Lehman's maze navigator from his released code:
    /// speed and turn rate integrate the outputs, a move into a wall is not
    /// made) or `vivae` (our differential robot of `[physics]`, sliding
    /// along walls). Unset = lehman.
    ///
    /// Example: "vivae".
    pub robot: MazeRobot,
    /// With robot `lehman`: `true` reproduces the released code's input
    /// quirks (the radar overwrites the backward rangefinder's input, the
    /// last input stays 0, ten network activations on the first inputs
    /// before the first step); `false` is the paper's description (six
    /// rangefinders, four radar slices, a bias; one activation per step).
    /// Unset = true.
    ///
    /// Example: false.
    pub quirks: bool,
    /// With robot `lehman` on a shipped maze: `lehman` (the wall segments of
    /// Lehman's maze files, `scenarios/*-maze.txt`) or `scenario` (the
    /// walls of the shipped SVG, re-drawn on a 5…200 frame). Any other maze
    /// file's walls are its own. Unset = lehman.
    ///
    /// Example: "scenario".
    pub walls: MazeWalls,
    /// With robot `lehman`: what a move into a wall does: `stop` (the
    /// robot stays where it was and keeps its speed, Lehman's rule) or
    /// `slide` (it moves along the wall: the move's x or y part alone when
    /// that is free). Unset = stop.
    ///
    /// Example: "slide".
    pub collision: Collision,
}

impl Default for MazeConfig {
    fn default() -> Self {
        MazeConfig {
            robot: MazeRobot::Lehman,
            quirks: true,
            walls: MazeWalls::Lehman,
            collision: Collision::Stop,
        }
    }
}

impl MazeConfig {
    /// Whether every key is at its default (the section is then not written).
    pub fn is_default(&self) -> bool {
        *self == MazeConfig::default()
    }
}

/// Names a kebab-case choice type: `name()`, `FromStr` naming every choice.
macro_rules! choice {
    ($ty:ident { $($variant:ident => $name:literal),+ }) => {
        impl $ty {
            /// The name as configs and the command line write it.
            pub fn name(self) -> &'static str {
                match self { $($ty::$variant => $name),+ }
            }
        }
        impl std::str::FromStr for $ty {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                [$($ty::$variant),+].into_iter().find(|k| k.name() == s).ok_or_else(|| {
                    format!("'{s}': expected {}", [$($name),+].join(" or "))
                })
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

/// Which robot model drives through the maze (`maze.robot`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum MazeRobot {
    /// Lehman's maze navigator ([`super::lehman`]).
    #[default]
    Lehman,
    /// Our differential robot in the driving physics ([`super::MazeTask`]).
    Vivae,
}
choice!(MazeRobot { Lehman => "lehman", Vivae => "vivae" });

/// Whose walls a shipped maze has under Lehman's robot (`maze.walls`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum MazeWalls {
    /// The segments of Lehman's maze files.
    #[default]
    Lehman,
    /// The walls of the scenario SVG.
    Scenario,
}
choice!(MazeWalls { Lehman => "lehman", Scenario => "scenario" });

/// What a move into a wall does under Lehman's robot (`maze.collision`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Collision {
    /// The move is not made (Lehman's rule).
    #[default]
    Stop,
    /// The move's x or y part alone is made when that is free.
    Slide,
}
choice!(Collision { Stop => "stop", Slide => "slide" });

/// With another task than the maze: refuses a `[maze]` section that is not
/// at its defaults (it would be ignored).
pub fn refuse_for_other_tasks(c: &crate::config::Config) -> Result<(), String> {
    if c.maze.is_default() {
        Ok(())
    } else {
        Err(format!(
            "[maze]: only a maze run reads it (experiment.task = \"{}\"): use --task maze or drop the section",
            c.experiment.task
        ))
    }
}

/// With `experiment.task = "maze"`: refuses the keys a maze run cannot
/// honour; the message names the key.
pub(super) fn validate(c: &Config) -> Result<(), String> {
    let e = &c.experiment;
    let s = &c.substrate;
    let refuse = |key: &str, why: &str| Err(format!("{key}: {why} (experiment.task = \"maze\")"));
    if !e.scenarios.is_empty() {
        return refuse(
            "experiment.scenarios",
            "a maze run has one maze: name it with experiment.scenario",
        );
    }
    if e.scenario.is_empty() {
        return refuse(
            "experiment.scenario",
            "name the maze: hard-maze, medium-maze or an SVG file with one robot and a `goal` mark",
        );
    }
    if e.robots != 1 {
        return refuse(
            &format!("experiment.robots = {}", e.robots),
            "a maze has one robot: use 1",
        );
    }
    if !e.init_population.is_empty() {
        return refuse(
            "experiment.init_population",
            "a maze run starts from minimal networks (retrain re-samples a substrate, which a maze network has not)",
        );
    }
    if !s.train_neurons.is_empty() || !s.train_sensors.is_empty() {
        return refuse(
            "substrate.train_neurons/train_sensors",
            "a maze network has no substrate to train at several resolutions",
        );
    }
    if !s.kind.is_polar() {
        return refuse(
            "substrate.kind",
            "a maze network is evolved directly, not decoded into an ES-HyperNEAT substrate",
        );
    }
    if c.strategy.behaviour != crate::config::strategy::BehaviourKind::EndPosition {
        return refuse(
            &format!("strategy.behaviour = {}", c.strategy.behaviour.name()),
            "a maze's behaviour is the robot's end position in px: leave it at end-position",
        );
    }
    validate_robot(c)?;
    let unused = [
        ("substrate", *s == SubstrateConfig::default()),
        (
            "surface_sensors",
            c.surface_sensors == vivae_sim::SurfaceSensors::default(),
        ),
        (
            "distance_sensors",
            c.distance_sensors == DistanceConfig::default(),
        ),
        (
            "hyperneat",
            c.hyperneat == vivae_neat::hyperneat::HyperParams::default(),
        ),
    ];
    match unused.iter().find(|(_, default)| !default) {
        Some((section, _)) => refuse(
            &format!("[{section}]"),
            "a maze robot has the paper's 6 rangefinders and 4 radar slices and a plain network: leave this section at its defaults",
        ),
        None => Ok(()),
    }
}

/// The `[maze]` keys and `[physics]` as the chosen robot reads them: Lehman's
/// robot has its own constants, ours has none of Lehman's options.
fn validate_robot(c: &Config) -> Result<(), String> {
    let m = &c.maze;
    match m.robot {
        MazeRobot::Lehman if c.physics != super::MazeTask::physics() => Err(
            "[physics]: Lehman's maze robot has its own constants (docs/guide.md, \"The maze\"): leave [physics] at the maze's defaults or use maze.robot = \"vivae\" (--robot vivae)".into(),
        ),
        MazeRobot::Vivae
            if (m.quirks, m.walls, m.collision)
                != (true, MazeWalls::Lehman, Collision::Stop) =>
        {
            Err("[maze] quirks/walls/collision: these are options of Lehman's robot (maze.robot = \"lehman\"); our robot reads [physics] and the scenario's walls".into())
        }
        _ => Ok(()),
    }
}

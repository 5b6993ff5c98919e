//! The maze task's `[maze]` section (which robot model, which walls, which
//! collision rule): plain data the run's config holds, apart from the rules
//! that read the rest of the config (`config.rs`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::config::{Config, OwnedSection, Section};

/// The maze task's robot model (`experiment.task = "maze"` only).
// Its details in docs/howto/maze.md; the maze task's own section (the doc
// line above is the config reference's), registered with its entry (`SECTION`).
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

    /// The section as `config` sets it.
    pub fn of(config: &Config) -> MazeConfig {
        config.owned.of()
    }
}

impl OwnedSection for MazeConfig {
    const NAME: &'static str = "maze";
}

/// The `[maze]` section's registration.
pub const SECTION: Section = Section::of::<MazeConfig>();

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

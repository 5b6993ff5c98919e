//! What the `[strategy]` section of a config says beside each strategy's
//! settings: which strategy runs ([`StrategyName`]) and which behaviour
//! descriptor it searches on ([`BehaviourKind`]). The section itself,
//! [`crate::search::StrategyConfig`], is declared where the strategies are
//! registered, each strategy's settings in its own file of `search/`. Every
//! strategy breeds with NEAT's operators and `[neat]` parameters, and
//! evaluates `neat.population_size` genomes per generation.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Which behaviour descriptor an episode reports (see [`crate::tasks::driving::descriptors`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum BehaviourKind {
    /// The robots' mean end position over the arena's size.
    #[default]
    EndPosition,
    /// Every robot's end position over the arena's size, concatenated.
    EndPositions,
    /// Mean signed side of the road and mean speed over `v_max`.
    SideSpeed,
    /// The robots' mean position over the arena's size at
    /// [`TRAJECTORY_SAMPLES`] evenly spaced times, the last at the end.
    Trajectory,
}

/// Positions a `trajectory` behaviour samples: 5, so 10 coordinates (as
/// Lehman & Stanley sampled their biped's path, a handful of points).
pub const TRAJECTORY_SAMPLES: usize = 5;

impl BehaviourKind {
    /// Coordinates of the descriptor for `robots` robots.
    pub fn dims(self, robots: usize) -> usize {
        match self {
            BehaviourKind::EndPositions => 2 * robots,
            BehaviourKind::Trajectory => 2 * TRAJECTORY_SAMPLES,
            BehaviourKind::EndPosition | BehaviourKind::SideSpeed => 2,
        }
    }

    /// The box every descriptor lies in: (lower, upper) per coordinate.
    pub fn bounds(self, robots: usize) -> (Vec<f64>, Vec<f64>) {
        let n = self.dims(robots);
        match self {
            BehaviourKind::SideSpeed => (vec![-1.0, 0.0], vec![1.0, 1.0]),
            _ => (vec![0.0; n], vec![1.0; n]),
        }
    }

    /// Column names of the descriptor's `dims` coordinates.
    pub fn coordinate_names(self, dims: usize) -> Vec<String> {
        match self {
            BehaviourKind::EndPosition => vec!["x".into(), "y".into()],
            BehaviourKind::SideSpeed => vec!["side".into(), "speed".into()],
            BehaviourKind::EndPositions => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2))
                .collect(),
            // The sample's number from 1 (the end is the last).
            BehaviourKind::Trajectory => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2 + 1))
                .collect(),
        }
    }

    /// The name as configs write it.
    pub fn name(self) -> &'static str {
        match self {
            BehaviourKind::EndPosition => "end-position",
            BehaviourKind::EndPositions => "end-positions",
            BehaviourKind::SideSpeed => "side-speed",
            BehaviourKind::Trajectory => "trajectory",
        }
    }
}

impl std::str::FromStr for BehaviourKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        [
            BehaviourKind::EndPosition,
            BehaviourKind::EndPositions,
            BehaviourKind::SideSpeed,
            BehaviourKind::Trajectory,
        ]
        .into_iter()
        .find(|k| k.name() == s)
        .ok_or_else(|| {
            format!("'{s}': expected end-position, end-positions, side-speed or trajectory")
        })
    }
}

/// The name of the search strategy a run uses (`strategy.kind`): one of the
/// strategies registered in [`crate::search`], which checks it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct StrategyName(pub String);

impl StrategyName {
    /// The default strategy's name: NEAT selecting on fitness, the paper's.
    pub const NEAT: &'static str = "neat";

    /// The name as configs and the command line write it.
    pub fn name(&self) -> &str {
        &self.0
    }
}

impl Default for StrategyName {
    fn default() -> Self {
        StrategyName(Self::NEAT.into())
    }
}

impl From<&str> for StrategyName {
    fn from(name: &str) -> Self {
        StrategyName(name.into())
    }
}

impl std::fmt::Display for StrategyName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::str::FromStr for StrategyName {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Ok(StrategyName(s.to_string()))
    }
}

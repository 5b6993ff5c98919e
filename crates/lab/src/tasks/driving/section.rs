//! The driving task's `[fitness]` section: what an episode scores. The
//! task registers it with its entry ([`SECTION`]); the config holds it as
//! its table, read typed by [`FitnessConfig::of`].

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::config::{Config, OwnedSection, Section};

/// What an episode of the driving task scores (unset = the paper's average speed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FitnessConfig {
    /// `average_speed` (the paper's: distance driven per robot-step) or
    /// `progress` (distance along each robot's route, its `data-route` or
    /// the nearest route, per robot-step: driving the wrong way counts
    /// against; needs a scenario with routes, docs/scenario-format.md).
    ///
    /// Example: "progress".
    pub kind: FitnessKind,
    /// Subtracted from the score for each contact begun per 1,000
    /// robot-steps (robot–robot, robot–scripted robot, robot–obstacle; not
    /// walls); 0 = contacts cost nothing.
    ///
    /// Unit: px/step per contact per 1,000 robot-steps. Example: 0.2.
    pub contact_cost: f64,
}

/// The score of an episode before any contact cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FitnessKind {
    /// Σ odometer / robot-steps (the paper's).
    #[default]
    AverageSpeed,
    /// Σ distance along each robot's route / robot-steps.
    Progress,
}

impl OwnedSection for FitnessConfig {
    const NAME: &'static str = "fitness";
}

/// The `[fitness]` section as the driving task registers it.
pub const SECTION: Section = Section::of::<FitnessConfig>();

impl FitnessConfig {
    /// Whether this is the default (so configs without the section write none).
    pub fn is_default(&self) -> bool {
        *self == FitnessConfig::default()
    }

    /// `config`'s `[fitness]` section (its defaults when unset).
    pub fn of(config: &Config) -> FitnessConfig {
        config.owned.of()
    }

    /// An error naming the key when a value is out of range.
    pub fn check(&self) -> Result<(), String> {
        let c = self.contact_cost;
        if !(c.is_finite() && (0.0..=1e6).contains(&c)) {
            return Err(format!(
                "fitness.contact_cost = {c}: must be a number from 0 to 1e6"
            ));
        }
        Ok(())
    }
}

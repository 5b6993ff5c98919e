//! The `[gymnasium]` section: which Gymnasium environment a `gymnasium`
//! run evolves controllers for, and how many episodes an evaluation plays.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::config::{Config, OwnedSection, Section};

/// A Gymnasium environment played from Python (the `gymnasium` task): its
/// id, the episodes per evaluation, and the shape its spaces give the
/// networks (filled in by `vivae.gym` from the environment itself).
// The gymnasium task's own section (the doc above is the config
// reference's), registered with its entry (`SECTION`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct GymnasiumConfig {
    /// The Gymnasium environment id ("LunarLander-v3", "Hopper-v5", …).
    pub env: String,
    /// Episodes per evaluation, each reset with a seed drawn from the
    /// evaluation's seed; fitness is their mean return.
    pub episodes: u32,
    /// Network inputs: the observation's size, plus one bias input.
    pub inputs: usize,
    /// Network outputs: one per discrete action (the largest is taken),
    /// or one per dimension of a continuous action (scaled to its bounds).
    pub outputs: usize,
    /// Steps after which an episode is truncated (the environment's
    /// `max_episode_steps`).
    pub max_steps: u32,
    /// The return at which the environment counts as solved (its
    /// `reward_threshold`); the champion's validated mean is held against it.
    pub reward_threshold: Option<f64>,
}

impl Default for GymnasiumConfig {
    fn default() -> Self {
        GymnasiumConfig {
            env: "LunarLander-v3".into(),
            episodes: 3,
            inputs: 9,
            outputs: 4,
            max_steps: 1000,
            reward_threshold: Some(200.0),
        }
    }
}

impl OwnedSection for GymnasiumConfig {
    const NAME: &'static str = "gymnasium";
}

impl GymnasiumConfig {
    /// The section of `config`.
    pub fn of(config: &Config) -> GymnasiumConfig {
        config.owned.of::<GymnasiumConfig>()
    }

    /// Why the section cannot be run, naming the key; `None` when it can.
    pub fn problem(&self) -> Option<String> {
        const MOST: usize = 4096;
        if self.env.trim().is_empty() {
            return Some("gymnasium.env = \"\": name a Gymnasium environment id".into());
        }
        if self.episodes == 0 {
            return Some("gymnasium.episodes = 0: an evaluation plays at least one".into());
        }
        if !(2..=MOST).contains(&self.inputs) {
            return Some(format!(
                "gymnasium.inputs = {}: expected 2 to {MOST} (the observation and a bias)",
                self.inputs
            ));
        }
        if !(1..=MOST).contains(&self.outputs) {
            return Some(format!(
                "gymnasium.outputs = {}: expected 1 to {MOST}",
                self.outputs
            ));
        }
        if self.max_steps == 0 {
            return Some("gymnasium.max_steps = 0: an episode takes at least one step".into());
        }
        match self.reward_threshold {
            Some(t) if !t.is_finite() => Some(format!(
                "gymnasium.reward_threshold = {t}: expected a finite number"
            )),
            _ => None,
        }
    }
}

/// The section's registration.
pub const SECTION: Section = Section::of::<GymnasiumConfig>();

//! The `[coevolution]` section: how a two-population run (the predator–prey
//! task) picks the opponents each population is evaluated against.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::config::{Config, OwnedSection, Section};

/// Whom each population's genomes meet in a generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Opponents {
    /// The other population's best of the previous generation (ViVAE's
    /// `PredatorKorist`; its first genome in generation 0).
    #[default]
    Best,
    /// A sample (with replacement) of the other population's hall of fame,
    /// its best of every earlier generation (Rosin & Belew 1997).
    HallOfFame,
    /// A fixed, non-evolving prey (`fixed_prey`): only the hunters evolve,
    /// every hunter meets that one prey (the baseline co-evolved hunters
    /// are compared with).
    Fixed,
}

impl Opponents {
    /// The name in the config.
    pub fn name(self) -> &'static str {
        match self {
            Opponents::Best => "best",
            Opponents::HallOfFame => "hall-of-fame",
            Opponents::Fixed => "fixed",
        }
    }
}

/// What one side's genomes are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SideController {
    /// A plain NEAT network of the sensors (11 inputs, 2 outputs).
    #[default]
    Neat,
    /// A CPPN decoded onto a substrate whose input nodes sit at the
    /// sensors' angles (HyperNEAT, the `[hyperneat]` settings).
    Hyperneat,
}

impl SideController {
    /// The name in the config.
    pub fn name(self) -> &'static str {
        match self {
            SideController::Neat => "neat",
            SideController::Hyperneat => "hyperneat",
        }
    }

    /// Whether this is plain NEAT (the default, not written to a config).
    pub fn is_neat(&self) -> bool {
        *self == SideController::Neat
    }
}

/// Co-evolution of two populations (the predator-prey task): whom each is
/// evaluated against.
// The predator–prey task's own section (the doc above is the config
// reference's), registered with its entry (`SECTION`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CoevolutionConfig {
    /// Whom each population's genomes are evaluated against: "best" (the
    /// other population's best of the previous generation),
    /// "hall-of-fame" (a sample of its best of every earlier generation) or
    /// "fixed" (only the hunters evolve, against the prey of `fixed_prey`);
    /// a genome's fitness is its mean over the opponents.
    pub opponents: Opponents,
    /// Opponents drawn from the hall of fame per generation (with
    /// "hall-of-fame"); the same sample for every genome of a population.
    pub sample: usize,
    /// With opponents = "fixed": the prey every hunter meets, the prey
    /// champion of a predator-prey run (its directory or its
    /// champions.json, or a fixed-prey run's fixed-prey.json); the run
    /// copies it to fixed-prey.json.
    ///
    /// Example: "runs/hall-6".
    #[serde(skip_serializing_if = "String::is_empty")]
    pub fixed_prey: String,
    /// The hunters' genomes: "neat" (plain NEAT networks; unset means it)
    /// or "hyperneat" (CPPNs decoded onto a substrate at the sensors'
    /// angles, with the `[hyperneat]` settings).
    ///
    /// Example: "hyperneat".
    #[serde(skip_serializing_if = "SideController::is_neat")]
    pub hunter: SideController,
    /// The prey's genomes: "neat" (unset means it) or "hyperneat", as
    /// `hunter`.
    ///
    /// Example: "hyperneat".
    #[serde(skip_serializing_if = "SideController::is_neat")]
    pub prey: SideController,
}

impl Default for CoevolutionConfig {
    fn default() -> Self {
        CoevolutionConfig {
            opponents: Opponents::Best,
            sample: 5,
            fixed_prey: String::new(),
            hunter: SideController::Neat,
            prey: SideController::Neat,
        }
    }
}

impl OwnedSection for CoevolutionConfig {
    const NAME: &'static str = "coevolution";
}

/// The `[coevolution]` section's registration.
pub const SECTION: Section = Section::of::<CoevolutionConfig>();

impl CoevolutionConfig {
    /// Whether this is the default: a config written without the section.
    pub fn is_default(&self) -> bool {
        *self == CoevolutionConfig::default()
    }

    /// The section as `config` sets it.
    pub fn of(config: &Config) -> CoevolutionConfig {
        config.owned.of()
    }
}

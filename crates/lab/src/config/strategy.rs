//! What the `[strategy]` section of a config says beside each strategy's
//! settings: which strategy runs ([`StrategyName`]) and which behaviour
//! descriptor it searches on ([`BehaviourName`], one its task offers). The section itself,
//! [`crate::search::StrategyConfig`], is declared where the strategies are
//! registered, each strategy's settings in its own file of `search/`. Every
//! strategy breeds with NEAT's operators and `[neat]` parameters, and
//! evaluates `neat.population_size` genomes per generation.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The impls a registered name shares: `name()`, its default (the type's
/// constant `$default`), and conversions from and to text (any text parses:
/// the registry that owns the names checks it).
macro_rules! registered_name {
    ($name:ident, $default:ident) => {
        impl $name {
            /// The name as configs and the command line write it.
            pub fn name(&self) -> &str {
                &self.0
            }
        }

        impl Default for $name {
            fn default() -> Self {
                $name(Self::$default.into())
            }
        }

        impl From<&str> for $name {
            fn from(name: &str) -> Self {
                $name(name.into())
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(&self.0)
            }
        }

        impl std::str::FromStr for $name {
            type Err = String;

            fn from_str(s: &str) -> Result<Self, String> {
                Ok($name(s.to_string()))
            }
        }
    };
}

/// The behaviour descriptor a run's strategy searches on
/// (`strategy.behaviour`): one of those its task offers, which checks it
/// (each task declares its own with its registration).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct BehaviourName(pub String);

impl BehaviourName {
    /// The default descriptor's name; a task with a descriptor of its own
    /// and no choice of them leaves the key at it.
    pub const DEFAULT: &'static str = "end-position";
}

registered_name!(BehaviourName, DEFAULT);

/// The name of the search strategy a run uses (`strategy.kind`): one of the
/// strategies registered in [`crate::search`], which checks it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct StrategyName(pub String);

impl StrategyName {
    /// The default strategy's name: NEAT selecting on fitness, the paper's.
    pub const NEAT: &'static str = "neat";
}

registered_name!(StrategyName, NEAT);

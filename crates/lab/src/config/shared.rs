//! The shared sections only some tasks read: a robot's substrate, its
//! sensors and the simulator's physics. A task's entry lists the ones it
//! reads; a run's `config.toml` holds only those (beside `[experiment]`,
//! `[neat]`, `[run]` and the owned sections), and a key of one it does not
//! read is refused by name.

use serde::Serialize;

use super::Config;

/// A shared section of the config that only the tasks listing it read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SharedSection {
    /// `[substrate]`: the output neuron sheet and the coordinate mode.
    Substrate,
    /// `[hyperneat]`: CPPN → substrate expression.
    Hyperneat,
    /// `[surface_sensors]`: the surface sensors.
    SurfaceSensors,
    /// `[distance_sensors]`: the distance sensors.
    DistanceSensors,
    /// `[opponent_sensors]`: the opponent radar.
    OpponentSensors,
    /// `[physics]`: the simulator's constants.
    Physics,
}

impl SharedSection {
    /// Every one of them, in the order a config writes them.
    pub const ALL: [SharedSection; 6] = [
        SharedSection::Substrate,
        SharedSection::Hyperneat,
        SharedSection::SurfaceSensors,
        SharedSection::DistanceSensors,
        SharedSection::OpponentSensors,
        SharedSection::Physics,
    ];

    /// Its table's name in a config file.
    pub fn name(self) -> &'static str {
        match self {
            SharedSection::Substrate => "substrate",
            SharedSection::Hyperneat => "hyperneat",
            SharedSection::SurfaceSensors => "surface_sensors",
            SharedSection::DistanceSensors => "distance_sensors",
            SharedSection::OpponentSensors => "opponent_sensors",
            SharedSection::Physics => "physics",
        }
    }

    /// The one called `name`, if it is one.
    pub fn named(name: &str) -> Option<SharedSection> {
        SharedSection::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The section of `config` as TOML (every key it writes).
    pub fn value(self, config: &Config) -> Option<toml::Value> {
        fn toml<T: Serialize>(t: &T) -> Option<toml::Value> {
            toml::Value::try_from(t).ok()
        }
        match self {
            SharedSection::Substrate => toml(&config.substrate),
            SharedSection::Hyperneat => toml(&config.hyperneat),
            SharedSection::SurfaceSensors => toml(&config.surface_sensors),
            SharedSection::DistanceSensors => toml(&config.distance_sensors),
            SharedSection::OpponentSensors => toml(&config.opponent_sensors),
            SharedSection::Physics => toml(&config.physics),
        }
    }
}

impl Config {
    /// The config as TOML with, of the [`SharedSection`]s, only those in
    /// `reads` (a run's `config.toml`: its task's); with all of them, as
    /// [`Config::to_toml`].
    pub fn to_toml_reading(&self, reads: &[SharedSection]) -> String {
        toml::to_string(&Reading {
            config: self,
            reads,
        })
        .expect("config serialises to TOML")
    }
}

/// A config written with only the shared sections `reads`.
pub(super) struct Reading<'a> {
    pub(super) config: &'a Config,
    pub(super) reads: &'a [SharedSection],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_config_written_reading_every_section_is_the_whole_config() {
        let mut c = Config::maze();
        c.opponent_sensors.slices = 4;
        assert_eq!(c.to_toml_reading(&SharedSection::ALL), c.to_toml());
        let text = c.to_toml_reading(&[SharedSection::Physics]);
        for s in SharedSection::ALL {
            let opens = text.contains(&format!("\n[{}]\n", s.name()));
            assert_eq!(opens, s == SharedSection::Physics, "{s:?}: {text}");
        }
        assert!(text.contains("\n[neat]\n") && text.contains("\n[strategy]\n"));
        assert_eq!(Config::from_toml(&text).unwrap().physics, c.physics);
        for s in SharedSection::ALL {
            assert_eq!(SharedSection::named(s.name()), Some(s));
        }
        assert_eq!(SharedSection::named("neat"), None);
    }
}

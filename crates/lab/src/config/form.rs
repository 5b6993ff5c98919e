//! The config's serde form: the shared sections in order, each left out
//! where the derive left it out (at its defaults, for the sections written
//! only when set), then the sections tasks own, as
//! [`OwnedSections`](super::owned::OwnedSections) holds them. Reading keeps
//! every table that is not a shared section as written, for the tasks'
//! sections to settle ([`super::owned::settle`]).

use serde::de::{Error as _, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::Config;
use super::shared::{Reading, SharedSection};

/// The shared sections' names, in the order a config is written.
pub(crate) const FIELDS: [&str; 9] = [
    "experiment",
    "substrate",
    "hyperneat",
    "surface_sensors",
    "distance_sensors",
    "opponent_sensors",
    "physics",
    "neat",
    "run",
];

/// The search strategies' section: theirs (each strategy's settings in
/// it), held with the tasks' own sections but written after `[run]`, where
/// it always was.
pub(crate) const STRATEGY: &str = "strategy";

impl Serialize for Config {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        Reading {
            config: self,
            reads: &SharedSection::ALL,
        }
        .serialize(serializer)
    }
}

impl Serialize for Reading<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let (c, reads) = (self.config, self.reads);
        let mut out = serializer.serialize_map(None)?;
        out.serialize_entry("experiment", &c.experiment)?;
        if reads.contains(&SharedSection::Substrate) {
            out.serialize_entry("substrate", &c.substrate)?;
        }
        if reads.contains(&SharedSection::Hyperneat) {
            out.serialize_entry("hyperneat", &c.hyperneat)?;
        }
        if reads.contains(&SharedSection::SurfaceSensors) {
            out.serialize_entry("surface_sensors", &c.surface_sensors)?;
        }
        if reads.contains(&SharedSection::DistanceSensors) {
            out.serialize_entry("distance_sensors", &c.distance_sensors)?;
        }
        if reads.contains(&SharedSection::OpponentSensors)
            && !c.opponent_sensors.is_off_by_default()
        {
            out.serialize_entry("opponent_sensors", &c.opponent_sensors)?;
        }
        if reads.contains(&SharedSection::Physics) {
            out.serialize_entry("physics", &c.physics)?;
        }
        out.serialize_entry("neat", &c.neat)?;
        out.serialize_entry("run", &c.run)?;
        if let Some(strategy) = c.owned.raw(STRATEGY) {
            out.serialize_entry(STRATEGY, strategy)?;
        }
        for (name, table) in c.owned.iter().filter(|(n, _)| *n != STRATEGY) {
            out.serialize_entry(name, table)?;
        }
        out.end()
    }
}

impl<'de> Deserialize<'de> for Config {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Config, D::Error> {
        d.deserialize_map(Sections)
    }
}

/// Reads a config's sections, each key left out at its default.
struct Sections;

impl<'de> Visitor<'de> for Sections {
    type Value = Config;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a config's sections")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Config, A::Error> {
        let mut c = Config::default();
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "experiment" => c.experiment = map.next_value()?,
                "substrate" => c.substrate = map.next_value()?,
                "hyperneat" => c.hyperneat = map.next_value()?,
                "surface_sensors" => c.surface_sensors = map.next_value()?,
                "distance_sensors" => c.distance_sensors = map.next_value()?,
                "opponent_sensors" => c.opponent_sensors = map.next_value()?,
                "physics" => c.physics = map.next_value()?,
                "neat" => c.neat = map.next_value()?,
                "run" => c.run = map.next_value()?,
                _ => match map.next_value::<toml::Value>()? {
                    table @ toml::Value::Table(_) => c.owned.insert(key, table),
                    _ => return Err(A::Error::unknown_field(&key, &FIELDS)),
                },
            }
        }
        Ok(c)
    }
}

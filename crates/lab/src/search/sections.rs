//! The settings sections strategies register with their entry
//! ([`Settings`]): `[strategy.NAME]` kept as written, read by the
//! strategy's settings type, and the `[strategy]` section's serde form.
//!
//! A config that names no registered section is written exactly as before
//! (the built-in fields, in order); a run of a strategy with a registered
//! section writes that section with every key, so its `config.toml` says
//! every setting the run used.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::ser::SerializeStruct;
use serde::{Deserialize, Serialize};

use crate::error::one_line;
use crate::search::{Settings, StrategyConfig, StrategySettings, entries};

/// The `[strategy]` keys that are the built-in fields, not sections.
pub(crate) const FIELDS: [&str; 5] = ["kind", "behaviour", "novelty", "map_elites", "nsga2"];

/// The registered settings sections a config sets, by name, each as
/// written (keys left out take their defaults). Two are equal when every
/// registered section has the same settings in both.
#[derive(Debug, Clone, Default)]
pub struct Sections(BTreeMap<String, toml::Table>);

/// Every registered settings section.
fn registered() -> Vec<Settings> {
    entries().into_iter().filter_map(|e| e.settings).collect()
}

/// The registered section called `name`.
fn section(name: &str) -> Option<Settings> {
    registered().into_iter().find(|s| s.section == name)
}

impl Sections {
    /// Section `s` with every key (as written, the rest at its defaults).
    fn full(&self, s: &Settings) -> std::result::Result<toml::Table, String> {
        (s.read)(self.0.get(s.section).unwrap_or(&toml::Table::new()))
    }

    /// The settings `T`, its keys left out at their defaults.
    pub(crate) fn settings<T: StrategySettings>(&self) -> std::result::Result<T, String> {
        parse_section(self.0.get(T::SECTION).unwrap_or(&toml::Table::new()))
    }

    /// Sets the section of `T` to `settings` (every key).
    pub fn set<T: StrategySettings>(&mut self, settings: &T) -> std::result::Result<(), String> {
        match toml::Value::try_from(settings) {
            Ok(toml::Value::Table(t)) => {
                self.0.insert(T::SECTION.to_string(), t);
                Ok(())
            }
            _ => Err(format!("strategy.{}: not a table of settings", T::SECTION)),
        }
    }

    /// Checks every section set for a task measuring `metrics`; the error
    /// names the key.
    pub(crate) fn validate(&self, metrics: &[&str]) -> std::result::Result<(), String> {
        for (name, table) in &self.0 {
            let s = section(name).ok_or_else(|| unknown(name))?;
            (s.validate)(table, metrics)?;
        }
        Ok(())
    }

    /// Every registered section at its defaults, for the config reference.
    pub fn documented() -> Vec<(&'static str, toml::Table)> {
        let none = Sections::default();
        (registered().iter())
            .filter_map(|s| Some((s.section, none.full(s).ok()?)))
            .collect()
    }
}

impl PartialEq for Sections {
    fn eq(&self, other: &Self) -> bool {
        let same = |s: &Settings| self.full(s) == other.full(s);
        // Sections no longer registered (none, as configs are read) as written.
        let stray = |m: &Sections| (m.0.iter()).filter(|(k, _)| section(k).is_none()).count();
        registered().iter().all(same) && stray(self) == 0 && stray(other) == 0
    }
}

/// What serde says of a key of `[strategy]` that is neither a field nor a
/// registered section.
fn unknown(name: &str) -> String {
    let names: Vec<String> = (FIELDS.iter().copied())
        .chain(registered().iter().map(|s| s.section))
        .map(|n| format!("`{n}`"))
        .collect();
    format!(
        "unknown field `{name}`, expected one of {}",
        names.join(", ")
    )
}

impl<'de> Deserialize<'de> for Sections {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        use serde::de::Error as _;
        let written = BTreeMap::<String, toml::Value>::deserialize(d)?;
        let mut out = BTreeMap::new();
        for (name, value) in written {
            let s = section(&name).ok_or_else(|| D::Error::custom(unknown(&name)))?;
            let toml::Value::Table(table) = value else {
                let why = format!("strategy.{name}: expected a table of settings");
                return Err(D::Error::custom(why));
            };
            (s.read)(&table).map_err(D::Error::custom)?;
            out.insert(name, table);
        }
        Ok(Sections(out))
    }
}

/// Every registered section's schema, as properties of `[strategy]`.
impl JsonSchema for Sections {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "StrategySections".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let mut properties = serde_json::Map::new();
        for s in registered() {
            properties.insert(s.section.into(), (s.schema)(generator).to_value());
        }
        schemars::json_schema!({ "type": "object", "properties": properties })
    }
}

/// The built-in fields in order, then each registered section the config
/// sets or its strategy reads, with every key.
impl Serialize for StrategyConfig {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::Error as _;
        let own = (entries().into_iter())
            .find(|e| e.kind == self.kind.name())
            .and_then(|e| e.settings);
        let mut written = Vec::new();
        for s in registered() {
            let ours = own.is_some_and(|o| o.section == s.section);
            if ours || self.sections.0.contains_key(s.section) {
                written.push((s.section, self.sections.full(&s).map_err(S::Error::custom)?));
            }
        }
        let mut out =
            serializer.serialize_struct("StrategyConfig", FIELDS.len() + written.len())?;
        out.serialize_field("kind", &self.kind)?;
        out.serialize_field("behaviour", &self.behaviour)?;
        out.serialize_field("novelty", &self.novelty)?;
        out.serialize_field("map_elites", &self.map_elites)?;
        out.serialize_field("nsga2", &self.nsga2)?;
        for (name, table) in &written {
            out.serialize_field(name, table)?;
        }
        out.end()
    }
}

/// The settings `T` of a section as written (keys left out take their defaults).
pub(crate) fn parse_section<T: StrategySettings>(
    table: &toml::Table,
) -> std::result::Result<T, String> {
    toml::Value::Table(table.clone())
        .try_into()
        .map_err(|e| format!("strategy.{}: {}", T::SECTION, one_line(&e.to_string())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    /// A registered strategy with a settings section (the first there is).
    fn with_section() -> (&'static str, Settings) {
        let e = (entries().into_iter())
            .find(|e| e.settings.is_some())
            .expect("a strategy registers a settings section");
        (e.kind, e.settings.unwrap())
    }

    #[test]
    fn only_a_strategy_that_reads_a_section_writes_it_whole() {
        let (kind, s) = with_section();
        // Another strategy's config is written as it always was: the five fields.
        let mut c = Config::default();
        StrategyConfig::update(&mut c, |s| s.kind = "novelty".into());
        let text = c.to_toml();
        assert!(
            !text.contains(&format!("[strategy.{}]", s.section)),
            "{text}"
        );
        assert_eq!(Config::from_toml(&text).unwrap(), c);
        // Its own strategy's: the section with every key, at its defaults.
        StrategyConfig::update(&mut c, |s| s.kind = kind.into());
        let text = c.to_toml();
        let defaults = toml::to_string(&Sections::default().full(&s).unwrap()).unwrap();
        let section = format!("[strategy.{}]\n{defaults}", s.section);
        assert!(text.contains(&section), "{text}");
        let back = Config::from_toml(&text).unwrap();
        assert_eq!(back, c);
        assert!(StrategyConfig::of(&back).sections.0.contains_key(s.section));
        assert!(!StrategyConfig::of(&back).is_default());
        // A section at its defaults for a config of NEAT is no setting.
        let mut neat = back;
        StrategyConfig::update(&mut neat, |s| s.kind = "neat".into());
        assert!(StrategyConfig::of(&neat).is_default());
    }

    #[test]
    fn unknown_keys_of_the_strategy_section_are_refused_by_name() {
        let (_, s) = with_section();
        // The config reads `[strategy]` by its registration (the shared
        // rules alone keep it as written).
        let e = crate::tasks::config_from_toml("[strategy]\nknd = \"neat\"\n").unwrap_err();
        assert!(e.message.contains("unknown field `knd`"), "{}", e.message);
        assert!(
            e.message.contains(&format!("`{}`", s.section)),
            "{}",
            e.message
        );
        let text = format!("[strategy.{}]\nno_such_key = 1\n", s.section);
        let e = crate::tasks::config_from_toml(&text).unwrap_err();
        assert!(e.message.contains("no_such_key"), "{}", e.message);
        let text = format!("[strategy]\n{} = 3\n", s.section);
        let e = crate::tasks::config_from_toml(&text).unwrap_err();
        assert!(e.message.contains("expected a table"), "{}", e.message);
    }

    #[test]
    fn a_section_name_is_registered_once() {
        let (_, s) = with_section();
        let holder = (entries().into_iter())
            .find(|e| e.settings.is_some())
            .unwrap();
        static TWIN: std::sync::OnceLock<crate::search::StrategyEntry> = std::sync::OnceLock::new();
        let twin = TWIN.get_or_init(|| crate::search::StrategyEntry {
            kind: "twin-of-a-sectioned-strategy",
            variant: "TwinOfASectionedStrategy",
            settings: Some(s),
            ..clone_entry(holder)
        });
        let e = crate::search::register(twin).unwrap_err();
        assert!(e.contains(&format!("[strategy.{}]", s.section)), "{e}");
    }

    /// A copy of `e`'s fields.
    fn clone_entry(e: &crate::search::StrategyEntry) -> crate::search::StrategyEntry {
        crate::search::StrategyEntry {
            kind: e.kind,
            needs: e.needs,
            takes_population: e.takes_population,
            variant: e.variant,
            from_state: e.from_state,
            extra_columns: e.extra_columns,
            build: e.build,
            header_line: e.header_line,
            report: e.report,
            files: e.files,
            settings: e.settings,
        }
    }
}

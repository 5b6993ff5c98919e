//! The sections a task owns beside the shared ones (a task's own robot
//! model, its opponents): the task declares the section's type
//! ([`OwnedSection`]) and registers it with its entry ([`Section::of`]);
//! the config holds each as its table ([`OwnedSections`]: every key, left
//! out while at its defaults), which the task reads and writes typed.
//!
//! The config knows no task: a config file's tables that are not shared
//! sections are kept as written until they are settled against the
//! registered sections ([`settle`]), which reads each by its type and
//! refuses the others by name.

use schemars::JsonSchema;
use serde::de::{DeserializeOwned, IgnoredAny, MapAccess, Visitor};
use serde::{Deserialize, Serialize};

use super::ConfigError;
use super::toml_error::{describe_toml_error, merge, one_line};

/// The type of a section a task owns: plain data with its defaults.
pub trait OwnedSection:
    Serialize + DeserializeOwned + Default + PartialEq + JsonSchema + 'static
{
    /// Its table's name in a config file (`[NAME]`).
    const NAME: &'static str;
}

/// The owned sections a config sets, by name: each with every key (or as
/// a config file wrote it, until settled); a section at its defaults is
/// left out.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OwnedSections(toml::Table);

impl OwnedSections {
    /// Section `T` as set (keys left out at the defaults of `T`, also in
    /// its sub-tables; all of them when the section is); the error names the
    /// section.
    pub fn get<T: OwnedSection>(&self) -> Result<T, String> {
        let Some(table) = self.0.get(T::NAME) else {
            return Ok(T::default());
        };
        let bad =
            |e: &dyn std::fmt::Display| format!("[{}]: {}", T::NAME, one_line(&e.to_string()));
        // Over the defaults of `T`, whose sub-tables may be types of their
        // own with other defaults (`[strategy.novelty]`).
        let mut full = toml::Value::try_from(T::default()).map_err(|e| bad(&e))?;
        merge(&mut full, table.clone());
        full.try_into()
            .map_err(|e: toml::de::Error| bad(&e.message()))
    }

    /// Section `T` as set, its defaults when it cannot be read: for a config
    /// that has been checked ([`settle`] or the task's check reads it first).
    pub fn of<T: OwnedSection>(&self) -> T {
        self.get().unwrap_or_default()
    }

    /// Sets section `T` to `value` (left out when that is its defaults).
    pub fn set<T: OwnedSection>(&mut self, value: &T) {
        if *value == T::default() {
            self.0.remove(T::NAME);
            return;
        }
        match toml::Value::try_from(value) {
            Ok(table @ toml::Value::Table(_)) => {
                self.0.insert(T::NAME.to_string(), table);
            }
            // A section type is a struct of plain values: always a table.
            _ => unreachable!("section [{}] is a table", T::NAME),
        }
    }

    /// Changes section `T` by `change`.
    pub fn update<T: OwnedSection>(&mut self, change: impl FnOnce(&mut T)) {
        let mut value = self.of::<T>();
        change(&mut value);
        self.set(&value);
    }

    /// The names of the sections set, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.0.keys().map(String::as_str)
    }

    /// Each section set, by name, in order.
    pub(super) fn iter(&self) -> impl Iterator<Item = (&String, &toml::Value)> {
        self.0.iter()
    }

    /// Section `name` as held, if set.
    pub fn raw(&self, name: &str) -> Option<&toml::Value> {
        self.0.get(name)
    }

    /// Keeps `value` as section `name`, as written.
    pub(super) fn insert(&mut self, name: String, value: toml::Value) {
        self.0.insert(name, value);
    }
}

/// A section as a task registers it: [`Section::of`] an [`OwnedSection`] type.
#[derive(Clone, Copy)]
pub struct Section {
    /// Its table's name.
    pub name: &'static str,
    /// Rewrites the section in a config's owned sections with every key (or
    /// leaves it out at its defaults); the error names the section.
    pub settle: fn(&mut OwnedSections) -> Result<(), String>,
    /// Reads the section as a config file's text writes it; the error names
    /// the line and the key.
    pub check_text: fn(&str) -> Result<(), ConfigError>,
    /// The section at its defaults, for the config reference.
    pub defaults: fn() -> toml::Table,
    /// The section's JSON schema with its definitions (its doc comments,
    /// for the config reference).
    pub schema: fn() -> schemars::Schema,
}

impl Section {
    /// The registration of section type `T`.
    pub const fn of<T: OwnedSection>() -> Section {
        Section {
            name: T::NAME,
            settle: settle_section::<T>,
            check_text: check_text::<T>,
            defaults: defaults::<T>,
            schema: schema::<T>,
        }
    }
}

impl std::fmt::Debug for Section {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Section").field("name", &self.name).finish()
    }
}

/// Settles every section of `owned` by its registration in `sections`,
/// refusing the ones none registers (naming the shared sections and the
/// registered ones).
pub fn settle(owned: &mut OwnedSections, sections: &[Section]) -> Result<(), String> {
    check_names(owned, sections)?;
    sections.iter().try_for_each(|s| (s.settle)(owned))
}

/// Refuses the sections of `owned` that no entry of `sections` registers.
pub fn check_names(owned: &OwnedSections, sections: &[Section]) -> Result<(), String> {
    let stray = owned
        .names()
        .find(|n| !sections.iter().any(|s| s.name == *n));
    match stray {
        None => Ok(()),
        Some(name) => {
            let names: Vec<String> = (super::form::FIELDS.iter().copied())
                .chain(sections.iter().map(|s| s.name))
                .map(|n| format!("`{n}`"))
                .collect();
            Err(format!(
                "unknown field `{name}`, expected one of {}",
                names.join(", ")
            ))
        }
    }
}

/// `e` (an unknown section's) at the line of `text` that opens the table it
/// names.
pub(super) fn at_line_of_table(e: ConfigError, text: &str) -> ConfigError {
    let name = e.message.split('`').nth(1).unwrap_or_default();
    let opens = |line: &str| {
        let header = line.trim().trim_start_matches('[');
        header.split([']', '.']).next().map(str::trim) == Some(name)
    };
    match text
        .lines()
        .position(|l| l.trim().starts_with('[') && opens(l))
    {
        Some(i) if e.message.starts_with("unknown field") => {
            ConfigError::new(format!("line {}: key {name}: {}", i + 1, e.message))
        }
        _ => e,
    }
}

/// [`Section::settle`] of `T`.
fn settle_section<T: OwnedSection>(owned: &mut OwnedSections) -> Result<(), String> {
    let value = owned.get::<T>()?;
    owned.set(&value);
    Ok(())
}

/// [`Section::defaults`] of `T`.
fn defaults<T: OwnedSection>() -> toml::Table {
    match toml::Value::try_from(T::default()) {
        Ok(toml::Value::Table(t)) => t,
        _ => unreachable!("section [{}] is a table", T::NAME),
    }
}

/// [`Section::schema`] of `T`.
fn schema<T: OwnedSection>() -> schemars::Schema {
    schemars::schema_for!(T)
}

/// [`Section::check_text`] of `T`: the strict parse of its table alone, so
/// that an error says where the text is wrong.
fn check_text<T: OwnedSection>(text: &str) -> Result<(), ConfigError> {
    toml::from_str::<Only<T>>(text)
        .map(|_| ())
        .map_err(|e| describe_toml_error(text, &e))
}

/// Section `T` of a config file's text, every other table skipped.
struct Only<T>(std::marker::PhantomData<T>);

impl<'de, T: OwnedSection> Deserialize<'de> for Only<T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Tables<T>(std::marker::PhantomData<T>);
        impl<'de, T: OwnedSection> Visitor<'de> for Tables<T> {
            type Value = Only<T>;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a config's tables")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Only<T>, A::Error> {
                while let Some(key) = map.next_key::<String>()? {
                    if key == T::NAME {
                        map.next_value::<T>()?;
                    } else {
                        map.next_value::<IgnoredAny>()?;
                    }
                }
                Ok(Only(std::marker::PhantomData))
            }
        }
        d.deserialize_map(Tables(std::marker::PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A section of a made-up task.
    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
    #[serde(deny_unknown_fields, default)]
    struct Gait {
        /// Legs.
        legs: u32,
        /// Whether it hops.
        hops: bool,
    }

    impl Default for Gait {
        fn default() -> Self {
            Gait {
                legs: 4,
                hops: false,
            }
        }
    }

    impl OwnedSection for Gait {
        const NAME: &'static str = "gait";
    }

    const GAIT: Section = Section::of::<Gait>();

    /// The table of TOML `text`.
    fn table(text: &str) -> toml::Value {
        toml::Value::Table(text.parse().unwrap())
    }

    #[test]
    fn a_section_is_kept_whole_and_left_out_at_its_defaults() {
        let mut owned = OwnedSections::default();
        owned.set(&Gait::default());
        assert_eq!(owned.names().count(), 0);
        owned.update(|g: &mut Gait| g.hops = true);
        assert_eq!(owned.names().collect::<Vec<_>>(), ["gait"]);
        let table = owned.0["gait"].as_table().unwrap();
        assert_eq!(table.len(), 2, "{table:?}");
        assert!(owned.of::<Gait>().hops);
    }

    #[test]
    fn settling_fills_in_the_keys_and_refuses_strays_by_name() {
        let mut owned = OwnedSections::default();
        owned.insert("gait".into(), table("legs = 6"));
        settle(&mut owned, &[GAIT]).unwrap();
        assert_eq!(
            owned.of::<Gait>(),
            Gait {
                legs: 6,
                hops: false
            }
        );
        assert_eq!(owned.0["gait"].as_table().unwrap().len(), 2);
        owned.insert("gait".into(), table("legs = 4"));
        settle(&mut owned, &[GAIT]).unwrap();
        assert_eq!(owned, OwnedSections::default());
        owned.insert("gaits".into(), table("legs = 4"));
        let e = settle(&mut owned, &[GAIT]).unwrap_err();
        assert!(
            e.starts_with("unknown field `gaits`, expected one of `experiment`"),
            "{e}"
        );
        assert!(e.ends_with("`gait`"), "{e}");
        let mut owned = OwnedSections::default();
        owned.insert("gait".into(), table("legs = \"six\""));
        let e = settle(&mut owned, &[GAIT]).unwrap_err();
        assert!(e.starts_with("[gait]: "), "{e}");
    }

    #[test]
    fn a_bad_key_in_the_text_is_named_with_its_line() {
        let text = "[experiment]\nseed = 3\n\n[gait]\nlegs = 2\nhop = true\n";
        let e = (GAIT.check_text)(text).unwrap_err();
        assert!(e.message.starts_with("line 6: "), "{}", e.message);
        assert!(e.message.contains("gait.hop"), "{}", e.message);
        (GAIT.check_text)("[gait]\nlegs = 2\n[neat]\nx = 1\n").unwrap();
    }
}

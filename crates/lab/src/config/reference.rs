//! The config reference, read from the doc comments of the fields the keys set:
//! `vivae config default`, `vivae config reference` and docs/reference/config.md.

use super::*;

impl Config {
    /// The default config as TOML with a comment on every section and key,
    /// the sections tasks own (`sections`) last.
    pub fn default_commented(sections: &[Section]) -> String {
        commented(reference(sections))
    }

    /// [`Config::default_commented`] of one task: the config `self` (its
    /// defaults) with, of the shared sections a robot task reads, only
    /// `reads`, and the owned sections `sections` (the strategies' and the
    /// task's own).
    pub fn default_commented_for(&self, reads: &[SharedSection], sections: &[Section]) -> String {
        commented(reference_of(self, reads, sections))
    }

    /// A Markdown table of every key (the sections tasks own, `sections`,
    /// last): name, default, unit, paper's value, meaning.
    pub fn markdown_reference(sections: &[Section]) -> String {
        markdown_table(reference(sections).iter().flat_map(|s| &s.keys))
    }

    /// The config reference as a whole Markdown page (docs/reference/config.md):
    /// what the file is, then one section per TOML table with its keys'
    /// table (the sections tasks own, `owned`, last), each top-level section
    /// saying which tasks read it (`read_by` of its name, e.g. `every task`).
    pub fn markdown_reference_page(owned: &[Section], read_by: &dyn Fn(&str) -> String) -> String {
        let sections = reference(owned);
        let mut out = String::from(
            "# Config reference\n\n\
             Every key of a run's config file (TOML), generated from the doc comments of \
             the parameter structs, the one place each key is documented: \
             `vivae config reference` prints this page, `scripts/update-reference.sh` \
             rewrites it, and a test fails while the two differ. \
             `vivae config default` prints the default config with a comment on every key; \
             `vivae config check FILE` prints a file fully resolved.\n\n\
             Keys left out take their defaults, and command-line flags override the file \
             (see [the command-line reference](cli.md)). \
             In the tables, *default* is the value as TOML (*unset*: the key is absent \
             unless set), *unit* its unit when it has one, and *paper* the value of the \
             published experiment where it gives one.\n\n",
        );
        out.push_str("| section | what it holds | read by |\n| --- | --- | --- |\n");
        // A sub-section is read by the tasks that read its section.
        let readers = |path: &str| read_by(path.split('.').next().unwrap_or(path));
        for section in &sections {
            let _ = writeln!(
                out,
                "| [`[{}]`](#{}) | {} | {} |",
                section.path,
                heading_anchor(&section.path),
                markdown_cell(&section.what),
                readers(&section.path)
            );
        }
        for section in &sections {
            let _ = write!(out, "\n## `[{}]`\n\n", section.path);
            if !section.what.is_empty() {
                let _ = write!(out, "{}\n\n", section.what);
            }
            if !section.path.contains('.') {
                let _ = write!(out, "Read by {}.\n\n", readers(&section.path));
            }
            if section.keys.is_empty() {
                out.push_str("No keys of its own: its sub-sections follow.\n");
            } else {
                out.push_str(&markdown_table(&section.keys));
            }
        }
        out
    }
}

/// A config's sections `docs` as TOML with a comment on every section and key.
fn commented(docs: Vec<SectionDoc>) -> String {
    let mut out = String::from(
        "# vivae configuration: every parameter of a run.\n\
         # Keys left out take their defaults; command-line flags override the file.\n\
         # Each comment gives: what the key is [unit]; its default; the paper's value where it has one.\n",
    );
    for section in docs {
        let _ = writeln!(out, "\n# {}", section.what);
        let _ = writeln!(out, "[{}]", section.path);
        for key in &section.keys {
            let _ = writeln!(out, "# {}", key.comment());
            let name = key.name();
            match &key.default {
                Some(value) => {
                    let _ = writeln!(out, "{name} = {value}");
                }
                // A key unset by default is shown commented out, with an example.
                None => {
                    let _ = writeln!(out, "# {name} = {}", key.example);
                }
            }
        }
    }
    out
}

/// The Markdown table of `keys`: name, default, unit, paper's value, meaning.
fn markdown_table<'a>(keys: impl IntoIterator<Item = &'a KeyDoc>) -> String {
    let mut out = String::from(
        "| key | default | unit | paper | meaning |\n| --- | --- | --- | --- | --- |\n",
    );
    for key in keys {
        let default = match &key.default {
            Some(value) => format!("`{value}`"),
            None => "unset".to_string(),
        };
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} |",
            key.key,
            markdown_cell(&default),
            markdown_cell(&key.unit),
            markdown_cell(&key.paper),
            markdown_cell(&key.what)
        );
    }
    out
}

/// The anchor GitHub and mdBook give the heading `` `[path]` ``: its letters,
/// digits, `-` and `_`, lower case (the dots and brackets dropped).
fn heading_anchor(path: &str) -> String {
    path.chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_')
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

/// A table cell's text: a `|` would end the cell, so it is escaped.
pub(super) fn markdown_cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// Documentation of one config key, read from the doc comment of the field it sets.
///
/// A field's doc comment is its meaning, optionally followed by a paragraph of
/// notes: `Unit: px/step.`, `Paper: 100.` (the paper's value) and, for a key
/// that is unset by default, `Example: 10.` (the value `vivae config default`
/// shows commented out).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyDoc {
    /// Dotted key, e.g. `neat.population_size`.
    pub key: String,
    /// What the key is: the doc comment without its notes, lower-case first, no final period.
    pub what: String,
    /// Unit, empty when dimensionless.
    pub unit: String,
    /// The paper's value, empty when the paper gives none.
    pub paper: String,
    /// The default as TOML; `None` when the key is unset by default.
    pub default: Option<String>,
    /// A value to show for a key that is unset by default; empty otherwise.
    pub example: String,
}

impl KeyDoc {
    /// The key's name within its section.
    pub fn name(&self) -> &str {
        self.key.rsplit('.').next().unwrap_or(&self.key)
    }

    /// One line: what the key is [unit]; default: D; paper: P.
    pub fn comment(&self) -> String {
        let mut parts = vec![if self.unit.is_empty() {
            self.what.clone()
        } else {
            format!("{} [{}]", self.what, self.unit)
        }];
        parts.push(format!(
            "default: {}",
            self.default.as_deref().unwrap_or("unset")
        ));
        if !self.paper.is_empty() {
            parts.push(format!("paper: {}", self.paper));
        }
        parts.join("; ")
    }
}

/// Documentation of one config section (a TOML table) and of its keys.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SectionDoc {
    /// Dotted path of the table, e.g. `physics.friction`.
    pub path: String,
    /// What the section holds: the doc comment of the field that holds it.
    pub what: String,
    /// Its keys: those set by default in declaration order, then those unset by default.
    pub keys: Vec<KeyDoc>,
}

/// Every section and key of the config, documented from the doc comments of
/// the fields they set, the sections tasks own (`sections`, which the lab's
/// registries give) last: the one source of `vivae config default`, `vivae
/// config reference` and docs/reference/config.md.
pub fn reference(sections: &[Section]) -> Vec<SectionDoc> {
    reference_of(&Config::default(), &SharedSection::ALL, sections)
}

/// [`reference`] at the defaults of `base` (a task's default config), with
/// of the shared sections only `reads`.
fn reference_of(base: &Config, reads: &[SharedSection], sections: &[Section]) -> Vec<SectionDoc> {
    let schema = schemars::schema_for!(Config);
    let root = schema.as_value();
    let mut defaults = documented_defaults_of(base, sections);
    if let Some(table) = defaults.as_table_mut() {
        table.retain(|name, _| SharedSection::named(name).is_none_or(|s| reads.contains(&s)));
    }
    let defaults = defaults.as_table().expect("the config is a table");
    let mut out = Vec::new();
    for (name, value) in defaults {
        let table = value.as_table().expect("every top-level key is a section");
        match sections.iter().find(|s| s.name == name) {
            Some(s) => {
                let mut own = (s.schema)();
                // The root schema's title is the type's name; the doc is the description.
                (own.as_object_mut()).map(|o| o.remove("title"));
                let own = own.as_value();
                document_section(own, own, name, table, &mut out);
            }
            None => document_section(root, property(root, root, name), name, table, &mut out),
        }
    }
    out
}

/// The default config as the reference documents it: keys a default config
/// does not write (`substrate.kind`, `[substrate.es]`, `[fitness]`: written only when
/// set, so that existing runs' files stay the same) with their defaults all the
/// same, and the sections the strategies and tasks own (`sections`, each
/// documented by its registration; `[strategy]` after `[run]`, where it is written).
#[cfg(test)]
pub(super) fn documented_defaults(sections: &[Section]) -> toml::Value {
    documented_defaults_of(&Config::default(), sections)
}

/// [`documented_defaults`] of the config `base`: an owned section it sets
/// as it sets it.
fn documented_defaults_of(base: &Config, sections: &[Section]) -> toml::Value {
    let mut defaults = toml::Value::try_from(base).expect("the config is TOML");
    if let Some(sub) = defaults.get_mut("substrate").and_then(|s| s.as_table_mut()) {
        let kind = toml::Value::try_from(SubstrateKind::default()).expect("a kind is TOML");
        let mut es = toml::Value::try_from(EsConfig::default()).expect("ES keys are TOML");
        // `leo` and `leo_seed` are written only when true; documented all the same.
        if let Some(t) = es.as_table_mut() {
            t.insert("leo".into(), toml::Value::Boolean(false));
            t.insert("leo_seed".into(), toml::Value::Boolean(false));
        }
        sub.insert("kind".into(), kind);
        sub.insert("es".into(), es);
    }
    // Keys written only when changed (so that existing runs' config files
    // and checksums stay the same), documented at their defaults.
    if let Some(neat) = defaults.get_mut("neat").and_then(|s| s.as_table_mut()) {
        neat.insert("start_hidden".into(), toml::Value::Integer(0));
    }
    // The owned sections are written only when set; documented all the same.
    let (strategy, owned): (Vec<&Section>, Vec<&Section>) = sections
        .iter()
        .partition(|s| s.name == super::form::STRATEGY);
    if let Some(table) = defaults.as_table_mut() {
        let set = |s: &Section| {
            (base.owned.raw(s.name).cloned()).unwrap_or_else(|| toml::Value::Table((s.defaults)()))
        };
        for s in strategy {
            table.insert(s.name.into(), set(s));
        }
        let opponent = toml::Value::try_from(OpponentConfig::default()).expect("TOML");
        table.insert("opponent_sensors".into(), opponent);
        for s in owned {
            table.insert(s.name.into(), set(s));
        }
    }
    defaults
}

/// Documentation of the key `key` (dotted), if there is such a key among
/// the shared sections and `sections`.
pub fn key_doc(key: &str, sections: &[Section]) -> Option<KeyDoc> {
    reference(sections)
        .into_iter()
        .flat_map(|s| s.keys)
        .find(|k| k.key == key)
}

/// Documents the section at `path` whose schema is `schema` and whose defaults are `defaults`,
/// then its sub-sections.
pub(super) fn document_section(
    root: &serde_json::Value,
    schema: &serde_json::Value,
    path: &str,
    defaults: &toml::Table,
    out: &mut Vec<SectionDoc>,
) {
    let what = ParsedDoc::new(&description(schema)).what;
    let body = resolve(root, schema);
    let mut keys = Vec::new();
    let mut sections = Vec::new();
    // The defaults list the keys in declaration order (serde serialises fields in order).
    for (name, value) in defaults {
        let field = property(root, body, name);
        match value {
            toml::Value::Table(table) => sections.push((name, field, table)),
            value => keys.push(
                ParsedDoc::new(&description(field))
                    .key(format!("{path}.{name}"), Some(value.to_string())),
            ),
        }
    }
    // Keys the serialised default leaves out are `Option`s that are unset by default.
    if let Some(properties) = body.get("properties").and_then(|p| p.as_object()) {
        for (name, field) in properties {
            if !defaults.contains_key(name) {
                keys.push(ParsedDoc::new(&description(field)).key(format!("{path}.{name}"), None));
            }
        }
    }
    out.push(SectionDoc {
        path: path.to_string(),
        what,
        keys,
    });
    for (name, field, table) in sections {
        document_section(root, field, &format!("{path}.{name}"), table, out);
    }
}

/// The schema of property `name` of the object schema `object`; `null` when absent.
pub(super) fn property<'a>(
    root: &'a serde_json::Value,
    object: &'a serde_json::Value,
    name: &str,
) -> &'a serde_json::Value {
    resolve(root, object)
        .get("properties")
        .and_then(|p| p.get(name))
        .unwrap_or(&serde_json::Value::Null)
}

/// Follows `$ref` (directly or as the single entry of an `allOf`) into the root's definitions.
pub(super) fn resolve<'a>(
    root: &'a serde_json::Value,
    schema: &'a serde_json::Value,
) -> &'a serde_json::Value {
    let reference = schema.get("$ref").or_else(|| {
        schema
            .get("allOf")
            .and_then(|a| a.as_array())
            .filter(|a| a.len() == 1)
            .and_then(|a| a[0].get("$ref"))
    });
    match reference.and_then(|r| r.as_str()) {
        Some(r) => r
            .strip_prefix("#/")
            .and_then(|pointer| root.pointer(&format!("/{pointer}")))
            .map(|target| resolve(root, target))
            .unwrap_or(schema),
        None => schema,
    }
}

/// A schema's doc text: its title (a doc comment's `#` heading) and description.
pub(super) fn description(schema: &serde_json::Value) -> String {
    ["title", "description"]
        .iter()
        .filter_map(|k| schema.get(*k).and_then(|v| v.as_str()))
        .collect::<Vec<_>>()
        .join("\n\n")
}

/// A doc comment split into its meaning and its notes.
#[derive(Debug, Default, PartialEq)]
pub(super) struct ParsedDoc {
    pub(super) what: String,
    pub(super) unit: String,
    pub(super) paper: String,
    pub(super) example: String,
}

/// The notes a doc comment may end with.
const NOTES: [&str; 3] = ["Unit:", "Paper:", "Example:"];

impl ParsedDoc {
    pub(super) fn new(doc: &str) -> ParsedDoc {
        let mut parsed = ParsedDoc::default();
        let mut what = Vec::new();
        for paragraph in doc.split("\n\n") {
            let paragraph = paragraph.split_whitespace().collect::<Vec<_>>().join(" ");
            if NOTES.iter().any(|n| paragraph.starts_with(n)) {
                parsed.read_notes(&paragraph);
            } else if !paragraph.is_empty() {
                what.push(paragraph);
            }
        }
        parsed.what = what.join(" ");
        parsed
    }

    /// Reads `Unit: u. Paper: p. Example: e.` (any order, any subset).
    fn read_notes(&mut self, text: &str) {
        let mut starts: Vec<(usize, &str)> = NOTES
            .iter()
            .filter_map(|n| text.find(n).map(|at| (at, *n)))
            .collect();
        starts.sort();
        for (i, &(at, note)) in starts.iter().enumerate() {
            let end = starts.get(i + 1).map_or(text.len(), |&(next, _)| next);
            let value = text[at + note.len()..end].trim();
            let value = value.strip_suffix('.').unwrap_or(value).to_string();
            match note {
                "Unit:" => self.unit = value,
                "Paper:" => self.paper = value,
                _ => self.example = value,
            }
        }
    }

    fn key(self, key: String, default: Option<String>) -> KeyDoc {
        KeyDoc {
            key,
            what: sentence_fragment(&self.what),
            unit: self.unit,
            paper: self.paper,
            default,
            example: self.example,
        }
    }
}

/// A doc sentence as a fragment for a one-line comment: first word lower-case
/// (unless it is an acronym or symbol such as `CPPN`, `C1` or `C_ACT`), no final period.
pub(super) fn sentence_fragment(text: &str) -> String {
    let text = text.strip_suffix('.').unwrap_or(text);
    let word = text
        .split_whitespace()
        .next()
        .unwrap_or("")
        .trim_end_matches([':', ',', ';']);
    let mut chars = word.chars();
    match chars.next() {
        Some(first) if first.is_uppercase() && chars.all(|c| c.is_lowercase()) => first
            .to_lowercase()
            .chain(text[first.len_utf8()..].chars())
            .collect(),
        _ => text.to_string(),
    }
}

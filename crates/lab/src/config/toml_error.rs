//! TOML parse errors as one line naming the line and the key.

use super::*;

/// `text` on one line.
pub(super) fn one_line(text: &str) -> String {
    text.trim().replace('\n', " ")
}

/// Turns a toml parse error into one line: `line L: key K: reason`.
pub(super) fn describe_toml_error(text: &str, err: &toml::de::Error) -> ConfigError {
    let reason = err.message().trim().replace('\n', " ");
    let Some(span) = err.span() else {
        return ConfigError::new(reason);
    };
    let line_no = text[..span.start.min(text.len())].matches('\n').count() + 1;
    let key = key_at(text, span.start);
    match key {
        Some(key) => ConfigError::new(format!("line {line_no}: key {key}: {reason}")),
        None => ConfigError::new(format!("line {line_no}: {reason}")),
    }
}

/// The 1-based line that assigns dotted key `key` (`section.name`) in `text`, if any.
pub(super) fn line_of_key(text: &str, key: &str) -> Option<usize> {
    let (section, name) = key.rsplit_once('.')?;
    let mut current = "";
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(header) = trimmed.strip_prefix('[') {
            current = header.split(']').next().unwrap_or("").trim();
        } else if current == section
            && trimmed.split('=').next().map(str::trim) == Some(name)
            && trimmed.contains('=')
        {
            return Some(i + 1);
        }
    }
    None
}

/// The dotted key whose assignment contains byte offset `pos`, if any.
pub(super) fn key_at(text: &str, pos: usize) -> Option<String> {
    let mut section = String::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim();
        let end = offset + line.len();
        if let Some(header) = trimmed.strip_prefix('[') {
            let name = header
                .trim_start_matches('[')
                .split(']')
                .next()
                .unwrap_or("")
                .trim();
            if pos >= offset && pos < end {
                return Some(name.to_string());
            }
            section = name.to_string();
        } else if pos >= offset
            && pos < end
            && let Some((key, _)) = trimmed.split_once('=')
        {
            let key = key.trim().trim_matches('"');
            return Some(if section.is_empty() {
                key.to_string()
            } else {
                format!("{section}.{key}")
            });
        }
        offset = end;
    }
    (!section.is_empty()).then_some(section)
}

/// `over` laid over `base`: its keys replace the base's, table by table.
pub(super) fn merge(base: &mut toml::Value, over: toml::Value) {
    match (base, over) {
        (toml::Value::Table(b), toml::Value::Table(o)) => {
            for (k, v) in o {
                match b.get_mut(&k) {
                    Some(slot) => merge(slot, v),
                    None => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (slot, v) => *slot = v,
    }
}

/// The config of TOML `text` (which parses) with its unset keys taken from `base`.
pub(super) fn over_defaults(text: &str, base: &Config) -> Result<Config, ConfigError> {
    let bad = |e: &dyn std::fmt::Display| ConfigError::new(one_line(&e.to_string()));
    // A section a task owns that `base` leaves out is at its defaults,
    // which its type fills in when it is read.
    let mut base = toml::Value::try_from(base).map_err(|e| bad(&e))?;
    let over: toml::Value = toml::from_str(text).map_err(|e| bad(&e))?;
    merge(&mut base, over);
    base.try_into().map_err(|e: toml::de::Error| bad(&e))
}

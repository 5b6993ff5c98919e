//! Finding the keys of a config that its task does not read: the first one
//! changed from its default, so a refusal can name it.

use serde::Serialize;

use crate::config::Config;

/// The first key under `key` where `a` (a config or part of one) differs
/// from `b` (its defaults), skipping every key `skip` says is read:
/// (key, its value, the default), `unset` for a missing one.
pub(crate) fn first_change(
    key: &str,
    a: Option<&toml::Value>,
    b: Option<&toml::Value>,
    skip: &dyn Fn(&str) -> bool,
) -> Option<(String, String, String)> {
    if skip(key) {
        return None;
    }
    match (a, b) {
        (Some(toml::Value::Table(x)), Some(toml::Value::Table(y))) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            keys.into_iter().find_map(|k| {
                let sub = if key.is_empty() {
                    k.clone()
                } else {
                    format!("{key}.{k}")
                };
                first_change(&sub, x.get(k), y.get(k), skip)
            })
        }
        (a, b) if a != b => Some((key.to_string(), show(a), show(b))),
        _ => None,
    }
}

/// A value for a message: `unset` for a missing one, a huge or tiny
/// number in scientific notation (TOML would print 1e308's 309 digits).
fn show(v: Option<&toml::Value>) -> String {
    match v {
        None => "unset".into(),
        Some(toml::Value::Float(f))
            if f.is_finite() && *f != 0.0 && !(1e-6..1e9).contains(&f.abs()) =>
        {
            format!("{f:e}")
        }
        Some(v) => v.to_string(),
    }
}

/// Refuses `config`'s section `[section]` (its value `value`) when a key of
/// it differs from `default`: only an `owner` run reads it. The message
/// names the key and its value.
pub(crate) fn refuse_section<T: Serialize>(
    config: &Config,
    section: &str,
    value: &T,
    default: &T,
    owner: &str,
) -> Result<(), String> {
    let toml = |t: &T| toml::Value::try_from(t).ok();
    match first_change(
        section,
        toml(value).as_ref(),
        toml(default).as_ref(),
        &|_| false,
    ) {
        Some((key, value, _)) => Err(format!(
            "{key} = {value}: only a {owner} run reads [{section}] (experiment.task = \"{}\"): drop the section",
            config.experiment.task
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use crate::config::Config;
    use crate::tasks::config_from_toml;

    #[test]
    fn another_tasks_section_is_refused_by_its_first_changed_key() {
        for (task, text, key) in [
            (
                "driving",
                "[coevolution]\nsample = 7\n",
                "coevolution.sample = 7",
            ),
            (
                "maze",
                "[experiment]\ntask = \"maze\"\n[coevolution]\nopponents = \"hall-of-fame\"\n",
                "coevolution.opponents = \"hall-of-fame\"",
            ),
            (
                "predator-prey",
                "[experiment]\ntask = \"predator-prey\"\n[fitness]\ncontact_cost = -1e308\n",
                "fitness.contact_cost = -1e308",
            ),
            (
                "predator-prey",
                "[experiment]\ntask = \"predator-prey\"\n[fitness]\nkind = \"progress\"\n",
                "fitness.kind = \"progress\"",
            ),
            (
                "maze",
                "[experiment]\ntask = \"maze\"\n[fitness]\ncontact_cost = 0.5\n",
                "fitness.contact_cost = 0.5",
            ),
        ] {
            let err = config_from_toml(text).unwrap_err().to_string();
            assert!(err.contains(key), "{task}: {err}");
            assert!(err.contains("only a"), "{task}: {err}");
            assert!(err.contains(&format!("\"{task}\"")), "{task}: {err}");
        }
        // Their own tasks read them.
        config_from_toml("[coevolution]\nsample = 7\n[experiment]\ntask = \"predator-prey\"\n")
            .unwrap();
        config_from_toml("[fitness]\ncontact_cost = 0.5\n").unwrap();
        let c = Config::default();
        let fitness = crate::tasks::driving::section::FitnessConfig::of(&c);
        assert!(super::refuse_section(&c, "fitness", &fitness, &fitness, "driving").is_ok());
    }
}

//! Finding the keys of a config that its task does not read: the first one
//! changed from its default, so a refusal can name it.

use crate::config::{Config, SharedSection};
use crate::tasks::TaskEntry;

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

/// Refuses a key `config` (its owned sections settled) sets in a section
/// its task `task` does not read: a shared section it does not list in
/// [`TaskEntry::reads`] off the task's defaults, or another task's own
/// section (left out of a settled config at its defaults). The one-line
/// message names the key, its value and the tasks that read the section.
pub(crate) fn refuse_unread(config: &Config, task: &TaskEntry) -> Result<(), String> {
    let defaults = (task.default_config)();
    for s in SharedSection::ALL
        .iter()
        .filter(|s| !task.reads.contains(s))
    {
        let readers = |t: &TaskEntry| t.reads.contains(s);
        let (set, default) = (s.value(config), s.value(&defaults));
        refuse_section(config, s.name(), set.as_ref(), default.as_ref(), &readers)?;
    }
    let sections = super::sections();
    for name in config.owned.names().filter(|n| {
        *n != crate::search::SECTION.name && !task.sections.iter().any(|s| s.name == *n)
    }) {
        let default = sections
            .iter()
            .find(|s| s.name == name)
            .map(|s| toml::Value::Table((s.defaults)()));
        let readers = |t: &TaskEntry| t.sections.iter().any(|s| s.name == name);
        let set = config.owned.raw(name);
        refuse_section(config, name, set, default.as_ref(), &readers)?;
    }
    Ok(())
}

/// Refuses `config`'s section `[section]` (`value`) when a key of it
/// differs from `default`: only the tasks `reads` picks read it. The
/// message names the key, its value and those tasks.
fn refuse_section(
    config: &Config,
    section: &str,
    value: Option<&toml::Value>,
    default: Option<&toml::Value>,
    reads: &dyn Fn(&TaskEntry) -> bool,
) -> Result<(), String> {
    let Some((key, value, _)) = first_change(section, value, default, &|_| false) else {
        return Ok(());
    };
    let readers: Vec<&str> = (super::entries().into_iter())
        .filter(|t| reads(t))
        .map(|t| t.name)
        .collect();
    let (who, fix) = match readers.as_slice() {
        [] => (format!("no task reads [{section}]"), String::new()),
        [one] => (
            format!("only {} run reads [{section}]", crate::error::a(one)),
            format!("set `task = \"{one}\"` under [experiment] or "),
        ),
        [first @ .., last] => (
            format!("only {} and {last} runs read [{section}]", first.join(", ")),
            String::new(),
        ),
    };
    Err(format!(
        "{key} = {value}: {who} (experiment.task = \"{}\"): {fix}drop the section",
        config.experiment.task
    ))
}

#[cfg(test)]
mod tests {
    use crate::config::TaskName;
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
    }

    #[test]
    fn a_shared_section_a_task_does_not_read_is_refused_naming_its_readers() {
        let err = config_from_toml("[experiment]\ntask = \"cartpole\"\n[physics]\nv_max = 3.0\n")
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "line 4: physics.v_max = 3.0: only driving, maze and predator-prey runs read [physics] \
             (experiment.task = \"cartpole\"): drop the section"
        );
        // At its defaults (a run's config.toml of the whole form) it is read back.
        let whole = crate::tasks::default_config(Some(&TaskName("cartpole".into())))
            .unwrap()
            .to_toml();
        assert!(whole.contains("\n[physics]\n"), "{whole}");
        config_from_toml(&whole).unwrap();
        let err =
            config_from_toml("[experiment]\ntask = \"cartpole\"\n[maze]\nrobot = \"vivae\"\n")
                .unwrap_err()
                .to_string();
        assert!(
            err.contains("maze.robot = \"vivae\": only a maze run reads [maze]"),
            "{err}"
        );
    }
}

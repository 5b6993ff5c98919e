//! The scenarios shipped with the tasks (each task's entry lists its own,
//! [`super::TaskEntry::scenarios`]), built into the program so that
//! `--scenario NAME` works wherever `vivae` is installed: looking them up by
//! name, and loading a scenario named by a path or a shipped name.

use std::path::Path;

use vivae_sim::{LoadOptions, Scenario};

use crate::error::Result;
use crate::io::{DEFAULT_SCENARIO, DEFAULT_SCENARIO_NAME, LoadedScenario, bad_input, read_text};
use crate::shipped::Shipped;

/// Every shipped scenario, in the order `vivae scenario list` shows them:
/// each registered task's ([`super::TaskEntry::scenarios`]) in turn,
/// `roads` (the default) first.
pub fn all() -> impl Iterator<Item = &'static Shipped> {
    super::entries()
        .into_iter()
        .flat_map(|t| t.scenarios.iter())
}

/// The shipped scenario called `name` (with or without `.svg`), if any.
pub fn find(name: &str) -> Option<&'static Shipped> {
    let name = name.strip_suffix(".svg").unwrap_or(name);
    all().find(|s| s.name == name)
}

/// The task the scenarios `names` are drawn for, when each is a shipped
/// scenario (no file of that name here) and they agree on one task.
pub fn task_of(names: &[String]) -> Option<&'static str> {
    let shipped = |n: &String| {
        let is_file = std::path::Path::new(n).exists();
        (!is_file).then(|| find(n)).flatten()
    };
    let mut tasks = names.iter().map(|n| shipped(n).map(|s| s.task));
    let first = tasks.next()??;
    tasks.all(|t| t == Some(first)).then_some(first)
}

/// A training map named in a config file in folder `base`: a relative path is
/// relative to `base`, but a bare shipped name (`oval`) with no such file
/// there stays a shipped name.
pub fn resolve_map(base: &Path, name: &str) -> String {
    let path = Path::new(name);
    if path.is_absolute() {
        return name.to_string();
    }
    let joined = base.join(path);
    let bare = path.parent() == Some(Path::new(""));
    if bare && !joined.exists() && find(name).is_some() {
        return name.to_string();
    }
    joined.to_string_lossy().into_owned()
}

/// Loads the scenario at `path`, or the embedded default when `path` is `None`;
/// a bare name that is no file, such as `oval`, is a shipped scenario.
pub fn load_scenario(path: Option<&Path>) -> Result<LoadedScenario> {
    let shipped = path
        .filter(|p| !p.exists() && p.parent() == Some(Path::new("")))
        .and_then(|p| find(&p.to_string_lossy()));
    if let Some(p) = path.filter(|p| shipped.is_none() && !p.exists() && p.extension().is_none()) {
        return Err(bad_input(format!(
            "{}: no such file, nor a shipped scenario (see `vivae scenario list`)",
            p.display()
        )));
    }
    let (text, name) = match path {
        _ if shipped.is_some() => {
            let s = shipped.expect("checked");
            (s.svg.to_string(), format!("{}.svg (shipped)", s.name))
        }
        Some(p) => (read_text(p)?, p.display().to_string()),
        None => (
            DEFAULT_SCENARIO.to_string(),
            DEFAULT_SCENARIO_NAME.to_string(),
        ),
    };
    let scenario = Scenario::from_svg(&text, &name, &LoadOptions::default())?;
    Ok(LoadedScenario { scenario, text })
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_sim::{LoadOptions, Scenario};

    #[test]
    fn every_shipped_scenario_loads_without_warnings_and_fits_the_default_experiment() {
        let config = crate::config::Config::default();
        for s in all() {
            let scenario = Scenario::from_svg(s.svg, s.name, &LoadOptions::default())
                .unwrap_or_else(|e| panic!("{}: {e}", s.name));
            assert!(
                scenario.warnings.is_empty(),
                "{}: {:?}",
                s.name,
                scenario.warnings
            );
            if s.task != config.experiment.task.name() {
                // Other tasks' scenarios are checked by their task's tests.
                continue;
            }
            // The default experiment drives the first 5.
            assert!(scenario.robots.len() >= 5, "{}", s.name);
            for r in &scenario.robots {
                let surface = scenario.surface_exact(r.pos).map(|(k, _)| k);
                assert_eq!(
                    surface,
                    Some(vivae_sim::SurfaceKind::Road),
                    "{} {}",
                    s.name,
                    r.id
                );
            }
            crate::tasks::driving::episode::Episode::new(&config, &scenario)
                .unwrap_or_else(|e| panic!("{}: {e}", s.name));
        }
    }

    #[test]
    fn names_resolve_with_or_without_extension() {
        assert_eq!(find("oval").unwrap().name, "oval");
        assert_eq!(find("town.svg").unwrap().name, "town");
        assert!(find("nowhere").is_none());
    }

    #[test]
    fn shipped_scenarios_name_the_task_they_are_drawn_for() {
        let names = |n: &[&str]| n.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(all().next().unwrap().name, "roads", "the default first");
        for task in super::super::TASKS {
            for s in task.scenarios {
                assert_eq!(s.task, task.name, "{}", s.name);
                assert_eq!(task_of(&names(&[s.name])), Some(task.name));
                let file = format!("{}.svg", s.name);
                assert_eq!(task_of(&names(&[file.as_str()])), Some(task.name));
            }
        }
        assert_eq!(task_of(&names(&["oval", "town"])), Some("driving"));
        let pp = "predator-prey";
        assert_eq!(task_of(&names(&["oval", pp])), None, "two tasks");
        assert_eq!(task_of(&names(&["my-arena.svg"])), None, "not shipped");
        assert_eq!(task_of(&[]), None);
    }
}

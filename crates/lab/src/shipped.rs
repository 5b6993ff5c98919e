//! The scenarios shipped in `scenarios/`, built into the program so that
//! `--scenario NAME` works wherever `vivae` is installed. Each task lists
//! the ones drawn for it in its entry ([`crate::tasks::TaskEntry::scenarios`]).

/// A shipped scenario: its name (file name without `.svg`), what it is, its SVG text.
#[derive(Debug, Clone, Copy)]
pub struct Shipped {
    /// Name, e.g. `oval` (the file `scenarios/oval.svg`).
    pub name: &'static str,
    /// One line on what it is.
    pub what: &'static str,
    /// The SVG text.
    pub svg: &'static str,
    /// The task (`experiment.task`) it is drawn for.
    pub task: &'static str,
}

/// Every shipped scenario, in the order `vivae scenario list` shows them:
/// each registered task's ([`crate::tasks::TaskEntry::scenarios`]) in turn,
/// `roads` (the default) first.
pub fn all() -> impl Iterator<Item = &'static Shipped> {
    crate::tasks::entries()
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
        for task in crate::tasks::TASKS {
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

//! The behaviour descriptors tasks offer: what `strategy.behaviour` may
//! name. Each task declares its own with its registration
//! ([`TaskEntry::behaviours`]) and gives a run the space of the one its
//! config names ([`crate::tasks::RunTask::behaviour_space`]); the search
//! layer knows none of their names.

use crate::config::Config;
use crate::config::strategy::BehaviourName;
use crate::search::StrategyConfig;
use crate::tasks::TaskEntry;

/// A behaviour descriptor a task offers (`strategy.behaviour = "its name"`).
#[derive(Debug, Clone, Copy)]
pub struct BehaviourEntry {
    /// Its name in `strategy.behaviour` and `--behaviour`.
    pub name: &'static str,
    /// Its coordinates' names, for a descriptor of `dims` coordinates (the
    /// archive's columns; the viewer's and report's labels).
    pub coordinates: fn(dims: usize) -> Vec<String>,
}

/// [`BehaviourEntry::coordinates`] of a descriptor of a position: `x`, `y`.
pub fn position(_dims: usize) -> Vec<String> {
    vec!["x".into(), "y".into()]
}

/// Refuses a `strategy.behaviour` that `task` does not offer, naming the
/// key, the value and the names it offers; a task that offers none (it has
/// one descriptor of its own, or none) leaves the key at its default.
pub(crate) fn check(config: &Config, task: &TaskEntry) -> std::result::Result<(), String> {
    let name = StrategyConfig::of(config).behaviour;
    let name = name.name();
    if task.behaviours.iter().any(|b| b.name == name) {
        return Ok(());
    }
    if task.behaviours.is_empty() {
        if name == BehaviourName::DEFAULT {
            return Ok(());
        }
        return Err(format!(
            "strategy.behaviour = {name:?}: {} run offers no choice of behaviour descriptor: leave it at {}",
            crate::error::a(task.name),
            BehaviourName::DEFAULT
        ));
    }
    let names: Vec<&str> = task.behaviours.iter().map(|b| b.name).collect();
    Err(format!(
        "strategy.behaviour = {name:?}: {} run offers {}",
        crate::error::a(task.name),
        names.join(", ")
    ))
}

/// The names of the coordinates of `config`'s behaviour descriptors of
/// `dims` coordinates, as its task names them (numbered from 1 where the
/// task offers no choice of descriptor, or its task is not registered).
pub fn coordinate_names(config: &Config, dims: usize) -> Vec<String> {
    let name = StrategyConfig::of(config).behaviour;
    let offered = crate::tasks::entry_of(config)
        .ok()
        .and_then(|t| t.behaviours.iter().find(|b| b.name == name.name()));
    match offered {
        Some(b) => (b.coordinates)(dims),
        None => (1..=dims).map(|i| format!("b{i}")).collect(),
    }
}

/// Every registered task's behaviour descriptors' names, each once, in
/// the registry's order (what `--behaviour` accepts; the task decides which
/// apply).
pub fn names() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = vec![BehaviourName::DEFAULT];
    for b in crate::tasks::entries().iter().flat_map(|t| t.behaviours) {
        if !out.contains(&b.name) {
            out.push(b.name);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(task: &str, behaviour: &str) -> Config {
        let task = crate::tasks::entry(task).unwrap();
        let mut c = (task.default_config)();
        StrategyConfig::update(&mut c, |s| {
            s.kind = "novelty".into();
            s.behaviour = behaviour.into();
        });
        c
    }

    #[test]
    fn a_behaviour_the_task_does_not_offer_is_refused_with_the_names_it_does() {
        for (task, offered) in [("driving", "trajectory"), ("maze", "end-position")] {
            crate::tasks::check(&with(task, offered)).unwrap();
        }
        let why = crate::tasks::check(&with("driving", "speed")).unwrap_err();
        assert_eq!(
            why.to_string(),
            "strategy.behaviour = \"speed\": a driving run offers end-position, end-positions, side-speed, trajectory"
        );
        let why = crate::tasks::check(&with("maze", "side-speed")).unwrap_err();
        assert_eq!(
            why.to_string(),
            "strategy.behaviour = \"side-speed\": a maze run offers end-position"
        );
        // A task with no choice keeps the default, and refuses any other name.
        let mut cartpole = with("cartpole", "trajectory");
        StrategyConfig::update(&mut cartpole, |s| s.kind = "neat".into());
        let why = crate::tasks::check(&cartpole).unwrap_err().to_string();
        assert!(
            why.starts_with("strategy.behaviour = \"trajectory\": a cartpole run offers no choice"),
            "{why}"
        );
    }

    #[test]
    fn the_names_are_every_tasks_each_once_and_coordinates_are_the_tasks() {
        assert_eq!(
            names(),
            ["end-position", "end-positions", "side-speed", "trajectory"]
        );
        let names_of = |task, behaviour, dims| coordinate_names(&with(task, behaviour), dims);
        assert_eq!(names_of("driving", "side-speed", 2), ["side", "speed"]);
        assert_eq!(
            names_of("driving", "end-positions", 4),
            ["x0", "y0", "x1", "y1"]
        );
        assert_eq!(names_of("maze", "end-position", 2), ["x", "y"]);
        // A task with no choice names no coordinates of its own here.
        assert_eq!(names_of("cartpole", "end-position", 2), ["b1", "b2"]);
    }
}

//! The scenarios shipped in `scenarios/`, built into the program so that
//! `--scenario NAME` works wherever `vivae` is installed.

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

/// Every shipped scenario; `roads` is the default. Each names the task it is
/// drawn for.
pub const SHIPPED: [Shipped; 12] = [
    Shipped {
        name: "roads",
        what: "the default: a road loop with a crossroad, a spur and an S-curve (5 robots)",
        svg: vivae_sim::ROADS_SVG,
        task: "driving",
    },
    Shipped {
        name: "oval",
        what: "an oval (stadium) track (5 robots)",
        svg: include_str!("../../../scenarios/oval.svg"),
        task: "driving",
    },
    Shipped {
        name: "town",
        what: "a town grid around four houses with a roundabout (5 robots)",
        svg: include_str!("../../../scenarios/town.svg"),
        task: "driving",
    },
    Shipped {
        name: "figure8",
        what: "a figure-8 track whose loops cross in the middle (5 robots)",
        svg: include_str!("../../../scenarios/figure8.svg"),
        task: "driving",
    },
    Shipped {
        name: "obstacles",
        what: "a road loop with sand, a pond, walls, movable crates and pucks (5 robots)",
        svg: include_str!("../../../scenarios/obstacles.svg"),
        task: "driving",
    },
    Shipped {
        name: "traffic",
        what: "a two-lane road loop driven both ways, with blocks and movable crates on the road (6 robots)",
        svg: include_str!("../../../scenarios/traffic.svg"),
        task: "driving",
    },
    Shipped {
        name: "obstacles-random",
        what: "a road loop whose 8 blocks are placed at random for every episode (5 robots)",
        svg: include_str!("../../../scenarios/obstacles-random.svg"),
        task: "driving",
    },
    Shipped {
        name: "oncoming",
        what: "a two-lane loop with 4 scripted robots driving the other lane the other way, a block in each long side's own lane (5 robots)",
        svg: include_str!("../../../scenarios/oncoming.svg"),
        task: "driving",
    },
    Shipped {
        name: "medium-maze",
        what: "Lehman & Stanley's medium maze, for --task maze (1 robot, a goal)",
        svg: include_str!("../../../scenarios/medium-maze.svg"),
        task: "maze",
    },
    Shipped {
        name: "hard-maze",
        what: "Lehman & Stanley's hard (deceptive) maze, for --task maze (1 robot, a goal)",
        svg: include_str!("../../../scenarios/hard-maze.svg"),
        task: "maze",
    },
    Shipped {
        name: "predator-prey",
        what: "an open 300 x 300 arena, for --task predator-prey (a hunter and a prey)",
        svg: include_str!("../../../scenarios/predator-prey.svg"),
        task: "predator-prey",
    },
    Shipped {
        name: "predator-prey-obstacles",
        what: "the predator-prey arena with four blocks to hide behind (a hunter and a prey)",
        svg: include_str!("../../../scenarios/predator-prey-obstacles.svg"),
        task: "predator-prey",
    },
];

/// Every shipped scenario, in the order `vivae scenario list` shows them.
pub fn all() -> impl Iterator<Item = &'static Shipped> {
    SHIPPED.iter()
}

/// The shipped scenario called `name` (with or without `.svg`), if any.
pub fn find(name: &str) -> Option<&'static Shipped> {
    let name = name.strip_suffix(".svg").unwrap_or(name);
    SHIPPED.iter().find(|s| s.name == name)
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
        for s in SHIPPED {
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
        assert_eq!(task_of(&names(&["hard-maze"])), Some("maze"));
        assert_eq!(task_of(&names(&["medium-maze.svg"])), Some("maze"));
        assert_eq!(task_of(&names(&["oval", "town"])), Some("driving"));
        assert_eq!(task_of(&names(&["oval", "hard-maze"])), None, "two tasks");
        assert_eq!(task_of(&names(&["my-maze.svg"])), None, "not shipped");
        assert_eq!(task_of(&[]), None);
    }
}

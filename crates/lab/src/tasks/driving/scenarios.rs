//! The driving task's shipped scenarios (`scenarios/*.svg`): road maps
//! and tracks; `roads` is the default of every run.

use crate::config::TaskName;
use crate::shipped::Shipped;

/// The driving task's shipped scenarios, `roads` first.
pub const SCENARIOS: [Shipped; 11] = [
    Shipped {
        name: "roads",
        what: "the default: a road loop with a crossroad, a spur and an S-curve (5 robots)",
        svg: vivae_sim::ROADS_SVG,
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "oval",
        what: "an oval (stadium) track (5 robots)",
        svg: include_str!("../../../../../scenarios/oval.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "town",
        what: "a town grid around four houses with a roundabout (5 robots)",
        svg: include_str!("../../../../../scenarios/town.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "figure8",
        what: "a figure-8 track whose loops cross in the middle (5 robots)",
        svg: include_str!("../../../../../scenarios/figure8.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "obstacles",
        what: "a road loop with sand, a pond, walls, movable crates and pucks (5 robots)",
        svg: include_str!("../../../../../scenarios/obstacles.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "traffic",
        what: "a two-lane road loop driven both ways, with blocks and movable crates on the road (6 robots)",
        svg: include_str!("../../../../../scenarios/traffic.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "obstacles-random",
        what: "a road loop whose 8 blocks are placed at random for every episode (5 robots)",
        svg: include_str!("../../../../../scenarios/obstacles-random.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "oncoming",
        what: "a two-lane loop with 4 scripted robots driving the other lane the other way, a block in each long side's own lane (5 robots)",
        svg: include_str!("../../../../../scenarios/oncoming.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "corridor",
        what: "a long, gently curved road between kerbs whose 16 blocks lie at random across its whole width, edges included, every episode (5 robots)",
        svg: include_str!("../../../../../scenarios/corridor.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "kerbed-loop",
        what: "a road loop between kerbs whose 16 blocks lie at random across its whole width, edges included, every episode (5 robots)",
        svg: include_str!("../../../../../scenarios/kerbed-loop.svg"),
        task: TaskName::DRIVING,
    },
    Shipped {
        name: "oncoming-edges",
        what: "oncoming without its fixed blocks: every episode 8 blocks across the learners' whole lane and 8 on the road's outer edge (5 robots)",
        svg: include_str!("../../../../../scenarios/oncoming-edges.svg"),
        task: TaskName::DRIVING,
    },
];

//! Behaviour descriptors and metrics of a driving episode: what novelty
//! search, MAP-Elites and NSGA-II need of an evaluation besides its fitness.
//!
//! They are measured only when the run's strategy uses them
//! ([`Measures::of`]): a NEAT run's episodes are the plain ones, bit for bit
//! and at the same cost.
//!
//! * **`end-position`** — the robots' mean end position, each coordinate
//!   divided by the arena's size: 2 numbers in [0, 1]. The mean keeps the
//!   descriptor 2-D whatever the number of robots (a grid of 10 × 10 cells
//!   covers it; per-robot positions would need 10⁵ cells for five robots),
//!   at the price of not telling which robot went where.
//! * **`end-positions`** — every robot's end position, normalised the same
//!   way, concatenated in robot order: 2 × robots numbers, for novelty
//!   search (a k-d tree copes with 10 dimensions, a grid does not).
//! * **`side-speed`** — the mean signed side of the road (in half-widths,
//!   −1 left edge … +1 right edge, as [`crate::tasks::driving::behaviour`] measures it; 0
//!   when no robot-step was on a road with both edges in reach) and the
//!   mean speed as a share of `physics.v_max`: 2 numbers in [−1, 1] × [0, 1],
//!   the repertoire of "keep left / keep right, slow / fast".
//! * **`trajectory`** — the robots' mean position, normalised as
//!   `end-position`, after steps ⌈k·steps/5⌉ for k = 1…5 (the last is the
//!   end position): 10 numbers in [0, 1], a sample of the path, which tells
//!   a robot that went round a loop from one that stood at its end.
//!
//! Metrics ([`METRICS`], in this order): `contacts`, contacts begun per 1,000
//! robot-steps (robot–robot and robot–obstacle, as `replay` counts
//! collisions), and `on_road`, the share of robot-steps ending on a road.
//!
//! Over several maps or resolutions ([`crate::tasks::driving::combined::Combined`]) a genome's
//! behaviour and metrics are the means over the parts, coordinate by
//! coordinate: the descriptor keeps its dimensions and units (concatenating
//! would multiply a grid's cells by the number of parts).

use vivae_neat::driver::Evaluation;
use vivae_sim::World;

use crate::config::Config;
use crate::search::{BehaviourSpace, StrategyConfig};
use crate::tasks::behaviours::{self, BehaviourEntry};
use crate::tasks::driving::behaviour::BehaviourMeter;
use crate::tasks::driving::fitness::Fitness;
use crate::tasks::driving::rollout::{Drive, Rollout};

/// Which behaviour descriptor a driving episode reports (see the module's
/// documentation): the driving task offers these ([`BEHAVIOURS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BehaviourKind {
    /// The robots' mean end position over the arena's size.
    EndPosition,
    /// Every robot's end position over the arena's size, concatenated.
    EndPositions,
    /// Mean signed side of the road and mean speed over `v_max`.
    SideSpeed,
    /// The robots' mean position over the arena's size at
    /// [`TRAJECTORY_SAMPLES`] evenly spaced times, the last at the end.
    Trajectory,
}

/// Positions a `trajectory` behaviour samples: 5, so 10 coordinates (as
/// Lehman & Stanley sampled their biped's path, a handful of points).
pub const TRAJECTORY_SAMPLES: usize = 5;

/// The driving task's behaviour descriptors, by name (its entry's
/// [`crate::tasks::TaskEntry::behaviours`]).
pub static BEHAVIOURS: [BehaviourEntry; 4] = [
    BehaviourEntry {
        name: BehaviourKind::EndPosition.name(),
        coordinates: behaviours::position,
    },
    BehaviourEntry {
        name: BehaviourKind::EndPositions.name(),
        coordinates: |dims| BehaviourKind::EndPositions.coordinate_names(dims),
    },
    BehaviourEntry {
        name: BehaviourKind::SideSpeed.name(),
        coordinates: |dims| BehaviourKind::SideSpeed.coordinate_names(dims),
    },
    BehaviourEntry {
        name: BehaviourKind::Trajectory.name(),
        coordinates: |dims| BehaviourKind::Trajectory.coordinate_names(dims),
    },
];

impl BehaviourKind {
    /// Every kind, in [`BEHAVIOURS`]' order.
    const ALL: [BehaviourKind; 4] = [
        BehaviourKind::EndPosition,
        BehaviourKind::EndPositions,
        BehaviourKind::SideSpeed,
        BehaviourKind::Trajectory,
    ];

    /// The kind `config`'s `strategy.behaviour` names, if a driving one.
    pub fn of(config: &Config) -> Option<BehaviourKind> {
        let name = StrategyConfig::of(config).behaviour;
        Self::named(name.name())
    }

    /// The kind called `name` (as configs write it), if any.
    pub fn named(name: &str) -> Option<BehaviourKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Coordinates of the descriptor for `robots` robots.
    pub fn dims(self, robots: usize) -> usize {
        match self {
            BehaviourKind::EndPositions => 2 * robots,
            BehaviourKind::Trajectory => 2 * TRAJECTORY_SAMPLES,
            BehaviourKind::EndPosition | BehaviourKind::SideSpeed => 2,
        }
    }

    /// The box every descriptor lies in: (lower, upper) per coordinate.
    pub fn bounds(self, robots: usize) -> (Vec<f64>, Vec<f64>) {
        let n = self.dims(robots);
        match self {
            BehaviourKind::SideSpeed => (vec![-1.0, 0.0], vec![1.0, 1.0]),
            _ => (vec![0.0; n], vec![1.0; n]),
        }
    }

    /// Column names of the descriptor's `dims` coordinates.
    pub fn coordinate_names(self, dims: usize) -> Vec<String> {
        match self {
            BehaviourKind::EndPosition => behaviours::position(dims),
            BehaviourKind::SideSpeed => vec!["side".into(), "speed".into()],
            BehaviourKind::EndPositions => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2))
                .collect(),
            // The sample's number from 1 (the end is the last).
            BehaviourKind::Trajectory => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2 + 1))
                .collect(),
        }
    }

    /// The space of the descriptors of `robots` robots.
    pub fn space(self, robots: usize) -> BehaviourSpace {
        let (lower, upper) = self.bounds(robots);
        let names = self.coordinate_names(lower.len());
        BehaviourSpace {
            lower,
            upper,
            names,
        }
    }

    /// The name as configs write it.
    pub const fn name(self) -> &'static str {
        match self {
            BehaviourKind::EndPosition => "end-position",
            BehaviourKind::EndPositions => "end-positions",
            BehaviourKind::SideSpeed => "side-speed",
            BehaviourKind::Trajectory => "trajectory",
        }
    }
}

/// The space of `config`'s behaviour descriptors for `robots` robots
/// (empty for a name the driving task does not offer, which its check refuses).
pub fn space(config: &Config, robots: usize) -> BehaviourSpace {
    BehaviourKind::of(config).map_or_else(BehaviourSpace::default, |k| k.space(robots))
}

/// Refuses a behaviour descriptor the run's maps cannot give (the message
/// names the key): `end-positions` on several maps, whose robots differ.
pub fn check(c: &Config) -> std::result::Result<(), String> {
    let s = StrategyConfig::of(c);
    let searched = crate::search::entry(s.kind.name()).is_ok_and(|e| e.needs.behaviour);
    let multi_map = !c.experiment.scenarios.is_empty();
    if searched && BehaviourKind::of(c) == Some(BehaviourKind::EndPositions) && multi_map {
        return Err(format!(
            "strategy.behaviour = {:?}: one map only (maps have their own robots): use end-position on several maps",
            s.behaviour.name()
        ));
    }
    Ok(())
}

/// Names of the metrics a driving evaluation carries when measured, in order.
pub const METRICS: [&str; 2] = ["contacts", "on_road"];

/// What an episode measures besides its fitness.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Measures {
    /// The behaviour descriptor, if the strategy needs one.
    pub behaviour: Option<BehaviourKind>,
    /// Whether the [`METRICS`] are measured.
    pub metrics: bool,
}

impl Measures {
    /// What a run with strategy `s` needs, as its entry says (`None`:
    /// nothing, the plain episode; also for a strategy not registered, which
    /// the config's check refuses).
    pub fn of(s: &StrategyConfig) -> Option<Measures> {
        let needs = crate::search::entry(s.kind.name()).ok()?.needs;
        let m = Measures {
            behaviour: needs
                .behaviour
                .then(|| BehaviourKind::named(s.behaviour.name()))
                .flatten(),
            metrics: needs.metrics,
        };
        (m.behaviour.is_some() || m.metrics).then_some(m)
    }
}

/// An episode of `steps` steps from `start`, scored by `fitness`.
pub struct EpisodeSetup<'a> {
    /// The world at the start of the episode.
    pub start: &'a World,
    /// Simulation steps.
    pub steps: u32,
    /// The episode's fitness function.
    pub fitness: &'a dyn Fitness,
}

/// The episode `setup` driven by `controller` through `rollout`, measuring
/// `measures` besides the fitness (which is the plain episode's, bit for bit).
pub fn measured_episode(
    setup: EpisodeSetup<'_>,
    mut rollout: Rollout,
    controller: &(impl Drive + ?Sized),
    measures: Measures,
) -> Evaluation {
    let steps = setup.steps;
    let mut world = setup.start.clone();
    let n = world.robots().len();
    let fitness = setup.fitness;
    let mut meter = fitness.meter(&world);
    let observe = fitness.observes_steps();
    let side = measures.behaviour == Some(BehaviourKind::SideSpeed);
    let mut behaviour = (measures.metrics || side)
        .then(|| BehaviourMeter::new(&world, steps as usize).measuring_side(side));
    let mut on_road = 0u64;
    let mut path = (measures.behaviour == Some(BehaviourKind::Trajectory))
        .then(|| Vec::with_capacity(2 * TRAJECTORY_SAMPLES));
    for t in 1..=steps {
        rollout.step(&mut world, controller, None);
        if let Some(p) = &mut path {
            sample_path(p, &world, t, steps);
        }
        if observe {
            meter.observe(&world);
        }
        if let Some(b) = &mut behaviour {
            b.observe(&world);
        }
        if measures.metrics {
            on_road += (0..n).filter(|&i| world.on_road(i)).count() as u64;
        }
    }
    let robot_steps = (n as f64) * f64::from(steps);
    let measured = behaviour.map(|b| b.finish());
    let metrics = match (&measured, measures.metrics) {
        (Some(b), true) => vec![b.collisions, on_road as f64 / robot_steps],
        _ => Vec::new(),
    };
    let (w, h) = (world.scenario().width(), world.scenario().height());
    let ends = || world.robots().iter().map(|r| [r.pos.x / w, r.pos.y / h]);
    let behaviour = match measures.behaviour {
        None => Vec::new(),
        Some(BehaviourKind::EndPosition) => mean_position(&world).to_vec(),
        Some(BehaviourKind::EndPositions) => ends().flatten().collect(),
        Some(BehaviourKind::Trajectory) => {
            let mut p = path.unwrap_or_default();
            // No steps at all: every sample is where the robots stand.
            sample_path(&mut p, &world, steps, steps);
            p
        }
        Some(BehaviourKind::SideSpeed) => {
            let odometer: f64 = world.robots().iter().map(|r| r.odometer).sum();
            let speed = odometer / robot_steps / world.params().v_max;
            let side = measured.and_then(|b| b.side).unwrap_or(0.0);
            vec![side, speed]
        }
    };
    Evaluation {
        fitness: meter.score(&world, robot_steps),
        metrics,
        behaviour,
    }
}

/// Appends to `path` the samples due by step `t` of `steps`: sample k
/// (from 1) after step ⌈k·steps/K⌉, so several at once when steps < K.
fn sample_path(path: &mut Vec<f64>, world: &World, t: u32, steps: u32) {
    let k = TRAJECTORY_SAMPLES as u64;
    while path.len() < 2 * TRAJECTORY_SAMPLES
        && u64::from(t) * k >= (path.len() as u64 / 2 + 1) * u64::from(steps)
    {
        path.extend(mean_position(world));
    }
}

/// The robots' mean position, each coordinate divided by the map's size
/// (0 with no robots).
fn mean_position(world: &World) -> [f64; 2] {
    let (w, h) = (world.scenario().width(), world.scenario().height());
    let n = world.robots().len().max(1) as f64;
    let (x, y) = world
        .robots()
        .iter()
        .fold((0.0, 0.0), |(x, y), r| (x + r.pos.x / w, y + r.pos.y / h));
    [x / n, y / n]
}

/// The evaluation of a genome that does not fit the substrate (evolution
/// never makes one): fitness 0, every measure 0.
pub fn unfit(measures: Measures, robots: usize) -> Evaluation {
    Evaluation {
        fitness: 0.0,
        metrics: vec![0.0; if measures.metrics { METRICS.len() } else { 0 }],
        behaviour: vec![0.0; measures.behaviour.map_or(0, |b| b.dims(robots))],
    }
}

/// The mean of `parts`' vectors, coordinate by coordinate; when their
/// lengths differ, the first part's (a run's parts share their robots, so
/// this does not happen in a valid run).
pub fn mean_of(parts: &[&[f64]]) -> Vec<f64> {
    let Some(first) = parts.first() else {
        return Vec::new();
    };
    if parts.iter().any(|p| p.len() != first.len()) {
        return first.to_vec();
    }
    let k = parts.len() as f64;
    (0..first.len())
        .map(|i| parts.iter().map(|p| p[i]).sum::<f64>() / k)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn end_positions_are_refused_on_several_maps_only() {
        let config = |behaviour, maps: &[&str]| {
            let mut c = Config::default();
            StrategyConfig::update(&mut c, |s| {
                s.kind = "novelty".into();
                s.behaviour = BehaviourKind::name(behaviour).into();
            });
            c.experiment.scenarios = maps.iter().map(|m| m.to_string()).collect();
            c
        };
        let two = ["oval", "roads"];
        let why = check(&config(BehaviourKind::EndPositions, &two)).unwrap_err();
        assert!(
            why.starts_with("strategy.behaviour = \"end-positions\""),
            "{why}"
        );
        assert_eq!(check(&config(BehaviourKind::EndPositions, &[])), Ok(()));
        assert_eq!(check(&config(BehaviourKind::EndPosition, &two)), Ok(()));
        // The task's validation refuses it, for the driving task only.
        let why = crate::tasks::check(&config(BehaviourKind::EndPositions, &two)).unwrap_err();
        assert!(why.to_string().contains("one map only"), "{why}");
    }

    #[test]
    fn a_trajectory_takes_its_samples_at_evenly_spaced_steps() {
        // Sample k after step ⌈k·steps/5⌉: steps 2, 4, 6, 8, 10 of 10; all
        // five after the only step of 1; with 3 steps, some steps take two.
        let due = |steps: u32| -> Vec<u32> {
            let mut path = Vec::new();
            let world = crate::tasks::scenarios::load_scenario(None)
                .unwrap()
                .scenario;
            let world = World::new(&world, &vivae_sim::PhysicsParams::default()).unwrap();
            let mut at = Vec::new();
            for t in 1..=steps {
                let before = path.len();
                sample_path(&mut path, &world, t, steps);
                at.extend(std::iter::repeat_n(t, (path.len() - before) / 2));
            }
            at
        };
        assert_eq!(due(10), vec![2, 4, 6, 8, 10]);
        assert_eq!(due(1), vec![1; 5]);
        assert_eq!(due(3), vec![1, 2, 2, 3, 3]);
        assert_eq!(due(1000), vec![200, 400, 600, 800, 1000]);
    }

    #[test]
    fn mean_of_parts_is_per_coordinate() {
        assert_eq!(mean_of(&[&[1.0, 2.0], &[3.0, 6.0]]), vec![2.0, 4.0]);
        assert!(mean_of(&[]).is_empty());
        assert!(mean_of(&[&[], &[]]).is_empty());
    }
}

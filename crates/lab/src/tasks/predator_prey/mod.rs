//! Predators and prey: two populations of plain NEAT networks co-evolved in
//! one arena, as in ViVAE's later predator–prey experiment
//! (`PredatorKorist`): a hunter population and a prey population, each
//! genome evaluated against opponents from the other population (its best
//! of the previous generation, or a sample of its hall of fame:
//! `[coevolution]`).
//!
//! The arena is a scenario with one robot of team `hunter` and one of team
//! `prey` (`data-team`, docs/scenario-format.md); the shipped ones are
//! `scenarios/predator-prey.svg` and `predator-prey-obstacles.svg`. Both
//! robots are Lehman & Stanley's robot ([`crate::tasks::robot::physics`]):
//! the same speed, so a hunter catches a prey only by cutting it off. Each
//! carries the opponent radar (four pie slices reading `1 − d/range`,
//! [`OpponentRadar`]), the maze's six rangefinders and a bias; its outputs
//! are the maze's turn and forward ([`crate::tasks::robot::wheels`]). An
//! episode ends when the two touch (a team contact: the catch) or after
//! `experiment.steps` steps.
//!
//! Fitness, with `T` the episode's steps, `t` the step of the catch and
//! `d̄` the mean hunter–prey distance over the episode as a share of the
//! arena's diagonal:
//!
//! * hunter: `2 − t/T` after a catch (in [1, 2): sooner is better), else
//!   `1 − d̄` (in [0, 1]: staying close is better than not, and every catch
//!   beats every miss);
//! * prey: `2 − hunter` (`t/T` when caught: later is better; `1 + d̄` when
//!   not: every escape beats every catch, further away is better).
//!
//! The game is constant-sum (hunter + prey = 2), so a CIAO matrix of the
//! hunter's fitness says everything about both sides.

pub mod brain;
pub mod coevo;
pub mod config;
pub mod files;
pub mod meeting;
pub mod meetings;
mod present;
pub mod run;
pub mod section;
pub mod tournament;

pub use run::TASK;

use vivae_neat::hyperneat::HyperParams;
use vivae_neat::{Genome, GenomeSpec};
use vivae_sim::{
    DistanceGrid, OpponentRadar, ParamError, PhysicsParams, Scenario, ScenarioError, Sensor, World,
};

use crate::tasks::predator_prey::brain::{Brain, Substrate};
use crate::tasks::predator_prey::section::{CoevolutionConfig, SideController};
use crate::tasks::robot::{self, RANGE};

/// The task's name in `experiment.task` and `--task`.
pub const NAME: &str = "predator-prey";
/// The hunters' team name in a scenario.
pub const HUNTER_TEAM: &str = "hunter";
/// The prey's team name in a scenario.
pub const PREY_TEAM: &str = "prey";
/// Slices of the opponent radar.
pub const RADAR_SLICES: usize = 4;
/// Network inputs: 4 opponent radar slices, 6 rangefinders, a bias of 1.
pub const INPUTS: usize = 11;
/// Network outputs: turn, forward.
pub const OUTPUTS: usize = 2;
/// Steps of one episode by default.
pub const STEPS: u32 = 500;

/// Why a scenario is not a predator–prey arena.
#[derive(Debug, thiserror::Error)]
pub enum ArenaError {
    /// The SVG did not load.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// Not two robots, one of each team.
    #[error(
        "{source_name}: a predator-prey arena has two robots, one with data-team=\"hunter\" and one with data-team=\"prey\" (found {hunters} and {prey}, {robots} robots in all)"
    )]
    Teams {
        /// The scenario file.
        source_name: String,
        /// Hunters found.
        hunters: usize,
        /// Prey found.
        prey: usize,
        /// Robots in the scenario.
        robots: usize,
    },
    /// An obstacle region: a predator–prey episode places nothing at random.
    #[error(
        "{source_name}: obstacle region '{id}': a predator-prey arena places no obstacles at random (draw them as fixed or movable obstacles)"
    )]
    Region {
        /// The scenario file.
        source_name: String,
        /// The region's id.
        id: String,
    },
    /// A sensor or physics setting out of range.
    #[error(transparent)]
    Param(#[from] ParamError),
}

/// Which side of the game.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The hunters.
    Hunter,
    /// The prey.
    Prey,
}

impl Side {
    /// `"hunter"` or `"prey"`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Hunter => HUNTER_TEAM,
            Side::Prey => PREY_TEAM,
        }
    }

    /// The other side.
    pub fn other(self) -> Side {
        match self {
            Side::Hunter => Side::Prey,
            Side::Prey => Side::Hunter,
        }
    }
}

/// How one episode ended.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Outcome {
    /// Whether the hunter caught the prey.
    pub caught: bool,
    /// Steps played (the step of the catch, or all of them).
    pub steps: u32,
    /// Steps an episode has at most.
    pub max_steps: u32,
    /// Mean hunter–prey centre distance over the steps, as a share of the arena's diagonal.
    pub mean_distance: f64,
}

impl Outcome {
    /// The hunter's fitness: `2 − t/T` after a catch, else `1 − d̄`.
    pub fn hunter_fitness(&self) -> f64 {
        if self.caught {
            2.0 - f64::from(self.steps) / f64::from(self.max_steps)
        } else {
            (1.0 - self.mean_distance).clamp(0.0, 1.0)
        }
    }

    /// The prey's fitness: `2 − hunter` (the game is constant-sum).
    pub fn prey_fitness(&self) -> f64 {
        2.0 - self.hunter_fitness()
    }

    /// The fitness of `side`.
    pub fn fitness(&self, side: Side) -> f64 {
        match side {
            Side::Hunter => self.hunter_fitness(),
            Side::Prey => self.prey_fitness(),
        }
    }
}

/// The arena: a scenario's walls, its hunter and its prey, and their sensors.
#[derive(Debug, Clone)]
pub struct Arena {
    world: World,
    hunter: usize,
    prey: usize,
    radar: OpponentRadar,
    rays: DistanceGrid,
    steps: u32,
    diagonal: f64,
    substrate: Substrate,
    controllers: [SideController; 2],
    hyper: [HyperParams; 2],
}

impl Arena {
    /// The hunter's and the prey's robot indices in `scenario`, or why it is
    /// not a predator–prey arena: the one check of a map for this task, by
    /// [`Arena::new`] and by the task's entry when a config's maps are loaded.
    pub fn teams(scenario: &Scenario) -> Result<(usize, usize), ArenaError> {
        let of = |team: &str| -> Vec<usize> {
            (scenario.robots.iter().enumerate())
                .filter(|(_, r)| r.team == team)
                .map(|(i, _)| i)
                .collect()
        };
        let (hunters, prey) = (of(HUNTER_TEAM), of(PREY_TEAM));
        let (&[hunter], &[prey_i], 2) =
            (hunters.as_slice(), prey.as_slice(), scenario.robots.len())
        else {
            return Err(ArenaError::Teams {
                source_name: scenario.source.clone(),
                hunters: hunters.len(),
                prey: prey.len(),
                robots: scenario.robots.len(),
            });
        };
        if let Some(region) = scenario.obstacle_regions.first() {
            return Err(ArenaError::Region {
                source_name: scenario.source.clone(),
                id: region.id.clone(),
            });
        }
        Ok((hunter, prey_i))
    }

    /// The arena of `scenario` with the robot of `physics`, episodes of `steps` steps.
    pub fn new(
        scenario: &Scenario,
        physics: &PhysicsParams,
        steps: u32,
    ) -> Result<Arena, ArenaError> {
        let (hunter, prey_i) = Arena::teams(scenario)?;
        let diagonal = scenario.width().hypot(scenario.height());
        let rim = RANGE - physics.robot_radius;
        let radar = OpponentRadar::new(RADAR_SLICES, diagonal)?;
        let rays = DistanceGrid::at_angles(&robot::rangefinder_angles(), rim);
        Ok(Arena {
            world: World::new(scenario, physics)?,
            hunter,
            prey: prey_i,
            substrate: Substrate::new(&radar, &rays),
            radar,
            rays,
            steps,
            diagonal,
            controllers: [SideController::Neat; 2],
            hyper: [HyperParams::default(), HyperParams::default()],
        })
    }

    /// This arena with the hunters' and the prey's controllers of kinds
    /// `hunter` and `prey` (plain NEAT networks by default), HyperNEAT
    /// ones decoded with `params`.
    pub fn with_controllers(
        mut self,
        hunter: SideController,
        prey: SideController,
        params: HyperParams,
    ) -> Arena {
        self.controllers = [hunter, prey];
        self.hyper = [params, params];
        self
    }

    /// The arena of a run's `config` in `scenario`: its physics, steps and
    /// both sides' kinds of controllers (`[coevolution]`, `[hyperneat]`).
    pub fn of_config(
        scenario: &Scenario,
        config: &crate::config::Config,
    ) -> Result<Arena, ArenaError> {
        let c = &CoevolutionConfig::of(config);
        let arena = Arena::new(scenario, &config.physics, config.experiment.steps)?;
        Ok(arena.with_controllers(c.hunter, c.prey, config.hyperneat))
    }

    /// `side`'s controller of `genome` for one episode (of its side's kind).
    pub fn brain(&self, side: Side, genome: &Genome) -> Brain {
        let k = usize::from(side == Side::Prey);
        Brain::new(self.controllers[k], genome, &self.substrate, &self.hyper[k])
    }

    /// This arena with the prey's HyperNEAT controllers decoded with
    /// `params` (when the two sides come from runs of different settings).
    pub fn with_prey_params(mut self, params: HyperParams) -> Arena {
        self.hyper[1] = params;
        self
    }

    /// The kind of `side`'s controllers.
    pub fn controller(&self, side: Side) -> SideController {
        self.controllers[usize::from(side == Side::Prey)]
    }

    /// The genome layout of a plain NEAT side: [`INPUTS`] inputs,
    /// [`OUTPUTS`] sigmoid outputs, recurrent links allowed (as the maze's).
    pub fn spec() -> GenomeSpec {
        robot::spec()
    }

    /// The genome layout of a side of kind `kind`: [`Arena::spec`], or a
    /// CPPN of the substrate ([`brain`]).
    pub fn spec_of(kind: SideController) -> GenomeSpec {
        let radar = OpponentRadar::new(RADAR_SLICES, 1.0);
        let rays = DistanceGrid::at_angles(&robot::rangefinder_angles(), RANGE);
        match radar {
            Ok(radar) => Substrate::new(&radar, &rays).spec(kind),
            Err(_) => robot::spec(),
        }
    }

    /// Steps of one episode at most.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// The world at the start.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The robot index of `side` in the world.
    pub fn robot(&self, side: Side) -> usize {
        match side {
            Side::Hunter => self.hunter,
            Side::Prey => self.prey,
        }
    }

    /// Reads `side`'s inputs in `world` (radar slices, rangefinders, bias),
    /// as [`Arena::play`] does each step (for a viewer that steps an episode itself).
    pub fn inputs(&self, world: &World, side: Side, inputs: &mut [f64; INPUTS]) {
        self.read(world, self.robot(side), inputs);
    }

    /// Whether the hunter touches the prey in `world` after its last step: the catch.
    pub fn caught(&self, world: &World) -> bool {
        let (a, b) = (self.hunter.min(self.prey), self.hunter.max(self.prey));
        world.team_contacts().iter().any(|c| c.a == a && c.b == b)
    }

    /// Reads robot `robot`'s inputs: radar slices, rangefinders, bias.
    fn read(&self, world: &World, robot: usize, inputs: &mut [f64; INPUTS]) {
        let (radar, rest) = inputs.split_at_mut(self.radar.len());
        self.radar.read(world, robot, radar);
        self.rays.read(world, robot, rest);
        inputs[INPUTS - 1] = 1.0;
    }

    /// Plays one episode: `hunter` and `prey` are asked each step for their
    /// outputs (turn, forward in [0, 1]) from their inputs. `each` sees the
    /// world after every step (for trajectories). Allocation-free after the
    /// world's copy.
    pub fn play(
        &self,
        mut hunter: impl FnMut(&[f64], &mut [f64]),
        mut prey: impl FnMut(&[f64], &mut [f64]),
        mut each: impl FnMut(&World),
    ) -> Outcome {
        let mut m = self.start();
        let (mut hi, mut pi) = ([0.0; INPUTS], [0.0; INPUTS]);
        let (mut ho, mut po) = ([0.0; OUTPUTS], [0.0; OUTPUTS]);
        while !self.over(&m) {
            self.read(m.world(), self.hunter, &mut hi);
            self.read(m.world(), self.prey, &mut pi);
            hunter(&hi, &mut ho);
            prey(&pi, &mut po);
            self.advance(&mut m, [ho[0], ho[1]], [po[0], po[1]]);
            each(m.world());
        }
        self.outcome(&m)
    }

    /// An episode of `hunter`'s controller against `prey`'s (each of its
    /// side's kind).
    pub fn play_genomes(&self, hunter: &Genome, prey: &Genome) -> Outcome {
        let (mut h, mut p) = (
            self.brain(Side::Hunter, hunter),
            self.brain(Side::Prey, prey),
        );
        self.play(|i, o| h.act(i, o), |i, o| p.act(i, o), |_| {})
    }
}

/// The shipped arena `name` with the task's robots and steps (for tests).
#[cfg(test)]
pub(crate) fn shipped_arena(name: &str) -> Arena {
    let svg = crate::tasks::scenarios::find(name).unwrap().svg;
    let options = vivae_sim::LoadOptions::default();
    let sc = Scenario::from_svg(svg, name, &options).unwrap();
    Arena::new(&sc, &robot::physics(), STEPS).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_sim::LoadOptions;

    fn arena(name: &str) -> Arena {
        shipped_arena(name)
    }

    /// Full speed at an opponent ahead; else slows down (a robot at top
    /// speed cannot turn) and turns towards the slice that sees it.
    fn chase(i: &[f64], o: &mut [f64]) {
        // Slices: left, ahead, right, behind.
        let out = if i[1] > 0.0 {
            [0.5, 1.0]
        } else if i[2] > 0.0 {
            [1.0, 0.3]
        } else {
            [0.0, 0.3]
        };
        o.copy_from_slice(&out);
    }

    #[test]
    fn a_chasing_hunter_catches_a_standing_prey_and_scores_by_time() {
        let a = arena("predator-prey");
        let out = a.play(chase, |_, o| o.copy_from_slice(&[0.5, 0.5]), |_| {});
        assert!(out.caught && out.steps < STEPS, "{out:?}");
        assert!(out.hunter_fitness() > 1.0 && out.hunter_fitness() < 2.0);
        assert_eq!(out.hunter_fitness() + out.prey_fitness(), 2.0);
        // Standing still, nobody catches anybody: fitness from the distance.
        let idle = a.play(|_, o| o.fill(0.5), |_, o| o.fill(0.5), |_| {});
        assert!(!idle.caught && idle.steps == STEPS);
        let start = a.world().robots()[0]
            .pos
            .distance(a.world().robots()[1].pos);
        let d = start / 300f64.hypot(300.0);
        assert!((idle.hunter_fitness() - (1.0 - d)).abs() < 1e-12);
        assert!(idle.prey_fitness() > 1.0, "every escape beats every catch");
    }

    #[test]
    fn inputs_see_the_opponent_and_the_walls() {
        let a = arena("predator-prey-obstacles");
        let mut first = None;
        a.play(
            |i, o| {
                first.get_or_insert_with(|| i.to_vec());
                o.fill(0.5);
            },
            |_, o| o.fill(0.5),
            |_| {},
        );
        let i = first.unwrap();
        // The hunter faces up at (60, 240); the prey is ahead-right at (240, 60), 45°: a slice boundary.
        assert_eq!(i[0], 0.0);
        assert_eq!(i[3], 0.0);
        assert!(i[1] + i[2] > 0.3, "{i:?}");
        assert_eq!(i[INPUTS - 1], 1.0);
        assert!(i.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn an_arena_with_an_obstacle_region_is_refused_by_name() {
        let svg = crate::tasks::scenarios::find("predator-prey").unwrap().svg.replace(
            "</svg>",
            r#"<rect id="zone" inkscape:label="ObstacleRegion" data-count="2" x="100" y="100" width="50" height="50"/></svg>"#,
        );
        let sc = Scenario::from_svg(&svg, "pp.svg", &LoadOptions::default()).unwrap();
        let err = Arena::new(&sc, &robot::physics(), 10)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("pp.svg: obstacle region 'zone'"), "{err}");
    }

    #[test]
    fn a_scenario_without_both_teams_is_refused() {
        let sc = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default());
        let err = Arena::new(&sc.unwrap(), &robot::physics(), 10)
            .unwrap_err()
            .to_string();
        assert!(err.contains("roads.svg") && err.contains("hunter"), "{err}");
    }
}

//! The maze navigation benchmark of Lehman & Stanley 2011 ("Abandoning
//! objectives: evolution through the search for novelty alone",
//! Evolutionary Computation 19(2)): a plain-NEAT network drives the paper's
//! robot through the medium or the hard maze for 400 steps.
//!
//! The mazes are shipped scenarios (`scenarios/medium-maze.svg`,
//! `scenarios/hard-maze.svg`): walls are fixed obstacles, the start is the
//! one robot and the goal is the position mark with id `goal`, its radius
//! the distance within which the maze counts as solved. The robot has the
//! paper's six rangefinders (reach 100 from its centre, one looking back)
//! and four pie-slice goal radar sensors ([`GoalRadar`]); its two outputs,
//! turn and forward, drive our differential robot (see [`wheels`]).
//!
//! Fitness is the paper's `b_f − d_g` (a bias minus the end distance to the
//! goal), the behaviour is the end position, and the metrics say whether
//! the goal was reached, the end distance and the steps taken. An episode
//! ends early when the robot reaches the goal, as in Lehman's simulator.

pub mod config;
pub mod lehman;
mod present;
pub mod run;
pub mod section;
pub mod walls;

pub use config::lehman_neat;
pub use run::TASK;

pub use crate::tasks::robot::{INPUTS, OUTPUTS, RANGE, wheels};

use crate::shipped::Shipped;

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome, GenomeSpec, Network, RecurrentNetwork};
use vivae_sim::{
    DVec2, DistanceGrid, GoalRadar, LoadOptions, ParamError, PhysicsParams, Scenario,
    ScenarioError, Sensor, World,
};

/// The medium maze (`scenarios/medium-maze.svg`).
pub const MEDIUM_MAZE_SVG: &str = include_str!("../../../../../scenarios/medium-maze.svg");
/// The hard maze (`scenarios/hard-maze.svg`).
pub const HARD_MAZE_SVG: &str = include_str!("../../../../../scenarios/hard-maze.svg");

/// The mazes as shipped scenarios (`--scenario medium-maze`).
pub const SCENARIOS: [Shipped; 2] = [
    Shipped {
        name: "medium-maze",
        what: "Lehman & Stanley's medium maze, for the maze task (1 robot, a goal)",
        svg: MEDIUM_MAZE_SVG,
        task: NAME,
    },
    Shipped {
        name: "hard-maze",
        what: "Lehman & Stanley's hard (deceptive) maze, for the maze task (1 robot, a goal)",
        svg: HARD_MAZE_SVG,
        task: NAME,
    },
];

/// The task's name in `experiment.task` and `--task`.
pub const NAME: &str = "maze";
/// Steps of one evaluation (the paper's 400).
pub const STEPS: u32 = 400;
/// The bias `b_f` of the fitness `b_f − d_g`: above any distance in either maze.
pub const FITNESS_BIAS: f64 = 300.0;
/// Id of the position mark that is the goal.
pub const GOAL_MARK: &str = "goal";
/// Names of [`Evaluation::metrics`], in order.
pub const METRICS: [&str; 3] = ["solved", "distance", "steps"];
/// Side of a cell of the maze's behaviour space worth one elite, px (the
/// example's MAP-Elites grid).
pub const CELL: f64 = 10.0;

/// Why a scenario is not a maze.
#[derive(Debug, thiserror::Error)]
pub enum MazeError {
    /// The SVG did not load.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A maze has exactly one robot.
    #[error("{source_name}: a maze needs exactly one robot, found {count}")]
    Robots {
        /// The scenario file.
        source_name: String,
        /// Robots found.
        count: usize,
    },
    /// No position mark with id `goal`.
    #[error("{source_name}: no position mark with id \"goal\" (the maze's goal)")]
    NoGoal {
        /// The scenario file.
        source_name: String,
    },
    /// A sensor or physics setting out of range (e.g. a goal mark of no size).
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A maze file in Lehman's format that does not parse.
    #[error("{source_name}: {why}")]
    File {
        /// The file.
        source_name: String,
        /// What is wrong.
        why: String,
    },
}

/// One of the two shipped mazes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Maze {
    /// The medium maze.
    Medium,
    /// The hard (deceptive) maze.
    Hard,
}

impl Maze {
    /// `"medium"` or `"hard"`.
    pub fn name(self) -> &'static str {
        match self {
            Maze::Medium => "medium",
            Maze::Hard => "hard",
        }
    }

    /// The maze's SVG text.
    pub fn svg(self) -> &'static str {
        match self {
            Maze::Medium => MEDIUM_MAZE_SVG,
            Maze::Hard => HARD_MAZE_SVG,
        }
    }

    /// The maze named `name` (`medium` or `hard`).
    pub fn from_name(name: &str) -> Option<Maze> {
        [Maze::Medium, Maze::Hard]
            .into_iter()
            .find(|m| m.name() == name)
    }

    /// The loaded scenario.
    pub fn scenario(self) -> Result<Scenario, ScenarioError> {
        let source = format!("{}-maze.svg", self.name());
        Scenario::from_svg(self.svg(), &source, &LoadOptions::default())
    }
}

/// How one episode ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Where the robot ended.
    pub end: DVec2,
    /// Its distance to the goal there, px.
    pub distance: f64,
    /// Whether it came within the goal radius.
    pub solved: bool,
    /// Steps taken (fewer than [`STEPS`] when it reached the goal early).
    pub steps: u32,
}

impl Outcome {
    /// An episode that ended at `end` after `steps`; `solved` tells from the
    /// squared distance to `goal` whether it reached it (the models differ:
    /// Lehman's `<`, ours `<=`).
    pub fn ended(end: DVec2, goal: DVec2, steps: u32, solved: impl FnOnce(f64) -> bool) -> Outcome {
        let d2 = end.distance_squared(goal);
        Outcome {
            end,
            distance: d2.sqrt(),
            solved: solved(d2),
            steps,
        }
    }

    /// The paper's fitness `b_f − d_g`, never below 0.
    pub fn fitness(&self) -> f64 {
        (FITNESS_BIAS - self.distance).max(0.0)
    }

    /// The evaluation: fitness, the metrics [`METRICS`], the end position as behaviour.
    pub fn evaluation(&self) -> Evaluation {
        Evaluation {
            fitness: self.fitness(),
            metrics: vec![
                f64::from(u8::from(self.solved)),
                self.distance,
                self.steps as f64,
            ],
            behaviour: vec![self.end.x, self.end.y],
        }
    }
}

/// The `goal` mark of a maze scenario, checked to have exactly one robot.
fn maze_goal(scenario: &Scenario) -> Result<&vivae_sim::Mark, MazeError> {
    let source_name = scenario.source.clone();
    if scenario.robots.len() != 1 {
        let count = scenario.robots.len();
        return Err(MazeError::Robots { source_name, count });
    }
    (scenario.mark(GOAL_MARK)).ok_or(MazeError::NoGoal { source_name })
}

/// What a maze run needs of a robot model: Lehman's ([`lehman::LehmanTask`],
/// the default) or ours ([`MazeTask`], `maze.robot = "vivae"`).
pub trait MazeModel: Task + Clone + std::fmt::Debug + Send + Sync + 'static {
    /// One episode driven by `genome`'s network.
    fn outcome(&self, genome: &Genome) -> Outcome;
    /// Steps of one episode at most.
    fn episode_steps(&self) -> u32;
    /// The box every end position lies in.
    fn bounds(&self) -> (Vec<f64>, Vec<f64>);
    /// Where the maze came from, for the run's header and a replay.
    fn source(&self) -> &str;
}

/// A maze model's [`Task`]: an evaluation is one episode's outcome.
macro_rules! maze_task {
    ($model:ty) => {
        impl Task for $model {
            fn evaluate(&self, genome: &Genome, _ctx: &EvalContext) -> Evaluation {
                $crate::tasks::maze::MazeModel::outcome(self, genome).evaluation()
            }

            fn metric_names(&self) -> &[&str] {
                &METRICS
            }

            /// An episode starts where the maze says: it depends on the genome alone.
            fn context_free(&self) -> bool {
                true
            }
        }
    };
}
pub(crate) use maze_task;

impl MazeModel for MazeTask {
    fn outcome(&self, genome: &Genome) -> Outcome {
        let mut net = RecurrentNetwork::from_genome(genome);
        self.run(|i, o| net.activate(i, o))
    }
    fn episode_steps(&self) -> u32 {
        self.steps
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.arena_bounds()
    }
    fn source(&self) -> &str {
        &self.world.scenario().source
    }
}

impl MazeModel for lehman::LehmanTask {
    fn outcome(&self, genome: &Genome) -> Outcome {
        let mut net = RecurrentNetwork::from_genome(genome);
        self.run(|i, o| net.activate(i, o))
    }
    fn episode_steps(&self) -> u32 {
        self.steps()
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.maze().bounds()
    }
    fn source(&self) -> &str {
        &self.maze().source
    }
}

/// The maze task: a scenario's walls, robot and goal with the paper's robot.
#[derive(Debug, Clone)]
pub struct MazeTask {
    world: World,
    rays: DistanceGrid,
    radar: GoalRadar,
    goal_radius: f64,
    steps: u32,
}

impl MazeTask {
    /// The robot's physics ([`crate::tasks::robot::physics`]).
    pub fn physics() -> PhysicsParams {
        crate::tasks::robot::physics()
    }

    /// Its rangefinders' angles ([`crate::tasks::robot::rangefinder_angles`]).
    pub fn rangefinder_angles() -> [f64; 6] {
        crate::tasks::robot::rangefinder_angles()
    }

    /// The maze in `scenario`: one robot, a `goal` mark.
    pub fn new(scenario: &Scenario) -> Result<MazeTask, MazeError> {
        MazeTask::with_settings(scenario, &MazeTask::physics(), STEPS)
    }

    /// [`MazeTask::new`] with another robot (`physics`) or episode length
    /// (`steps`): a maze run's `[physics]` and `experiment.steps`.
    pub fn with_settings(
        scenario: &Scenario,
        physics: &PhysicsParams,
        steps: u32,
    ) -> Result<MazeTask, MazeError> {
        let goal = maze_goal(scenario)?;
        let rim = RANGE - physics.robot_radius;
        Ok(MazeTask {
            world: World::new(scenario, physics)?,
            rays: DistanceGrid::at_angles(&MazeTask::rangefinder_angles(), rim),
            radar: GoalRadar::paper(goal.pos)?,
            goal_radius: goal.size.x.max(goal.size.y) / 2.0,
            steps,
        })
    }

    /// One of the shipped mazes.
    pub fn shipped(maze: Maze) -> Result<MazeTask, MazeError> {
        MazeTask::new(&maze.scenario()?)
    }

    /// The genome layout ([`crate::tasks::robot::spec`]).
    pub fn spec() -> GenomeSpec {
        crate::tasks::robot::spec()
    }

    /// Where the goal is.
    pub fn goal(&self) -> DVec2 {
        self.radar.goal()
    }

    /// Within this distance of the goal the maze is solved, px.
    pub fn goal_radius(&self) -> f64 {
        self.goal_radius
    }

    /// Steps of one episode (fewer when the robot reaches the goal).
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// The box every end position lies in: `([0, 0], [width, height])` of the arena.
    pub fn arena_bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let sc = self.world.scenario();
        (vec![0.0, 0.0], vec![sc.width(), sc.height()])
    }

    /// Where the robot starts.
    pub fn start(&self) -> DVec2 {
        self.world.robots()[0].pos
    }

    /// The world at the start (e.g. to draw the maze).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Runs one episode: `controller(inputs, outputs)` is asked each step
    /// (inputs: 6 rangefinders `1 − d/reach` from the rim, 4 radar slices
    /// left/ahead/right/behind, a bias of 1; outputs: turn, forward in
    /// [0, 1]). Allocation-free after the world's copy.
    pub fn run(&self, mut controller: impl FnMut(&[f64], &mut [f64])) -> Outcome {
        let mut world = self.world.clone();
        let (goal, r2) = (self.goal(), self.goal_radius * self.goal_radius);
        let mut inputs = [0.0; INPUTS];
        inputs[INPUTS - 1] = 1.0;
        let mut outputs = [0.0; OUTPUTS];
        let mut steps = 0;
        while steps < self.steps && world.robots()[0].pos.distance_squared(goal) > r2 {
            let (rays, rest) = inputs.split_at_mut(self.rays.len());
            self.rays.read(&world, 0, rays);
            self.radar.read(&world, 0, rest);
            controller(&inputs, &mut outputs);
            world.step(&[wheels(outputs[0], outputs[1])]);
            steps += 1;
        }
        Outcome::ended(world.robots()[0].pos, goal, steps, |d2| d2 <= r2)
    }
}

maze_task!(MazeTask);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wheels_map_forward_and_turn_onto_the_differential_drive() {
        assert_eq!(wheels(0.5, 1.0), [1.0, 1.0]);
        assert_eq!(wheels(0.5, 0.5), [0.0, 0.0]);
        assert_eq!(wheels(1.0, 0.5), [1.0, -1.0], "turn > 0.5 turns right");
        assert_eq!(wheels(0.0, 0.5), [-1.0, 1.0]);
    }

    #[test]
    fn standing_still_ends_where_it_started_unsolved() {
        let task = MazeTask::shipped(Maze::Hard).unwrap();
        let out = task.run(|_, o| o.copy_from_slice(&[0.5, 0.5]));
        assert_eq!(out.end, task.start());
        assert!(!out.solved);
        assert_eq!(out.steps, STEPS);
        assert_eq!(
            out.fitness(),
            FITNESS_BIAS - task.start().distance(task.goal())
        );
    }

    #[test]
    fn inputs_are_rays_radar_and_bias() {
        let task = MazeTask::shipped(Maze::Hard).unwrap();
        let mut first = None;
        task.run(|i, o| {
            first.get_or_insert_with(|| i.to_vec());
            o.fill(0.5);
        });
        let i = first.unwrap();
        assert_eq!(i.len(), INPUTS);
        assert_eq!(i[10], 1.0, "bias");
        // Facing +x at (36, 184) with the goal at (31, 20): the goal is to the left.
        assert_eq!(&i[6..10], &[1.0, 0.0, 0.0, 0.0]);
        // The bottom wall (y = 200) is 16 px to the right: 8 px from the rim.
        assert!((i[4] - (1.0 - 7.5 / 92.0)).abs() < 0.02, "{}", i[4]);
        assert!(i.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn evaluation_reports_end_position_and_metrics() {
        let task = MazeTask::shipped(Maze::Medium).unwrap();
        let spec = MazeTask::spec();
        let params = vivae_neat::NeatParams::plain_neat();
        let pop = vivae_neat::Population::new(params, spec, 3).unwrap();
        let ctx = EvalContext {
            generation: 0,
            index: 0,
            seed: 0,
        };
        let e = task.evaluate(&pop.genomes()[0], &ctx);
        assert_eq!(e.behaviour.len(), 2);
        assert_eq!(e.metrics.len(), METRICS.len());
        let out = task.outcome(&pop.genomes()[0]);
        assert_eq!(e.behaviour, [out.end.x, out.end.y]);
        assert_eq!(e.fitness, out.fitness());
        assert_eq!(task.evaluate(&pop.genomes()[0], &ctx), e, "deterministic");
    }

    #[test]
    fn a_scenario_without_goal_or_with_two_robots_is_refused() {
        let no_goal = HARD_MAZE_SVG.replace("id=\"goal\"", "id=\"exit\"");
        let sc = Scenario::from_svg(&no_goal, "m.svg", &LoadOptions::default()).unwrap();
        let err = MazeTask::new(&sc).unwrap_err().to_string();
        assert!(err.contains("m.svg") && err.contains("goal"), "{err}");
        let sc = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default());
        let err = MazeTask::new(&sc.unwrap()).unwrap_err().to_string();
        assert!(err.contains("exactly one robot"), "{err}");
    }
}

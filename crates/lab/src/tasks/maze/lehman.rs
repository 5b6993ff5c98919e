//! Lehman's maze navigator, the robot of the maze benchmark as his released
//! code simulates it (github.com/jal278/novelty-search-cpp at 9f53ede:
//! `maze.h`'s `Character` and `Environment`, `noveltyexp.cpp`'s `mazesim`).
//!
//! Each step: the outputs o₁, o₂ ∈ (0, 1) change the angular velocity by
//! o₁ − 0.5 degrees per step and the speed by o₂ − 0.5 units per step, both
//! clamped to [−3, 3]; the robot moves `speed` along its *old* heading, then
//! turns by the angular velocity (heading wrapped to 0…360); a move that
//! would bring its centre within its radius 8 of any wall is not made (the
//! robot stays put and keeps its speed). Six rangefinders at −90, −45, 0,
//! 45, 90 and −180° read the distance from the centre to the nearest wall
//! along 100 units, divided by 100 (1 = nothing in reach); four radar pie
//! slices (ahead −45…45°, right 45…135°, behind, left) fire 1 for the one
//! holding the goal. The maze is solved when the centre comes within 5 of
//! the goal; the robot then stops (we end the episode there).
//!
//! The released code has quirks that the paper does not describe
//! (`maze.quirks = true`, the default, reproduces them): the radar's four
//! values are written over the inputs from the backward rangefinder's on,
//! so the network never sees the −180° rangefinder; the eleventh input is
//! never written (we feed 0); and before the first step the network is
//! activated ten times on the first inputs. `quirks = false` feeds the six
//! rangefinders, four radar slices and the bias the paper lists and
//! activates once per step. Lehman computes in `float` with π = 3.1415926;
//! we compute in f64 with the same π.

use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::math::{atan2, cos, sin};
use vivae_neat::{EvalContext, Genome};
use vivae_sim::DVec2;

use super::config::{Collision, MazeConfig};
use super::walls::{LehmanMaze, Segment};
use super::{INPUTS, METRICS, OUTPUTS, Outcome};

/// π as Lehman's code writes it (its degree ↔ radian conversions): kept,
/// not `PI`, so that headings convert as in his simulator.
#[allow(clippy::approx_constant)]
const LEHMAN_PI: f64 = 3.1415926;
/// The robot's radius.
pub const RADIUS: f64 = 8.0;
/// The rangefinders' reach from the centre.
pub const RANGE: f64 = 100.0;
/// Top speed (units per step) and top angular velocity (degrees per step).
pub const MAX_RATE: f64 = 3.0;
/// The rangefinders' angles from the heading, degrees, in Lehman's order.
pub const RANGEFINDERS: [f64; 6] = [-90.0, -45.0, 0.0, 45.0, 90.0, -180.0];
/// Activations on the first inputs before the first step (`mazesimIni`).
pub const WARM_UP_ACTIVATIONS: usize = 10;

/// The navigator's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Navigator {
    /// Centre.
    pub pos: DVec2,
    /// Heading, degrees (0 = +x, clockwise on screen).
    pub heading: f64,
    /// Speed, units per step.
    pub speed: f64,
    /// Angular velocity, degrees per step.
    pub ang_vel: f64,
}

/// The maze task with Lehman's robot.
#[derive(Debug, Clone)]
pub struct LehmanTask {
    maze: LehmanMaze,
    quirks: bool,
    collision: Collision,
    steps: u32,
}

impl LehmanTask {
    /// `maze` with the robot options of `config` for `steps` steps.
    pub fn new(maze: LehmanMaze, config: &MazeConfig, steps: u32) -> LehmanTask {
        LehmanTask {
            maze,
            quirks: config.quirks,
            collision: config.collision,
            steps,
        }
    }

    /// A shipped maze with Lehman's walls, his code's quirks, 400 steps.
    pub fn shipped(maze: super::Maze) -> LehmanTask {
        LehmanTask::new(
            LehmanMaze::shipped(maze),
            &MazeConfig::default(),
            super::STEPS,
        )
    }

    /// The maze.
    pub fn maze(&self) -> &LehmanMaze {
        &self.maze
    }

    /// Steps of one episode (fewer when the robot reaches the goal).
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// The navigator at the start.
    pub fn start(&self) -> Navigator {
        Navigator {
            pos: self.maze.start,
            heading: self.maze.heading,
            speed: 0.0,
            ang_vel: 0.0,
        }
    }

    /// The distance from `pos` along `degrees` (absolute) to the nearest wall, at most [`RANGE`].
    fn range(&self, pos: DVec2, degrees: f64) -> f64 {
        let rad = degrees / 180.0 * LEHMAN_PI;
        let end = pos + DVec2::new(cos(rad), sin(rad)) * RANGE;
        (self.maze.walls.iter())
            .filter_map(|w| w.crossing(pos, end))
            .map(|hit| hit.distance(pos))
            .fold(RANGE, f64::min)
    }

    /// Writes the network's inputs for navigator `n` (see the module's doc).
    pub fn inputs(&self, n: &Navigator, inputs: &mut [f64; INPUTS]) {
        inputs[0] = 1.0;
        for (k, a) in RANGEFINDERS.iter().enumerate() {
            inputs[1 + k] = self.range(n.pos, n.heading + a) / RANGE;
        }
        // The goal's angle from the heading in Lehman's −90…270 degrees.
        let to_goal = self.maze.goal - n.pos;
        let mut angle = atan2(to_goal.y, to_goal.x) / LEHMAN_PI * 180.0 - n.heading;
        angle = angle.rem_euclid(360.0);
        if angle >= 270.0 {
            angle -= 360.0;
        }
        // Lehman's slices start at 315, 45, 135, 225 and span 90 degrees.
        let first = if self.quirks { 6 } else { 7 };
        for (k, lo) in [315.0, 45.0, 135.0, 225.0].into_iter().enumerate() {
            let inside = |a: f64| a >= lo && a < lo + 90.0;
            inputs[first + k] = f64::from(u8::from(inside(angle) || inside(angle + 360.0)));
        }
        if self.quirks {
            inputs[INPUTS - 1] = 0.0;
        }
    }

    /// Whether a centre at `p` is within the radius of a wall.
    fn collides(&self, p: DVec2) -> bool {
        self.maze
            .walls
            .iter()
            .any(|w: &Segment| w.distance(p) < RADIUS)
    }

    /// One step of `n` on outputs `o` (Lehman's `interpret_outputs` then `Update`).
    pub fn step(&self, n: &mut Navigator, o: &[f64; OUTPUTS]) {
        n.ang_vel = (n.ang_vel + (o[0] - 0.5)).clamp(-MAX_RATE, MAX_RATE);
        n.speed = (n.speed + (o[1] - 0.5)).clamp(-MAX_RATE, MAX_RATE);
        let rad = n.heading / 180.0 * LEHMAN_PI;
        let v = DVec2::new(cos(rad), sin(rad)) * n.speed;
        n.heading += n.ang_vel;
        if n.heading > 360.0 {
            n.heading -= 360.0;
        }
        if n.heading < 0.0 {
            n.heading += 360.0;
        }
        let candidates: &[DVec2] = match self.collision {
            Collision::Stop => &[v],
            Collision::Slide => &[v, DVec2::new(v.x, 0.0), DVec2::new(0.0, v.y)],
        };
        if let Some(free) = (candidates.iter())
            .map(|&d| n.pos + d)
            .find(|&p| !self.collides(p))
        {
            n.pos = free;
        }
    }

    /// Runs one episode: `controller(inputs, outputs)` is asked each step
    /// (and, with the quirks, ten more times on the first inputs before the
    /// first step); outputs: angular velocity, speed in (0, 1).
    /// Allocation-free.
    pub fn run(&self, mut controller: impl FnMut(&[f64], &mut [f64])) -> Outcome {
        let mut n = self.start();
        let r2 = self.maze.goal_radius * self.maze.goal_radius;
        let mut inputs = [0.0; INPUTS];
        let mut outputs = [0.0; OUTPUTS];
        let mut steps = 0;
        if self.quirks {
            self.inputs(&n, &mut inputs);
            for _ in 0..WARM_UP_ACTIVATIONS {
                controller(&inputs, &mut outputs);
            }
        }
        // Lehman's `dist < 5.0` is checked after each step (never at the start).
        while steps < self.steps {
            self.inputs(&n, &mut inputs);
            controller(&inputs, &mut outputs);
            self.step(&mut n, &outputs);
            steps += 1;
            if n.pos.distance_squared(self.maze.goal) < r2 {
                break;
            }
        }
        Outcome::ended(n.pos, self.maze.goal, steps, |d2| d2 < r2)
    }
}

super::maze_task!(LehmanTask);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::maze::Maze;

    #[test]
    fn first_inputs_are_lehmans_with_the_radar_over_the_backward_rangefinder() {
        let task = LehmanTask::shipped(Maze::Hard);
        let mut i = [0.0; INPUTS];
        task.inputs(&task.start(), &mut i);
        // At (36, 184) facing +x, the goal (31, 20) is up: 268.3° from the heading, the left slice.
        assert_eq!(i[0], 1.0);
        assert_eq!(&i[6..], &[0.0, 0.0, 0.0, 1.0, 0.0]);
        // Ahead along y = 184: the wall (77, 201)–(108, 164) at x ≈ 91.24.
        assert!((i[3] - (91.243 - 36.0) / 100.0).abs() < 1e-4, "{}", i[3]);
        // Right (+90°, down): the bottom wall (7, 202)–(195, 198) at y ≈ 201.4.
        assert!((i[5] - 0.174).abs() < 0.005, "{}", i[5]);
        let paper = LehmanTask::new(
            LehmanMaze::shipped(Maze::Hard),
            &MazeConfig {
                quirks: false,
                ..MazeConfig::default()
            },
            400,
        );
        let mut p = [0.0; INPUTS];
        paper.inputs(&paper.start(), &mut p);
        assert_eq!(&p[..6], &i[..6]);
        assert_eq!(
            &p[7..],
            &[0.0, 0.0, 0.0, 1.0],
            "radar after all six rangefinders"
        );
    }

    #[test]
    fn the_robot_integrates_speed_turns_after_moving_and_stops_at_walls() {
        let task = LehmanTask::shipped(Maze::Hard);
        let mut n = task.start();
        task.step(&mut n, &[1.0, 1.0]);
        // Speed 0.5 along the old heading 0, then the heading turns by 0.5°.
        assert_eq!(
            (n.pos, n.speed, n.ang_vel, n.heading),
            (DVec2::new(36.5, 184.0), 0.5, 0.5, 0.5)
        );
        for _ in 0..10 {
            task.step(&mut n, &[1.0, 1.0]);
        }
        assert_eq!((n.speed, n.ang_vel), (3.0, 3.0), "clamped");
        // Straight down into the bottom wall: it stops 8 short and keeps its speed.
        let mut n = Navigator {
            heading: 90.0,
            ..task.start()
        };
        for _ in 0..40 {
            task.step(&mut n, &[0.5, 1.0]);
        }
        assert_eq!(n.speed, 3.0);
        assert!(
            n.pos.y < 201.4 - RADIUS && n.pos.y > 201.4 - RADIUS - 3.0,
            "{}",
            n.pos.y
        );
    }

    #[test]
    fn quirks_warm_the_network_up_ten_times_on_the_first_inputs() {
        let calls = |quirks| {
            let config = MazeConfig {
                quirks,
                ..MazeConfig::default()
            };
            let task = LehmanTask::new(LehmanMaze::shipped(Maze::Medium), &config, 400);
            let mut n = 0;
            let out = task.run(|_, o| {
                n += 1;
                o.fill(0.5);
            });
            assert_eq!((out.steps, out.end), (400, task.start().pos));
            n
        };
        assert_eq!((calls(true), calls(false)), (410, 400));
    }
}

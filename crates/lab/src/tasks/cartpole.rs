//! CartPole-v1 with Gymnasium's dynamics (`gymnasium/envs/classic_control/
//! cartpole.py`): float64 state, explicit Euler, its constants, termination
//! at |x| > 2.4 or |θ| > 12°, truncation after 500 steps, reward 1 a step.
//! Its sin and cos are vivae's portable ones. An evaluation is 5 episodes,
//! each starting uniformly within ±0.05 (from the evaluation's seed);
//! fitness is their mean return, solved at Gymnasium's
//! `reward_threshold` of 475. The network reads the observation (float32, as
//! Gymnasium returns it) and a bias; action = argmax of its two outputs.

use vivae_neat::math::{cos, sin};

use super::TaskEntry;
use super::classic::{Classic, Draws, argmax};
use super::plain::{Described, entry};
use super::sketch::{Shape, Sketch};

/// The task's registration (`--task cartpole`).
pub static TASK: TaskEntry = entry::<CartPole>();

const GRAVITY: f64 = 9.8;
const MASSCART: f64 = 1.0;
const MASSPOLE: f64 = 0.1;
const TOTAL_MASS: f64 = MASSPOLE + MASSCART;
const LENGTH: f64 = 0.5;
const POLEMASS_LENGTH: f64 = MASSPOLE * LENGTH;
const FORCE_MAG: f64 = 10.0;
const TAU: f64 = 0.02;
const THETA_THRESHOLD: f64 = 12.0 * 2.0 * std::f64::consts::PI / 360.0;
const X_THRESHOLD: f64 = 2.4;

/// CartPole-v1 as a plain task.
#[derive(Debug, Clone, Copy)]
pub struct CartPole;

/// One step of Gymnasium's Euler integration, in its order of operations.
pub fn step([x, x_dot, theta, theta_dot]: [f64; 4], push_right: bool) -> [f64; 4] {
    let force = if push_right { FORCE_MAG } else { -FORCE_MAG };
    let (costheta, sintheta) = (cos(theta), sin(theta));
    let temp = (force + POLEMASS_LENGTH * (theta_dot * theta_dot) * sintheta) / TOTAL_MASS;
    let thetaacc = (GRAVITY * sintheta - costheta * temp)
        / (LENGTH * (4.0 / 3.0 - MASSPOLE * (costheta * costheta) / TOTAL_MASS));
    let xacc = temp - POLEMASS_LENGTH * thetaacc * costheta / TOTAL_MASS;
    [
        x + TAU * x_dot,
        x_dot + TAU * xacc,
        theta + TAU * theta_dot,
        theta_dot + TAU * thetaacc,
    ]
}

/// Whether the pole fell or the cart left the track.
// Gymnasium's four comparisons (a NaN state is not terminated there either).
#[allow(clippy::manual_range_contains)]
pub fn terminated([x, _, theta, _]: [f64; 4]) -> bool {
    x < -X_THRESHOLD || x > X_THRESHOLD || theta < -THETA_THRESHOLD || theta > THETA_THRESHOLD
}

/// The cart at `x` with its pole at `theta` (from the observation), and
/// the push its outputs choose, as an arrow into the cart's side.
fn picture(inputs: &[f64], outputs: &[f64], shapes: &mut Vec<Shape>) {
    let (x, theta) = (inputs[0], inputs[2]);
    let (half_width, half_height) = (0.2, 0.12);
    shapes.push(Shape::Polygon {
        points: vec![
            [x - half_width, -half_height],
            [x + half_width, -half_height],
            [x + half_width, half_height],
            [x - half_width, half_height],
        ],
        colour: "#000000",
    });
    let axle = [x, half_height / 2.0];
    let upright = std::f64::consts::FRAC_PI_2;
    shapes.push(Shape::bar(
        axle,
        upright - theta,
        2.0 * LENGTH,
        0.08,
        "#ca9865",
    ));
    shapes.push(Shape::Circle {
        centre: axle,
        radius: 0.04,
        colour: "#8184cb",
    });
    let side = if CartPole::act(outputs) { -1.0 } else { 1.0 };
    let (from, to) = (x + side * 0.5, x + side * (half_width + 0.02));
    shapes.extend(Shape::arrow([from, 0.0], [to, 0.0], 0.03, "#d32f2f"));
}

impl Described for CartPole {
    const NAME: &'static str = "cartpole";
    const ABOUT: &'static str = "CartPole-v1 (Gymnasium's dynamics)";
    const SCORING: &'static str = "fitness = the mean return of 5 episodes (1 a step, at most 500)";
    const INPUTS: usize = 5;
    const OUTPUTS: usize = 2;
    const OUTPUT_MEANING: &'static str = "CartPole-v1's action = argmax: out[0] >= out[1] pushes left (0), else right (1); inputs x, x_dot, theta, theta_dot, 1";
}

impl Classic for CartPole {
    const BEHAVIOUR: &'static [&'static str] = &["x", "theta"];
    const THRESHOLD: f64 = 475.0;
    type State = [f64; 4];
    type Action = bool;
    const MAX_STEPS: u32 = 500;

    /// Each coordinate uniform in [−0.05, 0.05).
    fn start(draws: &mut Draws) -> [f64; 4] {
        [0; 4].map(|_| draws.uniform(-0.05, 0.05))
    }

    fn act(outputs: &[f64]) -> bool {
        argmax(outputs) == 1
    }

    fn step(s: [f64; 4], push_right: bool) -> ([f64; 4], f64, bool) {
        let next = step(s, push_right);
        (next, 1.0, terminated(next))
    }

    fn place(o: &[f64]) -> [f64; 2] {
        [
            ((o[0] / X_THRESHOLD + 1.0) / 2.0).clamp(0.0, 1.0),
            ((o[2] / THETA_THRESHOLD + 1.0) / 2.0).clamp(0.0, 1.0),
        ]
    }

    /// Gymnasium's picture: the track with its ends at ±2.4, the cart, the
    /// pole (its full length, 2 × 0.5 m) and the push as an arrow.
    fn sketch() -> Option<Sketch> {
        let end = |x: f64| Shape::segment([x, -0.3], [x, 0.3], 0.02, "#9e9e9e");
        Some(Sketch {
            view: [-2.8, -0.5, 2.8, 1.3],
            backdrop: vec![
                Shape::segment([-2.8, -0.12], [2.8, -0.12], 0.01, "#000000"),
                end(-X_THRESHOLD),
                end(X_THRESHOLD),
            ],
            frame: picture,
        })
    }
}

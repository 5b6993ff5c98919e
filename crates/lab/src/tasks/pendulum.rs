//! Pendulum-v1 with Gymnasium's dynamics (`gymnasium/envs/classic_control/
//! pendulum.py`): a pendulum swung up by a torque in [−2, 2], float64 state,
//! one explicit step of 0.05 s, speed clipped at ±8; reward −(θ² + 0.1·θ'² +
//! 0.001·u²) with θ normalised into [−π, π); never terminated, truncated
//! after 200 steps. Its sin, cos and remainder are vivae's portable ones; the
//! torque is float32 (its action space's type) and, by NumPy 2's rules,
//! `3.0·u` and `0.001·u²` are computed in float32 as Gymnasium computes them.
//! An evaluation is 5 episodes, each starting as Gymnasium's `reset` draws
//! it (θ uniform in [−π, π), θ' in [−1, 1)) but from the evaluation's seed;
//! fitness is their mean return. Gymnasium gives Pendulum no
//! `reward_threshold`; the bar here is a mean return of −200. Hanging still
//! costs π² ≈ 9.9 a step (−1974 an episode) and standing still upright 0,
//! so −200 asks that the pendulum be swung up within the first few dozen
//! steps and held there, from every start, with little torque spent. The
//! network reads the observation (cos θ, sin θ, θ', float32) and a bias; the
//! torque is 2·`out[0]` (its one output, a bipolar sigmoid in [−1, 1])
//! rounded to float32.

use std::f64::consts::PI;

use vivae_neat::math::{cos, fmod, sin};

use super::TaskEntry;
use super::classic::{Classic, Draws, clip};
use super::plain::{Described, entry};
use super::sketch::{Shape, Sketch};

/// The task's registration (`--task pendulum`).
pub static TASK: TaskEntry = entry::<Pendulum>();

const MAX_SPEED: f64 = 8.0;
const MAX_TORQUE: f64 = 2.0;
const DT: f64 = 0.05;
const G: f64 = 10.0;
const M: f64 = 1.0;
const L: f64 = 1.0;

/// Pendulum-v1 as a plain task.
#[derive(Debug, Clone, Copy)]
pub struct Pendulum;

/// NumPy's float64 `%` (Python's: the result takes the divisor's sign).
fn remainder(a: f64, b: f64) -> f64 {
    let m = fmod(a, b);
    if m == 0.0 {
        0.0f64.copysign(b)
    } else if (b < 0.0) != (m < 0.0) {
        m + b
    } else {
        m
    }
}

/// θ into [−π, π) as Gymnasium's `angle_normalize` does.
fn angle_normalize(x: f64) -> f64 {
    remainder(x + PI, 2.0 * PI) - PI
}

/// One step of Gymnasium's Pendulum-v1 under torque `u` (the float32 its
/// action space holds), in its order of operations and types: the next
/// (θ, θ') and the reward.
pub fn step([th, thdot]: [f64; 2], u: f32) -> ([f64; 2], f64) {
    // `np.clip` of a float32 array by Python floats: float32, NaN kept.
    let (low, high) = (-MAX_TORQUE as f32, MAX_TORQUE as f32);
    let u = if u < low {
        low
    } else if u > high {
        high
    } else {
        u
    };
    let an = angle_normalize(th);
    let costs = an * an + 0.1 * (thdot * thdot) + f64::from((0.001f64 as f32) * (u * u));
    let torque = f64::from((3.0 / (M * (L * L))) as f32 * u);
    let newthdot = thdot + (3.0 * G / (2.0 * L) * sin(th) + torque) * DT;
    let newthdot = clip(newthdot, -MAX_SPEED, MAX_SPEED);
    let newth = th + newthdot * DT;
    ([newth, newthdot], -costs)
}

/// The rod from the observation (cos θ, sin θ) and the torque chosen.
fn picture(inputs: &[f64], outputs: &[f64], shapes: &mut Vec<Shape>) {
    let (c, s) = (inputs[0], inputs[1]);
    shapes.push(Shape::segment([0.0, 0.0], [-L * s, L * c], 0.2, "#cc4d4d"));
    shapes.push(Shape::Circle {
        centre: [0.0, 0.0],
        radius: 0.05,
        colour: "#000000",
    });
    let u = f64::from(Pendulum::act(outputs));
    let down = -std::f64::consts::FRAC_PI_2;
    shapes.extend(Shape::turn(
        [0.0, 0.0],
        0.35,
        down,
        0.5 * u / MAX_TORQUE,
        0.04,
        "#333333",
    ));
}

impl Described for Pendulum {
    const NAME: &'static str = "pendulum";
    const ABOUT: &'static str = "Pendulum-v1 (Gymnasium's dynamics)";
    const SCORING: &'static str = "fitness = the mean return of 5 episodes of 200 steps (minus the angle^2, 0.1 speed^2, 0.001 torque^2 a step); no Gymnasium threshold: -200 here";
    const INPUTS: usize = 4;
    const OUTPUTS: usize = 1;
    const OUTPUT_MEANING: &'static str = "Pendulum-v1's torque = 2*out[0] as float32 (out[0] a bipolar sigmoid, in [-1, 1]); inputs cos theta, sin theta, theta', 1";
}

impl Classic for Pendulum {
    const BEHAVIOUR: &'static [&'static str] = &["height", "speed"];
    const THRESHOLD: f64 = -200.0;
    const THRESHOLD_SOURCE: &'static str =
        "Gymnasium gives none; vivae's bar (docs/howto/classic-control.md)";
    type State = [f64; 2];
    type Action = f32;
    const MAX_STEPS: u32 = 200;

    /// θ uniform in [−π, π), θ' in [−1, 1).
    fn start(draws: &mut Draws) -> [f64; 2] {
        [draws.uniform(-PI, PI), draws.uniform(-1.0, 1.0)]
    }

    fn observe([th, thdot]: &[f64; 2], obs: &mut [f64]) {
        obs.copy_from_slice(&[cos(*th), sin(*th), *thdot]);
    }

    fn act(outputs: &[f64]) -> f32 {
        (MAX_TORQUE * outputs[0]) as f32
    }

    fn step(s: [f64; 2], u: f32) -> ([f64; 2], f64, bool) {
        let (next, reward) = step(s, u);
        (next, reward, false)
    }

    /// How high the pendulum is and how fast it turns, each in [0, 1].
    fn place(o: &[f64]) -> [f64; 2] {
        [(o[0] + 1.0) / 2.0, (o[2].abs() / MAX_SPEED).clamp(0.0, 1.0)]
    }

    /// Gymnasium's picture: the rod from its pivot (θ = 0 upright, θ
    /// anticlockwise) and the torque as a curved arrow as long as it is strong.
    fn sketch() -> Option<Sketch> {
        Some(Sketch {
            view: [-1.4, -1.4, 1.4, 1.4],
            backdrop: vec![Shape::segment([-0.25, 1.0], [0.25, 1.0], 0.01, "#9e9e9e")],
            frame: picture,
        })
    }
}

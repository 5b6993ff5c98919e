//! Acrobot-v1 with Gymnasium's dynamics (`gymnasium/envs/classic_control/
//! acrobot.py`, its default "book" equations): two links, torque −1, 0 or +1
//! on the joint between them, float64 state integrated by one fourth-order
//! Runge–Kutta step of 0.2 s, angles wrapped into [−π, π], velocities bounded
//! at ±4π and ±9π; reward −1 a step (0 on the terminating one), terminated
//! when the free end rises above the bar (−cos θ1 − cos(θ1 + θ2) > 1),
//! truncated after 500 steps. Its sin and cos are vivae's portable ones. An
//! evaluation is 5 episodes, each starting as Gymnasium's `reset` draws it
//! (the four state variables uniform in [−0.1, 0.1), rounded to float32)
//! but from the evaluation's seed; fitness is their mean return, solved at
//! Gymnasium's `reward_threshold` of −100. The network reads the observation
//! (cos θ1, sin θ1, cos θ2, sin θ2, θ1', θ2', float32 as Gymnasium returns
//! it) and a bias; the action is the argmax of its three outputs (torque −1,
//! 0, +1; the first on a tie).

use std::f64::consts::PI;

use vivae_neat::math::{atan2, cos, sin};

use super::TaskEntry;
use super::classic::{Classic, Draws, argmax};
use super::plain::{Described, entry};
use super::sketch::{Shape, Sketch};

/// The task's registration (`--task acrobot`).
pub static TASK: TaskEntry = entry::<Acrobot>();

const DT: f64 = 0.2;
const LINK_LENGTH_1: f64 = 1.0;
/// The second link's length (only drawn: the book dynamics do not use it).
const LINK_LENGTH_2: f64 = 1.0;
const LINK_MASS_1: f64 = 1.0;
const LINK_MASS_2: f64 = 1.0;
const LINK_COM_POS_1: f64 = 0.5;
const LINK_COM_POS_2: f64 = 0.5;
const LINK_MOI: f64 = 1.0;
const G: f64 = 9.8;
const MAX_VEL_1: f64 = 4.0 * PI;
const MAX_VEL_2: f64 = 9.0 * PI;
const AVAIL_TORQUE: [f64; 3] = [-1.0, 0.0, 1.0];

/// Acrobot-v1 as a plain task.
#[derive(Debug, Clone, Copy)]
pub struct Acrobot;

/// The time derivative of (θ1, θ2, θ1', θ2', torque): Gymnasium's `_dsdt`
/// ("book" dynamics), in its order of operations.
fn dsdt(s: [f64; 5]) -> [f64; 5] {
    let (m1, m2, l1, lc1, lc2) = (
        LINK_MASS_1,
        LINK_MASS_2,
        LINK_LENGTH_1,
        LINK_COM_POS_1,
        LINK_COM_POS_2,
    );
    let (i1, i2) = (LINK_MOI, LINK_MOI);
    let [theta1, theta2, dtheta1, dtheta2, a] = s;
    let sin2 = sin(theta2);
    let d1 = m1 * (lc1 * lc1) + m2 * (l1 * l1 + lc2 * lc2 + 2.0 * l1 * lc2 * cos(theta2)) + i1 + i2;
    let d2 = m2 * (lc2 * lc2 + l1 * lc2 * cos(theta2)) + i2;
    let phi2 = m2 * lc2 * G * cos(theta1 + theta2 - PI / 2.0);
    let phi1 = -m2 * l1 * lc2 * (dtheta2 * dtheta2) * sin2
        - 2.0 * m2 * l1 * lc2 * dtheta2 * dtheta1 * sin2
        + (m1 * lc1 + m2 * l1) * G * cos(theta1 - PI / 2.0)
        + phi2;
    let ddtheta2 = (a + d2 / d1 * phi1 - m2 * l1 * lc2 * (dtheta1 * dtheta1) * sin2 - phi2)
        / (m2 * (lc2 * lc2) + i2 - (d2 * d2) / d1);
    let ddtheta1 = -(d2 * ddtheta2 + phi1) / d1;
    [dtheta1, dtheta2, ddtheta1, ddtheta2, 0.0]
}

/// `y + h·k`, element by element.
fn ahead(y: [f64; 5], h: f64, k: [f64; 5]) -> [f64; 5] {
    std::array::from_fn(|i| y[i] + h * k[i])
}

/// `x` wrapped into [`m`, `M`] as Gymnasium's `wrap` does.
fn wrap(mut x: f64, m: f64, big_m: f64) -> f64 {
    let diff = big_m - m;
    while x > big_m {
        x -= diff;
    }
    while x < m {
        x += diff;
    }
    x
}

/// `x` bounded to [`m`, `M`] as Gymnasium's `bound` does (Python's `min(max(x, m), M)`).
fn bound(x: f64, m: f64, big_m: f64) -> f64 {
    let lower = if m > x { m } else { x };
    if big_m < lower { big_m } else { lower }
}

/// One step of Gymnasium's Acrobot under torque `AVAIL_TORQUE[action]`: its
/// `rk4` over [0, dt], then the wrap and the bounds, in its order of operations.
pub fn step(s: [f64; 4], action: usize) -> [f64; 4] {
    let y0 = [s[0], s[1], s[2], s[3], AVAIL_TORQUE[action]];
    let (dt, dt2) = (DT - 0.0, DT / 2.0);
    let k1 = dsdt(y0);
    let k2 = dsdt(ahead(y0, dt2, k1));
    let k3 = dsdt(ahead(y0, dt2, k2));
    let k4 = dsdt(ahead(y0, dt, k3));
    let ns: [f64; 5] =
        std::array::from_fn(|i| y0[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    [
        wrap(ns[0], -PI, PI),
        wrap(ns[1], -PI, PI),
        bound(ns[2], -MAX_VEL_1, MAX_VEL_1),
        bound(ns[3], -MAX_VEL_2, MAX_VEL_2),
    ]
}

/// Whether the free end is above the bar (Gymnasium's `_terminal`).
pub fn terminated(s: [f64; 4]) -> bool {
    -cos(s[0]) - cos(s[1] + s[0]) > 1.0
}

/// The two links from the observation (cos and sin of θ1 and θ2; θ1 = 0
/// hangs straight down, both angles anticlockwise) and the torque chosen.
fn picture(inputs: &[f64], outputs: &[f64], shapes: &mut Vec<Shape>) {
    let [c1, s1, c2, s2] = [inputs[0], inputs[1], inputs[2], inputs[3]];
    let (c12, s12) = (c1 * c2 - s1 * s2, s1 * c2 + c1 * s2);
    let p1 = [LINK_LENGTH_1 * s1, -LINK_LENGTH_1 * c1];
    let p2 = [p1[0] + LINK_LENGTH_2 * s12, p1[1] - LINK_LENGTH_2 * c12];
    for (a, b) in [([0.0, 0.0], p1), (p1, p2)] {
        shapes.push(Shape::segment(a, b, 0.2, "#00cccc"));
    }
    for p in [[0.0, 0.0], p1] {
        shapes.push(Shape::Circle {
            centre: p,
            radius: 0.1,
            colour: "#cccc00",
        });
    }
    let torque = AVAIL_TORQUE[Acrobot::act(outputs)];
    let along = atan2(-c12, s12);
    shapes.extend(Shape::turn(p1, 0.35, along, 0.6 * torque, 0.04, "#d32f2f"));
}

impl Described for Acrobot {
    const NAME: &'static str = "acrobot";
    const ABOUT: &'static str = "Acrobot-v1 (Gymnasium's dynamics)";
    const SCORING: &'static str = "fitness = the mean return of 5 episodes (-1 a step until the end is above the bar, at most 500 steps)";
    const INPUTS: usize = 7;
    const OUTPUTS: usize = 3;
    const OUTPUT_MEANING: &'static str = "Acrobot-v1's action = argmax of out[0..3] (torque -1, 0, +1; the first on a tie); inputs cos t1, sin t1, cos t2, sin t2, t1', t2', 1";
}

impl Classic for Acrobot {
    const BEHAVIOUR: &'static [&'static str] = &["cos_t1", "t1_velocity"];
    const THRESHOLD: f64 = -100.0;
    // Its episodes one by one: side by side in lanes was measured no faster.
    const LANES: bool = false;
    type State = [f64; 4];
    type Action = usize;
    const MAX_STEPS: u32 = 500;

    /// θ1, θ2, θ1', θ2' uniform in [−0.1, 0.1), rounded to float32 as Gymnasium's `reset` does.
    fn start(draws: &mut Draws) -> [f64; 4] {
        [0; 4].map(|_| f64::from(draws.uniform(-0.1, 0.1) as f32))
    }

    fn observe(s: &[f64; 4], obs: &mut [f64]) {
        obs.copy_from_slice(&[cos(s[0]), sin(s[0]), cos(s[1]), sin(s[1]), s[2], s[3]]);
    }

    fn act(outputs: &[f64]) -> usize {
        argmax(outputs)
    }

    fn step(s: [f64; 4], a: usize) -> ([f64; 4], f64, bool) {
        let next = step(s, a);
        let done = terminated(next);
        (next, if done { 0.0 } else { -1.0 }, done)
    }

    /// How high the first link is and how fast it swings, each in [0, 1].
    fn place(o: &[f64]) -> [f64; 2] {
        [
            (1.0 - o[0]) / 2.0,
            ((o[4] / MAX_VEL_1 + 1.0) / 2.0).clamp(0.0, 1.0),
        ]
    }

    /// Gymnasium's picture: the bar the free end must rise above, the two
    /// links hanging from the fixed joint, and the torque on the middle
    /// joint as a curved arrow.
    fn sketch() -> Option<Sketch> {
        Some(Sketch {
            view: [-2.2, -2.2, 2.2, 2.2],
            backdrop: vec![Shape::segment([-2.2, 1.0], [2.2, 1.0], 0.02, "#000000")],
            frame: picture,
        })
    }
}

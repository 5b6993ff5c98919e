//! MountainCarContinuous-v0 with Gymnasium's dynamics (`gymnasium/envs/
//! classic_control/continuous_mountain_car.py`): the car of MountainCar
//! pushed with a force in [−1, 1] (power 0.0015); reward 100 on reaching
//! position ≥ 0.45, minus 0.1·a² every step; truncated after 999 steps. Its
//! cos is vivae's portable one. Gymnasium keeps the state in float32 after
//! the first step and mixes float32 with Python floats (NumPy 2's rules: a
//! float32 with a Python float computes in float32); the step follows those
//! types operation by operation. An evaluation is 5 episodes, each starting
//! as Gymnasium's `reset` draws it (position uniform in [−0.6, −0.4),
//! speed 0) but from the evaluation's seed; fitness is their mean return,
//! solved at Gymnasium's `reward_threshold` of 90. The network reads the
//! observation (position, velocity, float32) and a bias; its one output (a
//! bipolar sigmoid, in [−1, 1]) rounded to float32 is the action, which
//! Gymnasium's clip to [−1, 1] leaves as it is. The behaviour descriptor is
//! MountainCar's: mean position and speed, scaled into [0, 1].

use vivae_neat::math::cos;

use super::TaskEntry;
use super::classic::{Classic, Draws, Values, clip};
use super::hill::{car, sketch};
use super::plain::{Described, entry};
use super::sketch::Sketch;

/// The task's registration (`--task mountain-car-continuous`).
pub static TASK: TaskEntry = entry::<MountainCarContinuous>();

const MIN_POSITION: f64 = -1.2;
const MAX_POSITION: f64 = 0.6;
const MAX_SPEED: f64 = 0.07;
const GOAL_POSITION: f64 = 0.45;
const POWER: f64 = 0.0015;

/// MountainCarContinuous-v0 as a plain task.
#[derive(Debug, Clone, Copy)]
pub struct MountainCarContinuous;

/// The (position, velocity) Gymnasium's env holds: float64 as `reset` sets
/// it, float32 after any step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum State {
    /// As `reset` leaves it (`np.array([uniform, 0])`).
    Reset([f64; 2]),
    /// As a step leaves it (`np.array([...], dtype=np.float32)`).
    Stepped([f32; 2]),
}

impl Values for State {
    /// A float64 state, as `reset` leaves it.
    fn of(values: &[f64]) -> Option<State> {
        values.try_into().ok().map(State::Reset)
    }

    fn values(&self) -> Vec<f64> {
        match self {
            State::Reset(v) => v.to_vec(),
            State::Stepped(v) => v.map(f64::from).to_vec(),
        }
    }

    fn write(&self, out: &mut [f64]) {
        match self {
            State::Reset(v) => out.copy_from_slice(v),
            State::Stepped(v) => out.copy_from_slice(&v.map(f64::from)),
        }
    }
}

/// A Python float cast to float32, as NumPy casts it in an operation with a float32.
fn weak(x: f64) -> f32 {
    x as f32
}

/// One step of Gymnasium's MountainCarContinuous-v0 under force `action`
/// (as the float32 its action space holds), in its order of operations and
/// types: the next state, the reward, whether it terminated.
pub fn step(s: State, action: f32) -> (State, f64, bool) {
    // `min(max(action[0], -1.0), 1.0)`: a float32 inside, a Python float when clipped.
    let clipped = if -1.0 > action {
        Some(-1.0)
    } else if 1.0 < action {
        Some(1.0)
    } else {
        None
    };
    // `force * power - 0.0025 * math.cos(3 * position)`, then `velocity += …`.
    let (position, velocity, terminated) = match s {
        State::Reset([position, velocity]) => {
            let gravity = 0.0025 * cos(3.0 * position);
            let change = match clipped {
                Some(force) => force * POWER - gravity,
                None => f64::from(action * weak(POWER) - weak(gravity)),
            };
            let velocity = clip(velocity + change, -MAX_SPEED, MAX_SPEED);
            let position = clip(position + velocity, MIN_POSITION, MAX_POSITION);
            let velocity = if position == MIN_POSITION && velocity < 0.0 {
                0.0
            } else {
                velocity
            };
            let done = position >= GOAL_POSITION && velocity >= 0.0;
            (position as f32, velocity as f32, done)
        }
        State::Stepped([position, velocity]) => {
            let gravity = 0.0025 * cos(f64::from(3.0 * position));
            let change = match clipped {
                Some(force) => weak(force * POWER - gravity),
                None => action * weak(POWER) - weak(gravity),
            };
            // Clipped values are Python floats; cast back to float32 by
            // every later operation with a float32, they act as these.
            let velocity = clip32(velocity + change, -weak(MAX_SPEED), weak(MAX_SPEED));
            let position = clip32(position + velocity, weak(MIN_POSITION), weak(MAX_POSITION));
            let velocity = if position == weak(MIN_POSITION) && velocity < 0.0 {
                0.0
            } else {
                velocity
            };
            let done = position >= weak(GOAL_POSITION) && velocity >= 0.0;
            (position, velocity, done)
        }
    };
    let mut reward = if terminated { 100.0 } else { 0.0 };
    let a = f64::from(action);
    reward -= a * a * 0.1;
    (State::Stepped([position, velocity]), reward, terminated)
}

/// `x` clipped to [`low`, `high`] in float32 (Gymnasium's `if x > high: x = high`, then the low bound).
fn clip32(x: f32, low: f32, high: f32) -> f32 {
    let x = if x > high { high } else { x };
    if x < low { low } else { x }
}

impl Described for MountainCarContinuous {
    const NAME: &'static str = "mountain-car-continuous";
    const ABOUT: &'static str = "MountainCarContinuous-v0 (Gymnasium's dynamics)";
    const SCORING: &'static str = "fitness = the mean return of 5 episodes (100 at the goal, -0.1*a^2 a step, at most 999 steps)";
    const INPUTS: usize = 3;
    const OUTPUTS: usize = 1;
    const OUTPUT_MEANING: &'static str = "MountainCarContinuous-v0's action = out[0] as float32 (a bipolar sigmoid, in [-1, 1]); inputs position, velocity, 1";
}

impl Classic for MountainCarContinuous {
    const BEHAVIOUR: &'static [&'static str] = &["position", "speed"];
    const THRESHOLD: f64 = 90.0;
    type State = State;
    type Action = f32;
    const MAX_STEPS: u32 = 999;

    /// Position uniform in [−0.6, −0.4), velocity 0, in float64.
    fn start(draws: &mut Draws) -> State {
        State::Reset([draws.uniform(-0.6, -0.4), 0.0])
    }

    fn act(outputs: &[f64]) -> f32 {
        outputs[0] as f32
    }

    fn step(s: State, a: f32) -> (State, f64, bool) {
        step(s, a)
    }

    fn place(o: &[f64]) -> [f64; 2] {
        place(o)
    }

    /// MountainCar's picture, its flag at this goal and the arrow as long as the force.
    fn sketch() -> Option<Sketch> {
        Some(sketch(GOAL_POSITION, |inputs, outputs, shapes| {
            let force = f64::from(MountainCarContinuous::act(outputs)).clamp(-1.0, 1.0);
            car(inputs[0], force, shapes);
        }))
    }
}
/// Where the car is and how fast it goes, each scaled into [0, 1] (its
/// behaviour descriptor, MountainCar's).
fn place(o: &[f64]) -> [f64; 2] {
    [
        ((o[0] - MIN_POSITION) / (MAX_POSITION - MIN_POSITION)).clamp(0.0, 1.0),
        (o[1].abs() / MAX_SPEED).clamp(0.0, 1.0),
    ]
}

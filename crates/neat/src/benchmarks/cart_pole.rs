//! The double pole on a cart as one trial: Wieland's equations, the
//! controller's inputs, failure, Gruau's damping fitness and the scorer —
//! what both [`pole`](super::pole) (the NEAT experiment) and
//! [`pole_lanes`](super::pole_lanes) (trials side by side) step.

use crate::Network;
use crate::math::sin_cos;

const GRAVITY: f64 = -9.8;
const MASS_CART: f64 = 1.0;
const MASS_POLE_1: f64 = 0.1;
const LENGTH_1: f64 = 0.5; // half length
const MASS_POLE_2: f64 = 0.01;
const LENGTH_2: f64 = 0.05;
pub(super) const FORCE_MAG: f64 = 10.0;
pub(super) const TAU: f64 = 0.01;
const MUP: f64 = 0.000002;
const FAIL_ANGLE: f64 = 36.0 * std::f64::consts::PI / 180.0;
/// Steps a controller must balance from the start state to succeed.
pub const SUCCESS_STEPS: u32 = 100_000;

/// Cart-pole state `[x, ẋ, θ1, θ̇1, θ2, θ̇2]`.
pub type State = [f64; 6];

/// Wieland's equations of motion (as in Stanley's NEAT code).
#[inline]
fn derivatives(force: f64, s: &State) -> State {
    let (sin1, cos1) = sin_cos(s[2]);
    let (sin2, cos2) = sin_cos(s[4]);
    derivatives_given(force, s, [sin1, cos1, sin2, cos2])
}

/// [`derivatives`] given `[sin θ1, cos θ1, sin θ2, cos θ2]` (shared with the
/// episodes side by side of [`super::pole_lanes`]: the same operations).
#[inline(always)]
pub(super) fn derivatives_given(force: f64, s: &State, trig: [f64; 4]) -> State {
    let [sin1, cos1, sin2, cos2] = trig;
    let gsin1 = GRAVITY * sin1;
    let gsin2 = GRAVITY * sin2;
    let ml1 = LENGTH_1 * MASS_POLE_1;
    let ml2 = LENGTH_2 * MASS_POLE_2;
    let temp1 = MUP * s[3] / ml1;
    let temp2 = MUP * s[5] / ml2;
    let fi1 = ml1 * s[3] * s[3] * sin1 + 0.75 * MASS_POLE_1 * cos1 * (temp1 + gsin1);
    let fi2 = ml2 * s[5] * s[5] * sin2 + 0.75 * MASS_POLE_2 * cos2 * (temp2 + gsin2);
    let mi1 = MASS_POLE_1 * (1.0 - 0.75 * cos1 * cos1);
    let mi2 = MASS_POLE_2 * (1.0 - 0.75 * cos2 * cos2);
    let xacc = (force + fi1 + fi2) / (mi1 + mi2 + MASS_CART);
    let acc1 = -0.75 * (xacc * cos1 + gsin1 + temp1) / LENGTH_1;
    let acc2 = -0.75 * (xacc * cos2 + gsin2 + temp2) / LENGTH_2;
    [s[1], xacc, s[3], acc1, s[5], acc2]
}

#[inline]
fn rk4(force: f64, s: &State) -> State {
    let add = |a: &State, k: &State, h: f64| -> State { std::array::from_fn(|i| a[i] + h * k[i]) };
    let k1 = derivatives(force, s);
    let k2 = derivatives(force, &add(s, &k1, TAU / 2.0));
    let k3 = derivatives(force, &add(s, &k2, TAU / 2.0));
    let k4 = derivatives(force, &add(s, &k3, TAU));
    std::array::from_fn(|i| s[i] + TAU / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// One control step: the action (network output in [0, 1]) held for two RK4 steps.
#[inline]
pub(super) fn step(action: f64, s: &mut State) {
    let force = (action - 0.5) * FORCE_MAG * 2.0;
    for _ in 0..2 {
        *s = rk4(force, s);
    }
}

/// Whether the cart left the track or a pole fell beyond ±36°.
pub(super) fn failed(s: &State) -> bool {
    s[0].abs() > 2.4 || s[2].abs() > FAIL_ANGLE || s[4].abs() > FAIL_ANGLE
}

/// The network's inputs in `out` (scaled as in Stanley's code); their number.
pub(super) fn observe(s: &State, markov: bool, out: &mut [f64; 7]) -> usize {
    if markov {
        *out = [
            s[0] / 4.8,
            s[1] / 2.0,
            s[2] / 0.52,
            s[3] / 2.0,
            s[4] / 0.52,
            s[5] / 2.0,
            0.5,
        ];
        7
    } else {
        out[..4].copy_from_slice(&[s[0] / 4.8, s[2] / 0.52, s[4] / 0.52, 0.5]);
        4
    }
}

/// Balances from `start` for at most `max_steps`; returns the steps survived and
/// Gruau's stability term Σ over the last 100 steps of |x| + |ẋ| + |θ1| + |θ̇1|.
pub(super) fn balance<N: Network + ?Sized>(
    net: &mut N,
    markov: bool,
    start: State,
    max_steps: u32,
) -> (u32, f64) {
    net.reset();
    let mut s = start;
    let mut obs = [0.0; 7];
    let mut out = [0.0];
    // Ring buffer of the last 100 stability terms (the trial may end at any step).
    let mut last = [0.0f64; 100];
    for t in 0..max_steps {
        let n = observe(&s, markov, &mut obs);
        net.activate(&obs[..n], &mut out);
        step(out[0], &mut s);
        if failed(&s) {
            return (t, last.iter().sum());
        }
        last[t as usize % 100] = stability(&s);
    }
    (max_steps, last.iter().sum())
}

/// Gruau's stability term of one step: |x| + |ẋ| + |θ1| + |θ̇1|.
#[inline(always)]
pub(super) fn stability(s: &State) -> f64 {
    s[0].abs() + s[1].abs() + s[2].abs() + s[3].abs()
}

/// The start state: the long pole at `degrees` (without velocities; Gruau's 4.5°
/// by default) or at Stanley's 0.07 rad (Markov), all else 0.
pub fn start_state(markov: bool, degrees: f64) -> State {
    let theta = if markov { 0.07 } else { degrees.to_radians() };
    [0.0, 0.0, theta, 0.0, 0.0, 0.0]
}

/// The task's fitness of `net` from `start` (Markov: steps balanced, at most
/// 100,000; without velocities: Gruau's damping fitness over at most 1,000
/// steps), and the network activations it took.
pub fn score<N: Network + ?Sized>(net: &mut N, markov: bool, start: State) -> (f64, u32) {
    let max_steps = max_steps(markov);
    let (t, wiggle) = balance(net, markov, start, max_steps);
    fitness_of(markov, max_steps, t, wiggle)
}

/// A trial's length: 100,000 steps with velocities, 1,000 without.
pub(super) fn max_steps(markov: bool) -> u32 {
    if markov { SUCCESS_STEPS } else { 1000 }
}

/// [`score`]'s result for a trial that balanced `t` steps (of at most
/// `max_steps`) with Gruau's stability sum `wiggle`.
pub(super) fn fitness_of(markov: bool, max_steps: u32, t: u32, wiggle: f64) -> (f64, u32) {
    // A trial that fails at step t activated the network t + 1 times.
    let activations = (t + 1).min(max_steps);
    if markov {
        return (t as f64, activations);
    }
    // Gruau et al. (1996): 0.1·t/1000 + 0.9·f2, f2 = 0.75 / wiggle if t ≥ 100.
    let f1 = t as f64 / 1000.0;
    let f2 = if t < 100 {
        0.0
    } else {
        0.75 / wiggle.max(1e-9)
    };
    (0.1 * f1 + 0.9 * f2, activations)
}

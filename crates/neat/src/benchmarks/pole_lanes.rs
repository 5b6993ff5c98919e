//! Double pole episodes side by side: several genomes' trials of
//! [`pole`](super::pole) stepped together, each state variable a vector
//! whose lanes are the episodes.
//!
//! One trial's physics is a dependent chain (two Runge–Kutta steps of
//! Wieland's equations per control step: 16 sines and cosines and about 40
//! divisions, each waiting for the last), so one episode at a time leaves
//! the core's vector units idle. Here every operation of a control step runs
//! over [`LANES`] episodes at once — the portable sine and cosine as the
//! branch-free lane-wise copies of [`math`](crate::math), the rest as loops
//! the compiler vectorises — with the same operations in the same order per
//! lane, so every trial gives exactly the bits of
//! [`pole::score`](super::pole::score). A lane
//! whose trial ends takes the next genome's.

use crate::activation::{Activation, apply_all};
use crate::math::sin_cos_in_place;
use crate::network::Network;
use crate::{FeedForwardNetwork, RecurrentNetwork};

use super::cart_pole::{
    FORCE_MAG, State, TAU, derivatives_given, failed, fitness_of, max_steps, observe, stability,
    step,
};

/// Episodes stepped together: four AVX2 vectors of f64.
pub const LANES: usize = 16;

/// One state variable (or derivative) of every lane.
type V = [f64; LANES];

/// The state of every lane, variable-major: `s[i][l]` is variable `i` of lane `l`.
type Lanes = [V; 6];

/// One trial in progress.
#[derive(Clone, Copy)]
struct Trial {
    /// Index of its network.
    net: usize,
    /// Control steps balanced so far.
    t: u32,
    /// Which of the rings holds its last 100 stability terms (moving a
    /// trial to another lane moves this index, not the ring).
    ring: usize,
}

/// [`pole::balance`](super::pole)'s stability sum of a trial that balanced
/// `t` steps: all 100 entries of its ring in index order once it has
/// wrapped, else the `t` written so far — the same bits, since the entries
/// not yet written are the scalar code's zeros, and adding +0 to a sum of
/// non-negative terms leaves it as it is (the sign of an empty sum's zero
/// is never read: the damping term needs 100 steps).
fn wiggle(ring: &[f64; 100], t: u32) -> f64 {
    ring[..(t as usize).min(100)].iter().sum()
}

/// A network whose trials [`score_lanes`] runs side by side: it may step
/// several networks at once (the default steps each as [`Network::activate`]).
pub trait LaneNetwork: Network + Sized {
    /// For each live lane `l`: network `nets[ids[l]]` reads `inputs[l][..k]`
    /// and its one output goes to `out[l]`, exactly as its
    /// [`Network::activate`] would give it. `scratch` is reused between calls.
    fn activate_lanes(
        nets: &mut [Self],
        ids: &[usize],
        inputs: &[[f64; 7]],
        k: usize,
        out: &mut [f64],
        scratch: &mut LaneScratch,
    ) {
        let _ = scratch;
        for ((&id, input), o) in ids.iter().zip(inputs).zip(out) {
            let mut one = [0.0];
            nets[id].activate(&input[..k], &mut one);
            *o = one[0];
        }
    }
}

/// Memory a [`LaneNetwork`] reuses from step to step.
#[derive(Debug, Default)]
pub struct LaneScratch {
    /// The activation function of each computed node of the live lanes.
    acts: Vec<Activation>,
    /// Their sums, then their values.
    sums: Vec<f64>,
}

impl LaneNetwork for FeedForwardNetwork {}

impl LaneNetwork for RecurrentNetwork {
    /// All lanes' sums, then every activation function at once as vector
    /// lanes ([`apply_all`]), then each network's state: the halves of
    /// [`Network::activate`]'s synchronous update (as
    /// [`RecurrentLanes`](crate::RecurrentLanes) steps them).
    fn activate_lanes(
        nets: &mut [Self],
        ids: &[usize],
        inputs: &[[f64; 7]],
        k: usize,
        out: &mut [f64],
        scratch: &mut LaneScratch,
    ) {
        let LaneScratch { acts, sums } = scratch;
        acts.clear();
        for &id in ids {
            acts.extend_from_slice(&nets[id].plan.acts);
        }
        sums.clear();
        sums.resize(acts.len(), 0.0);
        let mut at = 0;
        for (&id, input) in ids.iter().zip(inputs) {
            let net = &mut nets[id];
            let c = net.plan.acts.len();
            (net.plan).recurrent_sums(&input[..k], 1, &mut net.state, &mut sums[at..at + c]);
            at += c;
        }
        apply_all(acts, sums);
        let mut at = 0;
        for (&id, o) in ids.iter().zip(out) {
            let net = &mut nets[id];
            let c = net.plan.acts.len();
            let mut one = [0.0];
            (net.plan).recurrent_finish(&mut net.state, &sums[at..at + c], &mut one);
            *o = one[0];
            at += c;
        }
    }
}

/// The task's fitness of each of `nets` from `start` and the activations it
/// took — exactly [`pole::score`](super::pole::score) of each — into `out`
/// (cleared first), the trials run up to [`LANES`] at a time.
///
/// Live trials are kept in the first lanes (a lane whose trial ends takes
/// the next genome's, or the last live lane's trial), so that when few are
/// left — a Markov population's few long balancers — a step costs one
/// vector of 4 lanes or one scalar trial, not all 16 lanes.
pub fn score_lanes<N: LaneNetwork>(
    nets: &mut [N],
    markov: bool,
    start: State,
    out: &mut Vec<(f64, u32)>,
) {
    out.clear();
    out.resize(nets.len(), (0.0, 0));
    let max = max_steps(markov);
    let mut s: Lanes = [[0.0; LANES]; 6];
    let mut trials: [Trial; LANES] = std::array::from_fn(|l| Trial {
        net: 0,
        t: 0,
        ring: l,
    });
    let mut rings = [[0.0; 100]; LANES];
    // Lanes 0..live hold trials; network `next` is the next to start.
    let (mut live, mut next) = (0, 0);
    while live < LANES && next < nets.len() {
        start_trial(&mut s, &mut trials, live, next, start);
        nets[next].reset();
        (live, next) = (live + 1, next + 1);
    }
    let (mut obs, mut ids) = ([[0.0; 7]; LANES], [0; LANES]);
    let mut scratch = LaneScratch::default();
    let mut action = [0.5; LANES];
    while live > 0 {
        let mut k = 0;
        for (l, tr) in trials[..live].iter().enumerate() {
            k = observe(&lane(&s, l), markov, &mut obs[l]);
            ids[l] = tr.net;
        }
        N::activate_lanes(
            nets,
            &ids[..live],
            &obs[..live],
            k,
            &mut action[..live],
            &mut scratch,
        );
        control_step(&action, &mut s, live);
        let mut l = 0;
        while l < live {
            let tr = &mut trials[l];
            let state = lane(&s, l);
            let ended = if failed(&state) {
                true
            } else {
                rings[tr.ring][tr.t as usize % 100] = stability(&state);
                tr.t += 1;
                tr.t == max
            };
            if !ended {
                l += 1;
                continue;
            }
            out[tr.net] = fitness_of(markov, max, tr.t, wiggle(&rings[tr.ring], tr.t));
            if next < nets.len() {
                start_trial(&mut s, &mut trials, l, next, start);
                nets[next].reset();
                next += 1;
                l += 1;
            } else {
                // The last live lane's trial (not yet checked this step) moves here.
                live -= 1;
                trials[l] = trials[live];
                for v in s.iter_mut() {
                    v[l] = v[live];
                }
            }
        }
    }
}

/// Starts network `net`'s trial from `start` in lane `l` (with the ring of
/// the lane's last trial: [`wiggle`] reads only what this one writes).
fn start_trial(s: &mut Lanes, trials: &mut [Trial; LANES], l: usize, net: usize, start: State) {
    for (v, &x) in s.iter_mut().zip(&start) {
        v[l] = x;
    }
    trials[l].net = net;
    trials[l].t = 0;
}

/// Lane `l`'s state.
#[inline(always)]
fn lane(s: &Lanes, l: usize) -> State {
    std::array::from_fn(|i| s[i][l])
}

/// One control step of lanes `0..live`: each lane's action held for two
/// RK4 steps — one trial alone as `pole::step`, up to 4 as one AVX2 vector,
/// up to 8 as two, else all 16 — at the best vector level the CPU has (no
/// FMA: the same bits at every width and level).
fn control_step(action: &V, s: &mut Lanes, live: usize) {
    if live == 1 {
        let mut one = lane(s, 0);
        step(action[0], &mut one);
        for (v, x) in s.iter_mut().zip(one) {
            v[0] = x;
        }
        return;
    }
    #[cfg(target_arch = "x86_64")]
    if crate::simd::level() >= crate::simd::SimdLevel::Avx2
        && let Some(t) = crate::simd::x86::Avx2::new()
    {
        // SAFETY: the token `t` exists only when this CPU supports AVX2.
        return unsafe { control_step_avx2(t, action, s, live) };
    }
    control_step_width(action, s, live);
}

/// [`control_step_width`] compiled with AVX2 (and without FMA).
///
/// # Safety
/// The CPU must support AVX2 (the token proves it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn control_step_avx2(_: crate::simd::x86::Avx2, action: &V, s: &mut Lanes, live: usize) {
    control_step_width(action, s, live);
}

/// The narrowest body that covers lanes `0..live`.
#[inline(always)]
fn control_step_width(action: &V, s: &mut Lanes, live: usize) {
    if live <= 4 {
        control_step_body::<4>(action, s);
    } else if live <= 8 {
        control_step_body::<8>(action, s);
    } else {
        control_step_body::<LANES>(action, s);
    }
}

/// `pole::step` for lanes `0..W`.
#[inline(always)]
fn control_step_body<const W: usize>(action: &V, s: &mut Lanes) {
    let force: [f64; W] = std::array::from_fn(|l| (action[l] - 0.5) * FORCE_MAG * 2.0);
    for _ in 0..2 {
        rk4::<W>(&force, s);
    }
}

/// `pole::rk4` for lanes `0..W`: the same stages, sums and order.
#[inline(always)]
fn rk4<const W: usize>(force: &[f64; W], s: &mut Lanes) {
    let mut k = [[[0.0; W]; 6]; 4];
    let mut stage = [[0.0; W]; 6];
    for i in 0..6 {
        stage[i].copy_from_slice(&s[i][..W]);
    }
    for (j, h) in [TAU / 2.0, TAU / 2.0, TAU, 0.0].into_iter().enumerate() {
        derivatives::<W>(force, &stage, &mut k[j]);
        if j < 3 {
            for i in 0..6 {
                for l in 0..W {
                    stage[i][l] = s[i][l] + h * k[j][i][l];
                }
            }
        }
    }
    let [k1, k2, k3, k4] = &k;
    for i in 0..6 {
        for l in 0..W {
            s[i][l] += TAU / 6.0 * (k1[i][l] + 2.0 * k2[i][l] + 2.0 * k3[i][l] + k4[i][l]);
        }
    }
}

/// Wieland's equations for lanes `0..W` ([`derivatives_given`] with
/// lane-wise sines and cosines).
#[inline(always)]
fn derivatives<const W: usize>(force: &[f64; W], s: &[[f64; W]; 6], k: &mut [[f64; W]; 6]) {
    let (mut sin1, mut cos1, mut sin2, mut cos2) = ([0.0; W], [0.0; W], [0.0; W], [0.0; W]);
    sin_cos_in_place(&s[2], &mut sin1, &mut cos1);
    sin_cos_in_place(&s[4], &mut sin2, &mut cos2);
    for l in 0..W {
        let state = std::array::from_fn(|i| s[i][l]);
        let d = derivatives_given(force[l], &state, [sin1[l], cos1[l], sin2[l], cos2[l]]);
        for i in 0..6 {
            k[i][l] = d[i];
        }
    }
}

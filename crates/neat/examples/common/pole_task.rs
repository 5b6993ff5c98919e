//! The library's double pole task (`vivae_neat::benchmarks::pole`) as the
//! speed examples score it: the same physics, start state and fitness, copied
//! because the library keeps its scorer private, plus a count of the network
//! activations (control steps), so that a reader can see how much work an
//! evaluation did. Wieland's equations, 4th-order Runge–Kutta in 0.01 s steps,
//! the action held for two of them; failure at |x| > 2.4 m or a pole beyond
//! ±36°. Markov: 6 scaled inputs and a bias of 0.5, fitness = steps balanced
//! (at most 100,000). Non-Markov: x, θ1, θ2 and the bias, Gruau's damping
//! fitness over at most 1,000 steps.

use std::sync::atomic::{AtomicU64, Ordering};

use vivae_neat::Network;
use vivae_neat::benchmarks::pole::{SUCCESS_STEPS, State};
use vivae_neat::math::sin_cos;

const GRAVITY: f64 = -9.8;
const MASS_CART: f64 = 1.0;
const MASS_POLE_1: f64 = 0.1;
const LENGTH_1: f64 = 0.5; // half length
const MASS_POLE_2: f64 = 0.01;
const LENGTH_2: f64 = 0.05;
const FORCE_MAG: f64 = 10.0;
const TAU: f64 = 0.01;
const MUP: f64 = 0.000002;
const FAIL_ANGLE: f64 = 36.0 * std::f64::consts::PI / 180.0;

/// Network activations over all evaluations so far.
pub static STEPS: AtomicU64 = AtomicU64::new(0);
/// Evaluations so far.
pub static EVALS: AtomicU64 = AtomicU64::new(0);

/// Wieland's equations of motion (as in Stanley's NEAT code).
fn derivatives(force: f64, s: &State) -> State {
    let (sin1, cos1) = sin_cos(s[2]);
    let (sin2, cos2) = sin_cos(s[4]);
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

/// One 4th-order Runge–Kutta step of `TAU` seconds.
fn rk4(force: f64, s: &State) -> State {
    let add = |a: &State, k: &State, h: f64| -> State { std::array::from_fn(|i| a[i] + h * k[i]) };
    let k1 = derivatives(force, s);
    let k2 = derivatives(force, &add(s, &k1, TAU / 2.0));
    let k3 = derivatives(force, &add(s, &k2, TAU / 2.0));
    let k4 = derivatives(force, &add(s, &k3, TAU));
    std::array::from_fn(|i| s[i] + TAU / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// One control step: the action (network output in [0, 1]) held for two RK4 steps.
fn step(action: f64, s: &mut State) {
    let force = (action - 0.5) * FORCE_MAG * 2.0;
    for _ in 0..2 {
        *s = rk4(force, s);
    }
}

/// Whether the cart left the track or a pole fell.
fn failed(s: &State) -> bool {
    s[0].abs() > 2.4 || s[2].abs() > FAIL_ANGLE || s[4].abs() > FAIL_ANGLE
}

/// The network's inputs for `s` in `out`; returns how many.
fn observe(s: &State, markov: bool, out: &mut [f64; 7]) -> usize {
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

/// Balances from `start` for at most `max_steps`: steps, Gruau's stability term, activations.
fn balance(net: &mut impl Network, markov: bool, start: State, max_steps: u32) -> (u32, f64, u32) {
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
            return (t, last.iter().sum(), t + 1);
        }
        last[t as usize % 100] = s[0].abs() + s[1].abs() + s[2].abs() + s[3].abs();
    }
    (max_steps, last.iter().sum(), max_steps)
}

/// The library's fitness of `net` from `start`, counting its activations.
pub fn fitness(net: &mut impl Network, markov: bool, start: State) -> f64 {
    let (f, steps) = if markov {
        let (t, _, n) = balance(net, true, start, SUCCESS_STEPS);
        (t as f64, n)
    } else {
        // Gruau et al. (1996): 0.1·t/1000 + 0.9·f2, f2 = 0.75 / wiggle if t ≥ 100.
        let (t, wiggle, n) = balance(net, false, start, 1000);
        let f1 = t as f64 / 1000.0;
        let f2 = if t < 100 {
            0.0
        } else {
            0.75 / wiggle.max(1e-9)
        };
        (0.1 * f1 + 0.9 * f2, n)
    };
    STEPS.fetch_add(u64::from(steps), Ordering::Relaxed);
    EVALS.fetch_add(1, Ordering::Relaxed);
    f
}

/// `name: steps_per_eval=... steps_per_s=...` over `seconds` of runs.
pub fn steps_line(name: &str, seconds: f64) -> String {
    let steps = STEPS.load(Ordering::Relaxed) as f64;
    let evals = EVALS.load(Ordering::Relaxed).max(1) as f64;
    format!(
        "{name}: steps_per_eval={:.1} steps_per_s={:.0}",
        steps / evals,
        steps / seconds.max(1e-9)
    )
}

/// The pole speed examples' main: fixed-length runs of the library's task, never stopped early.
pub fn speed_main(name: &str, title: &str, markov: bool) {
    use std::cell::RefCell;
    use vivae_neat::benchmarks::pole::{pole_params, spec, start_state};
    use vivae_neat::{EvalContext, FeedForwardNetwork, Genome};
    let start = start_state(markov, 4.5);
    let task = |g: &Genome, _: &EvalContext| {
        if !markov {
            return crate::common::with_recurrent(g, |net| fitness(net, false, start));
        }
        // One network per thread, recompiled in place for each genome.
        thread_local! {
            static NET: RefCell<Option<FeedForwardNetwork>> = const { RefCell::new(None) };
        }
        NET.with_borrow_mut(|slot| {
            let net = slot.get_or_insert_with(|| FeedForwardNetwork::from_genome(g));
            net.recompile(g);
            fitness(net, true, start)
        })
    };
    let clock = std::time::Instant::now();
    let (params, spec) = (pole_params(markov), spec(markov));
    // An infinite target: a run that balances keeps evaluating until its time is up.
    if let Some(line) = crate::efficacy::sample(name, title, params, &spec, f64::INFINITY, task) {
        println!("{line}");
        println!("{}", steps_line(name, clock.elapsed().as_secs_f64()));
    }
}

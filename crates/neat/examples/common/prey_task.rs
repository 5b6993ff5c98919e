//! SharpNEAT 4's prey capture (`PreyCaptureWorld`, after Gomez & Miikkulainen
//! 1997), with the parameters of its `prey-capture.config.json`: a 24×24 grid,
//! the prey 4 to 14 cells from the walls and the agent 2 to 4 cells from it,
//! the prey moving 4 times first, prey speed 1, sensor range 4, 70 steps, 100
//! trials; fitness is the number of trials in which the prey is caught.
//! Inputs: bias, 8 prey sectors (within sensor range), prey within distance
//! 2, 4 wall detectors (N, E, S, W); outputs N, E, S, W (the highest ≥ 0.1
//! moves, ties do not). Computed in f64 with portable math where SharpNEAT
//! uses f32.

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use vivae_neat::{Network, math};

const GRID: i32 = 24;
const PI: f64 = std::f64::consts::PI;

/// The world's parameters.
#[derive(Clone, Copy)]
pub struct Prey {
    /// Moves the prey makes before the agent may move.
    pub init_moves: usize,
    /// Probability that the prey moves in a step.
    pub speed: f64,
    /// Distance within which the agent senses the prey's direction.
    pub sensor_range: f64,
    /// Steps per trial.
    pub max_steps: usize,
    /// Trials per evaluation (the maximum fitness).
    pub trials: usize,
}

/// SharpNEAT's parameters.
pub const SHARPNEAT_PREY: Prey = Prey {
    init_moves: 4,
    speed: 1.0,
    sensor_range: 4.0,
    max_steps: 70,
    trials: 100,
};

/// The squared distance and the angle in [0, 2π) of the offset (dx, dy).
fn polar(dx: i32, dy: i32) -> (i32, f64) {
    let a = math::atan2(dy as f64, dx as f64);
    (dx * dx + dy * dy, if a < 0.0 { a + 2.0 * PI } else { a })
}

/// Offsets between two cells of the grid, per axis.
const OFFSETS: usize = 2 * GRID as usize - 1;

/// [`polar`] and the prey's move weights for every offset between two cells,
/// computed once: pure functions of two small integers, so looking them up
/// gives the same bits as computing them each step (which was a third of an
/// evaluation: two `atan2`, a square root and four 32nd powers per step).
struct Tables {
    /// `polar(dx, dy)` at [`offset`]`(dx, dy)`.
    polar: Vec<(i32, f64)>,
    /// The prey's weights of moving N, E, S, W, given the agent at (dx, dy) from it.
    weights: Vec<[f64; 4]>,
}

/// The index of (dx, dy) in the tables.
fn offset(dx: i32, dy: i32) -> usize {
    (dx + GRID - 1) as usize * OFFSETS + (dy + GRID - 1) as usize
}

/// The tables, built on first use.
fn tables() -> &'static Tables {
    static TABLES: std::sync::OnceLock<Tables> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let range = || (1 - GRID..GRID).flat_map(|dx| (1 - GRID..GRID).map(move |dy| (dx, dy)));
        Tables {
            polar: range().map(|(dx, dy)| polar(dx, dy)).collect(),
            weights: range().map(|(dx, dy)| move_weights(dx, dy)).collect(),
        }
    })
}

/// The prey's weights of moving N, E, S, W with the agent at (dx, dy) from it:
/// away from the agent, more strongly the nearer it is.
fn move_weights(dx: i32, dy: i32) -> [f64; 4] {
    let (r2, az) = polar(dx, dy);
    let d = (r2 as f64).sqrt();
    let t = if d <= 4.0 {
        15.0 - d
    } else if d <= 15.0 {
        9.0 - d * 0.5
    } else {
        1.0
    } * 0.33;
    let w = |b: f64| {
        let d = (az - b).abs();
        exp32(if d > PI { 2.0 * PI - d } else { d } / PI * t)
    };
    [w(PI * 0.5), w(0.0), w(PI * 1.5), w(PI)]
}

fn step(p: &mut (i32, i32), dir: usize) {
    match dir {
        0 => p.1 = (p.1 + 1).min(GRID - 1),
        1 => p.0 = (p.0 + 1).min(GRID - 1),
        2 => p.1 = (p.1 - 1).max(0),
        _ => p.0 = (p.0 - 1).max(0),
    }
}

/// SharpNEAT's e^x ≈ (1 + x / 29.5)^32, tuned for [0, 2π].
fn exp32(x: f64) -> f64 {
    (1.0 + x / 29.5).powi(32)
}

impl Prey {
    fn inputs(&self, agent: (i32, i32), prey: (i32, i32), v: &mut [f64; 14]) {
        let (r2, az) = tables().polar[offset(prey.0 - agent.0, prey.1 - agent.1)];
        *v = [0.0; 14];
        v[0] = 1.0;
        if r2 as f64 <= self.sensor_range * self.sensor_range {
            let t = az - PI / 8.0;
            let t = if t < 0.0 { t + 2.0 * PI } else { t };
            v[1 + ((t * 4.0 / PI).floor() as usize).min(7)] = 1.0;
        }
        v[9] = if r2 <= 4 { 1.0 } else { 0.0 };
        let near = |d: i32| if d <= 4 { (4 - d) as f64 / 4.0 } else { 0.0 };
        (v[10], v[11]) = (near(GRID - 1 - agent.1), near(GRID - 1 - agent.0));
        (v[12], v[13]) = (near(agent.1), near(agent.0));
    }

    fn move_prey(&self, agent: (i32, i32), prey: &mut (i32, i32), rng: &mut Pcg64Mcg) {
        if self.speed < 1.0 && rng.random::<f64>() >= self.speed {
            return;
        }
        let p = tables().weights[offset(agent.0 - prey.0, agent.1 - prey.1)];
        let thresh = rng.random::<f64>() * p.iter().sum::<f64>();
        let mut acc = 0.0;
        let dir = p.iter().position(|&q| {
            acc += q;
            acc > thresh
        });
        step(prey, dir.unwrap_or(3));
    }

    /// One trial: whether `net` (14 inputs, 4 outputs) catches the prey.
    fn trial(&self, net: &mut impl Network, rng: &mut Pcg64Mcg) -> bool {
        let mut prey = (
            4 + rng.random_range(0..GRID - 8),
            4 + rng.random_range(0..GRID - 8),
        );
        let (s, c) = math::sin_cos(2.0 * PI * rng.random::<f64>());
        let r = 2.0 + 2.0 * rng.random::<f64>();
        let mut agent = (
            prey.0 + (c * r).trunc() as i32,
            prey.1 + (s * r).trunc() as i32,
        );
        let (mut v, mut out) = ([0.0; 14], [0.0; 4]);
        net.reset();
        for t in 0..self.max_steps {
            self.inputs(agent, prey, &mut v);
            net.activate(&v, &mut out);
            if t >= self.init_moves {
                let best = (1..4).fold(0, |b, i| if out[i] > out[b] { i } else { b });
                let tie = (0..4).any(|i| i != best && out[i] == out[best]);
                if !tie && out[best] >= 0.1 {
                    step(&mut agent, best);
                }
                if agent == prey {
                    return true;
                }
            }
            self.move_prey(agent, &mut prey, rng);
            if agent == prey && t >= self.init_moves {
                return true;
            }
        }
        false
    }

    /// The number of trials (seeded by `seed`) in which `net` catches the prey.
    pub fn fitness(&self, net: &mut impl Network, seed: u64) -> f64 {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        (0..self.trials)
            .filter(|_| self.trial(net, &mut rng))
            .count() as f64
    }
}

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
use vivae_neat::{Genome, Network, RecurrentLanes, math};

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

/// Networks [`Prey::fitness_lanes`] steps side by side at most.
pub const PREY_LANES: usize = 16;

/// One trial in progress: the agent's and the prey's cells, and the step.
#[derive(Clone, Copy)]
struct Trial {
    agent: (i32, i32),
    prey: (i32, i32),
    t: usize,
}

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

/// The cell offsets of the moves N, E, S, W.
const MOVES: [(i32, i32); 4] = [(0, 1), (1, 0), (0, -1), (-1, 0)];

/// Moves `p` (a cell of the grid) one cell `dir` (N, E, S, W), not past the
/// walls; `go` false leaves it. Selects, not branches: the direction is the
/// network's or the dice's, which no predictor guesses.
fn step(p: &mut (i32, i32), dir: usize, go: bool) {
    let (dx, dy) = MOVES[dir];
    let go = i32::from(go);
    *p = (
        (p.0 + go * dx).clamp(0, GRID - 1),
        (p.1 + go * dy).clamp(0, GRID - 1),
    );
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
        // The sector is written 1 when the prey is in range, else 0 (as it
        // was): no branch on where the prey is. `t` ≥ 0, so truncating is floor.
        let seen = r2 as f64 <= self.sensor_range * self.sensor_range;
        let t = az - PI / 8.0;
        let t = if t < 0.0 { t + 2.0 * PI } else { t };
        v[1 + ((t * 4.0 / PI) as usize).min(7)] = f64::from(u8::from(seen));
        v[9] = f64::from(u8::from(r2 <= 4));
        let near = |d: i32| (4 - d).max(0) as f64 / 4.0;
        (v[10], v[11]) = (near(GRID - 1 - agent.1), near(GRID - 1 - agent.0));
        (v[12], v[13]) = (near(agent.1), near(agent.0));
    }

    fn move_prey(&self, agent: (i32, i32), prey: &mut (i32, i32), rng: &mut Pcg64Mcg) {
        if self.speed < 1.0 && rng.random::<f64>() >= self.speed {
            return;
        }
        let p = tables().weights[offset(agent.0 - prey.0, agent.1 - prey.1)];
        let thresh = rng.random::<f64>() * p.iter().sum::<f64>();
        // The first direction whose running sum passes `thresh` (else W):
        // the weights are positive, so the running sums rise and that
        // direction is the count of sums not past it.
        let (mut acc, mut dir) = (0.0, 0);
        for q in p {
            acc += q;
            dir += usize::from(acc <= thresh);
        }
        step(prey, dir.min(3), true);
    }

    /// A trial's start, drawn from `rng`: the prey, then the agent around it.
    fn start(&self, rng: &mut Pcg64Mcg) -> Trial {
        let prey = (
            4 + rng.random_range(0..GRID - 8),
            4 + rng.random_range(0..GRID - 8),
        );
        let (s, c) = math::sin_cos(2.0 * PI * rng.random::<f64>());
        let r = 2.0 + 2.0 * rng.random::<f64>();
        let agent = (
            prey.0 + (c * r).trunc() as i32,
            prey.1 + (s * r).trunc() as i32,
        );
        Trial { agent, prey, t: 0 }
    }

    /// The rest of step `trial.t` once the network has answered `out`: the
    /// agent's move, then the prey's. `Some(caught)` when the trial ends.
    fn advance(&self, trial: &mut Trial, out: &[f64; 4], rng: &mut Pcg64Mcg) -> Option<bool> {
        let t = trial.t;
        if t >= self.init_moves {
            let best = (1..4).fold(0, |b, i| if out[i] > out[b] { i } else { b });
            // Another output equal to the best one is a tie (counting the
            // best itself: NaN equals nothing, as before).
            let tie = out.iter().filter(|&&o| o == out[best]).count() > 1;
            step(&mut trial.agent, best, !tie && out[best] >= 0.1);
            if trial.agent == trial.prey {
                return Some(true);
            }
        }
        self.move_prey(trial.agent, &mut trial.prey, rng);
        if trial.agent == trial.prey && t >= self.init_moves {
            return Some(true);
        }
        trial.t += 1;
        (trial.t >= self.max_steps).then_some(false)
    }

    /// One trial: whether `net` (14 inputs, 4 outputs) catches the prey.
    fn trial(&self, net: &mut impl Network, rng: &mut Pcg64Mcg) -> bool {
        let mut trial = self.start(rng);
        if self.max_steps == 0 {
            return false;
        }
        let (mut v, mut out) = ([0.0; 14], [0.0; 4]);
        net.reset();
        loop {
            self.inputs(trial.agent, trial.prey, &mut v);
            net.activate(&v, &mut out);
            if let Some(caught) = self.advance(&mut trial, &out, rng) {
                return caught;
            }
        }
    }

    /// The number of trials (seeded by `seed`) in which `net` catches the prey.
    pub fn fitness(&self, net: &mut impl Network, seed: u64) -> f64 {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        (0..self.trials)
            .filter(|_| self.trial(net, &mut rng))
            .count() as f64
    }

    /// [`Prey::fitness`] of each of `genomes`' recurrent networks, trials
    /// seeded by `seeds` (one each), pushed onto `out` in order: the same
    /// bits, with up to `lanes.capacity()` networks stepped side by side
    /// ([`RecurrentLanes`]). A genome's trials run one after the other in
    /// its lane, and a genome done with its last hands the lane to the next
    /// genome, so no lane idles while genomes are left.
    #[allow(dead_code)]
    pub fn fitness_lanes(
        &self,
        genomes: &[Genome],
        seeds: &[u64],
        lanes: &mut RecurrentLanes,
        out: &mut Vec<f64>,
    ) {
        assert_eq!(genomes.len(), seeds.len(), "one seed per genome");
        let base = out.len();
        out.resize(base + genomes.len(), 0.0);
        if self.trials == 0 || self.max_steps == 0 {
            return; // nothing can be caught
        }
        /// A genome in a lane: its trials so far and the one in progress.
        struct Run {
            genome: usize,
            rng: Pcg64Mcg,
            trials: usize,
            caught: usize,
            trial: Trial,
        }
        let width = lanes.capacity().min(PREY_LANES);
        let mut runs: Vec<Run> = Vec::with_capacity(width);
        let (mut v, mut o) = ([[0.0; 14]; PREY_LANES], [[0.0; 4]; PREY_LANES]);
        let mut next = 0;
        lanes.clear();
        loop {
            while runs.len() < width && next < genomes.len() {
                let mut rng = Pcg64Mcg::seed_from_u64(seeds[next]);
                let trial = self.start(&mut rng);
                lanes.push(&genomes[next]);
                runs.push(Run {
                    genome: next,
                    rng,
                    trials: 0,
                    caught: 0,
                    trial,
                });
                next += 1;
            }
            if runs.is_empty() {
                return;
            }
            let n = runs.len();
            for (r, v) in runs.iter().zip(&mut v) {
                self.inputs(r.trial.agent, r.trial.prey, v);
            }
            let ins: [&[f64]; PREY_LANES] = std::array::from_fn(|l| &v[l][..]);
            let mut outs: [&mut [f64]; PREY_LANES] = o.each_mut().map(|o| &mut o[..]);
            lanes.activate(&ins[..n], &mut outs[..n]);
            // Backwards, so that dropping a lane moves only lanes already done.
            for l in (0..n).rev() {
                let r = &mut runs[l];
                let Some(caught) = self.advance(&mut r.trial, &o[l], &mut r.rng) else {
                    continue;
                };
                r.caught += usize::from(caught);
                r.trials += 1;
                if r.trials < self.trials {
                    r.trial = self.start(&mut r.rng);
                    lanes.reset_lane(l);
                } else {
                    out[base + r.genome] = r.caught as f64;
                    runs.remove(l);
                    lanes.remove(l);
                }
            }
        }
    }
}

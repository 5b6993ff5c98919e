//! A plain task: steer a point along a line to a target. Each of
//! [`EPISODES`] episodes starts at 0 with a target drawn from the
//! evaluation's seed in [−1, 1]; every step the network reads the distance
//! to the target (and a bias); its two outputs, each in [−1, 1], push the
//! point right and left by a twentieth of each. Fitness is 1 − the mean
//! distance over the steps.

use vivae_lab::tasks::TaskEntry;
use vivae_lab::tasks::plain::{Described, Plain, Trace, entry};
use vivae_neat::Network;
use vivae_neat::driver::Evaluation;
use vivae_neat::eval::splitmix64;

/// The task's registration (`--task seek`).
pub static TASK: TaskEntry = entry::<Seek>();

/// Episodes per evaluation.
const EPISODES: u32 = 4;
/// Steps per episode.
const STEPS: u32 = 30;

/// Seeking a target on a line, as a plain task.
pub struct Seek;

impl Described for Seek {
    const NAME: &'static str = "seek";
    const ABOUT: &'static str = "steering a point to a target on a line";
    const SCORING: &'static str = "fitness = 1 - the mean distance to the target (4 episodes)";
    const INPUTS: usize = 2;
    const OUTPUTS: usize = 2;
    const OUTPUT_MEANING: &'static str =
        "velocity = (out[0] - out[1]) / 20; inputs target - position, 1";
}

impl Plain for Seek {
    const STEPS: u64 = (EPISODES * STEPS) as u64;
    const TRACES: bool = true;

    fn evaluate(net: &mut dyn Network, seed: u64, mut trace: Option<&mut Trace>) -> Evaluation {
        let mut distance = 0.0;
        let mut out = [0.0; 2];
        for k in 0..EPISODES {
            let bits = splitmix64(seed ^ u64::from(k)) >> 11;
            let target = 2.0 * (bits as f64 / (1u64 << 53) as f64) - 1.0;
            let mut position = 0.0;
            net.reset();
            for _ in 0..STEPS {
                let inputs = [target - position, 1.0];
                net.activate(&inputs, &mut out);
                position += (out[0] - out[1]) / 20.0;
                let off = f64::abs(target - position);
                distance += off;
                if let Some(t) = trace.as_deref_mut() {
                    t.step(k, &inputs, &out, -off);
                }
            }
        }
        Evaluation::fitness(1.0 - distance / f64::from(EPISODES * STEPS))
    }
}

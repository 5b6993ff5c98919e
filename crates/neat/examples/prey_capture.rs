//! SharpNEAT's prey capture, sampled as its EfficacySampler does: runs of a
//! fixed wall-clock length, the best fitness each reaches.
//!
//! `cargo run --release -p vivae-neat --example prey_capture -- --runs 5 --seconds 60`
//!
//! 100 seeded trials per evaluation on a 24×24 grid (see
//! `common/prey_task.rs`); fitness is the prey caught. Population 225 as
//! SharpNEAT's `prey-capture.config.json`; the rest is our
//! `NeatParams::plain_neat` with recurrent links allowed and sigmoid nodes
//! (SharpNEAT uses LeakyReLU and its own operators). The trials' seed comes
//! from the evaluation context, so a run is reproducible.

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/prey_task.rs"]
mod prey_task;

use prey_task::SHARPNEAT_PREY;
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams};

const TITLE: &str = "SharpNEAT's prey capture";

fn main() {
    let params = NeatParams {
        population_size: 225,
        ..NeatParams::plain_neat()
    };
    let world = SHARPNEAT_PREY;
    let task = |g: &Genome, ctx: &EvalContext| {
        common::with_recurrent(g, |net| world.fitness(net, ctx.seed))
    };
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(14, 4)
    };
    let target = world.trials as f64;
    if let Some(line) = efficacy::sample("prey_capture", TITLE, params, &spec, target, task) {
        println!("{line}");
    }
}

//! SharpNEAT's generative sinewave, sampled as its EfficacySampler does: runs
//! of a fixed wall-clock length, the best fitness each reaches.
//!
//! `cargo run --release -p vivae-neat --example sinewave -- --runs 5 --seconds 60`
//!
//! A recurrent network with only a bias input must draw sin over [0, 8π],
//! one sample per activation (see `common/sine_task.rs`; at most 1,000).
//! Population 600 as SharpNEAT's `generative-sinewave.config.json`; the rest
//! is our `NeatParams::plain_neat` with recurrent links allowed and sigmoid
//! nodes (SharpNEAT uses LeakyReLU and its own operators).

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/sine_task.rs"]
mod sine_task;

use sine_task::Sine;
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams};

const TITLE: &str = "SharpNEAT's generative sinewave";

fn main() {
    let params = NeatParams {
        population_size: 600,
        ..NeatParams::plain_neat()
    };
    let sine = Sine::new();
    let task = |g: &Genome, _: &EvalContext| common::with_recurrent(g, |net| sine.fitness(net));
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(1, 1)
    };
    if let Some(line) = efficacy::sample("sinewave", TITLE, params, &spec, 1000.0, task) {
        println!("{line}");
    }
}

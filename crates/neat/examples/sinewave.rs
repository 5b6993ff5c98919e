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

use std::cell::RefCell;

use sine_task::{MAX_LANES, Sine};
use vivae_neat::driver::{Evaluation, GroupTask};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams, RecurrentLanes};

const TITLE: &str = "SharpNEAT's generative sinewave";

/// The sinewave scored a group of genomes at a time, their networks side by side.
#[derive(Clone)]
struct SineLanes(Sine);

impl GroupTask for SineLanes {
    fn group_size(&self) -> usize {
        MAX_LANES
    }

    fn evaluate_group(&self, genomes: &[Genome], _: &[EvalContext], out: &mut Vec<Evaluation>) {
        thread_local! {
            static LANES: RefCell<RecurrentLanes> = RefCell::new(RecurrentLanes::new(MAX_LANES));
            static FITNESS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
        }
        LANES.with_borrow_mut(|lanes| {
            FITNESS.with_borrow_mut(|fitness| {
                lanes.recompile(genomes);
                fitness.clear();
                self.0.fitness_lanes(lanes, fitness);
                out.extend(fitness.iter().map(|&f| Evaluation::fitness(f)));
            })
        })
    }
}

fn main() {
    let params = NeatParams {
        population_size: 600,
        ..NeatParams::plain_neat()
    };
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(1, 1)
    };
    // `--one-at-a-time`: each network alone (the same bits, for comparison).
    let alone = std::env::args().any(|a| a == "--one-at-a-time");
    let sine = Sine::new();
    let line = if alone {
        let task = |g: &Genome, _: &EvalContext| common::with_recurrent(g, |net| sine.fitness(net));
        efficacy::sample("sinewave", TITLE, params, &spec, 1000.0, task)
    } else {
        efficacy::sample_grouped("sinewave", TITLE, params, &spec, 1000.0, SineLanes(sine))
    };
    if let Some(line) = line {
        println!("{line}");
    }
}

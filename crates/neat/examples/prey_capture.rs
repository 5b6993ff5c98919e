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
//!
//! Up to 16 genomes' networks step side by side as vector lanes
//! (`Prey::fitness_lanes`); `--one-at-a-time` evaluates each network alone,
//! with the same bits.

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/prey_task.rs"]
mod prey_task;

use std::cell::RefCell;

use prey_task::{PREY_LANES, Prey, SHARPNEAT_PREY};
use vivae_neat::driver::{Evaluation, GroupTask};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams, RecurrentLanes};

const TITLE: &str = "SharpNEAT's prey capture";

/// Prey capture scored a group of genomes at a time, their networks side by side.
#[derive(Clone)]
struct PreyLanes(Prey);

impl GroupTask for PreyLanes {
    /// A whole population of 225 in one group on the example's one thread:
    /// the lanes drain only once, at the group's end.
    fn group_size(&self) -> usize {
        256
    }

    fn evaluate_group(&self, genomes: &[Genome], ctx: &[EvalContext], out: &mut Vec<Evaluation>) {
        thread_local! {
            static LANES: RefCell<RecurrentLanes> = RefCell::new(RecurrentLanes::new(PREY_LANES));
            static SCRATCH: RefCell<(Vec<u64>, Vec<f64>)> = const { RefCell::new((Vec::new(), Vec::new())) };
        }
        LANES.with_borrow_mut(|lanes| {
            SCRATCH.with_borrow_mut(|(seeds, fitness)| {
                seeds.clear();
                seeds.extend(ctx.iter().map(|c| c.seed));
                fitness.clear();
                self.0.fitness_lanes(genomes, seeds, lanes, fitness);
                out.extend(fitness.iter().map(|&f| Evaluation::fitness(f)));
            })
        })
    }
}

fn main() {
    let params = NeatParams {
        population_size: 225,
        ..NeatParams::plain_neat()
    };
    let world = SHARPNEAT_PREY;
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(14, 4)
    };
    let target = world.trials as f64;
    // `--one-at-a-time`: each network alone (the same bits, for comparison).
    let alone = std::env::args().any(|a| a == "--one-at-a-time");
    let line = if alone {
        let task = |g: &Genome, ctx: &EvalContext| {
            common::with_recurrent(g, |net| world.fitness(net, ctx.seed))
        };
        efficacy::sample("prey_capture", TITLE, params, &spec, target, task)
    } else {
        efficacy::sample_grouped(
            "prey_capture",
            TITLE,
            params,
            &spec,
            target,
            PreyLanes(world),
        )
    };
    if let Some(line) = line {
        println!("{line}");
    }
}

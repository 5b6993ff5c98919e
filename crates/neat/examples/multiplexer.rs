//! The binary 11-multiplexer, sampled as SharpNEAT's EfficacySampler does:
//! runs of a fixed wall-clock length, the best fitness each reaches.
//!
//! `cargo run --release -p vivae-neat --example multiplexer -- --runs 5 --seconds 60`
//!
//! Fitness as SharpNEAT 4 defines it (see `common/mux_task.rs`; at most 2,048).
//! Population 600 as SharpNEAT's `binary-eleven-multiplexer.config.json`; the
//! rest is our `NeatParams::plain_neat` with feed-forward sigmoid networks
//! (SharpNEAT uses LeakyReLU and its own operators).

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/mux_task.rs"]
mod mux_task;

use std::cell::RefCell;

use mux_task::{MUX_CASES, MUX_LANES, mux_fitness_lanes};
use vivae_neat::{EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams};

const TITLE: &str = "The binary 11-multiplexer (SharpNEAT's fitness)";

fn main() {
    let params = NeatParams {
        population_size: 600,
        ..NeatParams::plain_neat()
    };
    let task = |g: &Genome, _: &EvalContext| {
        // One network and lane scratch per thread, recompiled in place for
        // each genome: no allocation per evaluation once they are large enough.
        thread_local! {
            static NET: RefCell<Option<(FeedForwardNetwork, Vec<[f64; MUX_LANES]>)>> =
                const { RefCell::new(None) };
        }
        NET.with_borrow_mut(|slot| {
            let (net, scratch) =
                slot.get_or_insert_with(|| (FeedForwardNetwork::from_genome(g), Vec::new()));
            net.recompile(g);
            mux_fitness_lanes(net, scratch)
        })
    };
    let target = MUX_CASES as f64;
    let spec = GenomeSpec::plain(12, 1);
    if let Some(line) = efficacy::sample("multiplexer", TITLE, params, &spec, target, task) {
        println!("{line}");
    }
}

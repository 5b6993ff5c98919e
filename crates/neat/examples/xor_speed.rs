//! The library's XOR task at a fixed wall-clock length: evaluations per
//! second, for the side by side with neat-python (`neat_python/efficacy.py xor`).
//!
//! `cargo run --release -p vivae-neat --example xor_speed -- --runs 2 --seconds 15 --set add_node_probability=0 --set add_link_probability=0`
//!
//! Fitness (4 − Σ|error|)² over the four cases, the library's own scorer
//! (`vivae_neat::benchmarks::xor::score`), the four cases as lanes of one pass; parameters `NeatParams::plain_neat` (population 150),
//! feed-forward networks with 2 inputs and a bias. Runs never stop at a
//! solution (without new nodes none is possible).

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;

use std::cell::RefCell;

use vivae_neat::benchmarks::xor::score;
use vivae_neat::{EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams};

const TITLE: &str = "XOR (speed)";

fn main() {
    let task = |g: &Genome, _: &EvalContext| {
        // One network and lane scratch per thread, recompiled for each genome.
        thread_local! {
            static NET: RefCell<Option<(FeedForwardNetwork, Vec<[f64; 4]>)>> =
                const { RefCell::new(None) };
        }
        NET.with_borrow_mut(|slot| {
            let (net, scratch) =
                slot.get_or_insert_with(|| (FeedForwardNetwork::from_genome(g), Vec::new()));
            score(net, scratch, g).0
        })
    };
    let spec = GenomeSpec::plain(3, 1);
    let params = NeatParams::plain_neat();
    if let Some(line) = efficacy::sample("xor_speed", TITLE, params, &spec, f64::INFINITY, task) {
        println!("{line}");
    }
}

//! The library's XOR task at a fixed wall-clock length: evaluations per
//! second, for the side by side with neat-python (`neat_python/efficacy.py xor`).
//!
//! `cargo run --release -p vivae-neat --example xor_speed -- --runs 2 --seconds 15 --set add_node_probability=0 --set add_link_probability=0`
//!
//! Fitness (4 − Σ|error|)² over the four cases as `vivae_neat::benchmarks::xor`
//! scores it (copied: the library keeps its scorer private), the four cases as
//! lanes of one pass; parameters `NeatParams::plain_neat` (population 150),
//! feed-forward networks with 2 inputs and a bias. Runs never stop at a
//! solution (without new nodes none is possible).

// Only the command line and overrides of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;

use std::cell::RefCell;

use vivae_neat::{EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams};

const TITLE: &str = "XOR (speed)";

/// The four cases as lanes: `INPUTS[i][case]` is input `i` (the last is the bias).
const INPUTS: [[f64; 4]; 3] = [[0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 0.0, 1.0], [1.0; 4]];
const TARGETS: [f64; 4] = [0.0, 1.0, 1.0, 0.0];

/// The library's XOR fitness of `net`, recompiled for `g` in place.
fn fitness(net: &mut FeedForwardNetwork, scratch: &mut Vec<[f64; 4]>, g: &Genome) -> f64 {
    net.recompile(g);
    let mut out = [[0.0; 4]];
    net.activate_lanes(&INPUTS, &mut out, scratch);
    let err = (out[0].iter().zip(TARGETS)).fold(0.0, |e, (&y, t)| e + (y - t).abs());
    (4.0 - err).powi(2)
}

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
            fitness(net, scratch, g)
        })
    };
    let spec = GenomeSpec::plain(3, 1);
    let params = NeatParams::plain_neat();
    if let Some(line) = efficacy::sample("xor_speed", TITLE, params, &spec, f64::INFINITY, task) {
        println!("{line}");
    }
}

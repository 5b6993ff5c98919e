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

use mux_task::{MUX_CASES, mux_fitness};
use vivae_neat::{EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams};

const USAGE: &str = "\
The binary 11-multiplexer (SharpNEAT's fitness): fixed-length runs, one summary line.

Usage: cargo run --release -p vivae-neat --example multiplexer -- [OPTIONS]

Options:
  --seconds T           wall-clock length of each run (default 60)
  --runs N              runs, with seeds S, S+1, ... (default 5)
  --seed S              seed of the first run (default 1)
  --max-generations G   also stop a run after G generations
  --set FIELD=JSON      override one NeatParams field (repeatable)
  -h, --help            print this help

Prints `multiplexer: runs=N best_fitness(min/median/max)=... evals_per_run(median)=...
evals_per_s=...` on stdout (one thread) and one line per run on stderr.
";

fn main() {
    let params = NeatParams {
        population_size: 600,
        ..NeatParams::plain_neat()
    };
    let task = |g: &Genome, _: &EvalContext| mux_fitness(&mut FeedForwardNetwork::from_genome(g));
    let target = MUX_CASES as f64;
    let spec = GenomeSpec::plain(12, 1);
    if let Some(line) = efficacy::sample("multiplexer", USAGE, params, &spec, target, task) {
        println!("{line}");
    }
}

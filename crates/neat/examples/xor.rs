//! XOR, the classic NEAT benchmark (Stanley & Miikkulainen 2002).
//!
//! `cargo run --release -p vivae-neat --example xor -- --runs 100 --seed 1`
//!
//! Population 150, fitness (4 − Σ|error|)², solved when all four outputs are on the
//! right side of 0.5. Evaluations are counted up to and including the first genome
//! that solves (as if evaluated one by one). Parameters are Stanley's XOR settings
//! where our operators match his: the `NeatParams::plain_neat` preset.

mod common;
#[path = "common/xor_task.rs"]
mod xor_task;
use common::{RunResult, plain_main};
use xor_task::run_xor;

use vivae_neat::NeatParams;

fn run(params: &NeatParams, seed: u64, max_generations: u32) -> RunResult {
    match run_xor(params, seed, max_generations) {
        Some((evals, hidden)) => RunResult {
            evals: Some(evals),
            hidden,
            generalisation: None,
        },
        None => RunResult::unsolved(),
    }
}

/// The first line of `--help`.
const TITLE: &str =
    "XOR with NEAT (Stanley & Miikkulainen 2002): many seeded runs, one summary line.";
/// What the summary line holds.
const SUMMARY: &str = "solved=S/N mean_evals=... median_evals=... mean_hidden=... mean_ms=...";

fn main() {
    let text = (TITLE, SUMMARY, "population_size=300");
    plain_main("xor", text, (100, 500), run);
}

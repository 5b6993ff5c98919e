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
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize};
use xor_task::run_xor;

use vivae_neat::NeatParams;

const USAGE: &str = "\
XOR with NEAT (Stanley & Miikkulainen 2002): many seeded runs, one summary line.

Usage: cargo run --release -p vivae-neat --example xor -- [OPTIONS]

Options:
  --runs N              runs, with seeds S, S+1, ... (default 100)
  --seed S              seed of the first run (default 1)
  --max-generations G   generations before a run counts as unsolved (default 500)
  --set FIELD=JSON      override one NeatParams field (repeatable), e.g. --set population_size=300
  -h, --help            print this help

Prints `xor: solved=S/N mean_evals=... median_evals=... mean_hidden=... mean_ms=...`
on stdout and one line per run on stderr.
";

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

fn main() {
    let Some(args) = args_or_exit("xor", USAGE, &[], &[]) else {
        return;
    };
    let params =
        apply_overrides(NeatParams::plain_neat(), &args.sets).unwrap_or_else(|e| fail("xor", &e));
    let runs = args.runs.unwrap_or(100);
    let seed = args.seed.unwrap_or(1);
    let max_generations = args.max_generations.unwrap_or(500);
    let line = summarize("xor", runs, seed, |seed| {
        run(&params, seed, max_generations)
    });
    println!("{line}");
}

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
use common::{RunResult, override_param, summarize};
use xor_task::run_xor;

use vivae_neat::NeatParams;

fn run(params: &NeatParams, seed: u64, max_generations: u32) -> RunResult {
    match run_xor(params, seed, max_generations) {
        Some((evals, hidden)) => RunResult {
            evals: Some(evals),
            hidden,
        },
        None => RunResult {
            evals: None,
            hidden: 0,
        },
    }
}

fn main() {
    let mut runs = 100usize;
    let mut seed = 1u64;
    let mut max_generations = 500u32;
    let mut params = NeatParams::plain_neat();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| -> u64 {
            it.next()
                .and_then(|v| v.parse().ok())
                .unwrap_or_else(|| panic!("{name} needs a number"))
        };
        match a.as_str() {
            "--runs" => runs = value("--runs") as usize,
            "--seed" => seed = value("--seed"),
            "--max-generations" => max_generations = value("--max-generations") as u32,
            "--set" => {
                let kv = it.next().expect("--set needs field=json_value");
                params = override_param(&params, kv);
            }
            other => panic!(
                "unknown argument {other} (use --runs N --seed S --max-generations G --set field=value)"
            ),
        }
    }
    let line = summarize("xor", runs, seed, |seed| {
        run(&params, seed, max_generations)
    });
    println!("{line}");
}

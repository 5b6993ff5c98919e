//! 3-bit even parity, XOR's bigger sibling, for comparing NEAT settings.
//!
//! `cargo run --release -p vivae-neat --example parity -- --runs 50 --seed 1`
//!
//! Inputs are three bits and a bias of 1; the output must be above 0.5 exactly
//! when an odd number of bits is set. Fitness (8 − Σ|error|)² over the 8 cases,
//! solved when all 8 are on the right side of 0.5. Population 150 with the
//! `NeatParams::plain_neat` preset, as for XOR. Evaluations are counted up to and
//! including the first solving genome. With `PARITY_TRACE` set, each
//! generation's statistics are printed on stderr (species counts over time).

mod common;
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize};

use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Population};

const USAGE: &str = "\
3-bit parity with NEAT: many seeded runs, one summary line.

Usage: cargo run --release -p vivae-neat --example parity -- [OPTIONS]

Options:
  --runs N              runs, with seeds S, S+1, ... (default 50)
  --seed S              seed of the first run (default 1)
  --max-generations G   generations before a run counts as unsolved (default 500)
  --set FIELD=JSON      override one NeatParams field (repeatable), e.g. --set target_species=10
  -h, --help            print this help

Prints `parity: solved=S/N mean_evals=... median_evals=... mean_hidden=... mean_ms=...`
on stdout and one line per run on stderr.
";

const CASES: usize = 8;

/// The 8 cases as lanes: `INPUTS[i][case]` is bit `i` of `case` (the last input
/// is the bias).
fn inputs() -> [[f64; CASES]; 4] {
    let bit = |i: usize| std::array::from_fn(|c| ((c >> i) & 1) as f64);
    [bit(0), bit(1), bit(2), [1.0; CASES]]
}

/// Fitness and whether all 8 cases are on the right side of 0.5.
fn evaluate(
    net: &mut FeedForwardNetwork,
    scratch: &mut Vec<[f64; CASES]>,
    inputs: &[[f64; CASES]; 4],
    g: &Genome,
) -> (f64, bool) {
    net.recompile(g);
    let mut out = [[0.0; CASES]];
    net.activate_lanes(inputs, &mut out, scratch);
    let mut err = 0.0;
    let mut solved = true;
    for (case, &y) in out[0].iter().enumerate() {
        let odd = case.count_ones() % 2 == 1;
        err += (y - f64::from(u8::from(odd))).abs();
        solved &= (y > 0.5) == odd;
    }
    ((CASES as f64 - err).powi(2), solved)
}

fn run(params: &NeatParams, seed: u64, max_generations: u32) -> RunResult {
    let mut pop = Population::new(params.clone(), GenomeSpec::plain(4, 1), seed)
        .unwrap_or_else(|e| fail("parity", &e.to_string()));
    let mut net = FeedForwardNetwork::from_genome(&pop.genomes()[0]);
    let mut scratch = Vec::new();
    let inputs = inputs();
    let trace = std::env::var_os("PARITY_TRACE").is_some();
    for _ in 0..max_generations {
        let mut fitness = Vec::with_capacity(pop.genomes().len());
        let mut first_solver = None;
        for (i, g) in pop.genomes().iter().enumerate() {
            let (f, solved) = evaluate(&mut net, &mut scratch, &inputs, g);
            fitness.push(f);
            if solved && first_solver.is_none() {
                first_solver = Some(i);
            }
        }
        pop.set_fitnesses(fitness)
            .unwrap_or_else(|e| fail("parity", &e.to_string()));
        if trace {
            eprintln!("{:?}", pop.stats());
        }
        if let Some(i) = first_solver {
            return RunResult {
                evals: Some(pop.generation() as usize * pop.genomes().len() + i + 1),
                hidden: pop.genomes()[i].num_hidden(),
                generalisation: None,
            };
        }
        pop.next_generation();
    }
    RunResult::unsolved()
}

fn main() {
    let Some(args) = args_or_exit("parity", USAGE, &[], &[]) else {
        return;
    };
    let params = apply_overrides(NeatParams::plain_neat(), &args.sets)
        .unwrap_or_else(|e| fail("parity", &e));
    let runs = args.runs.unwrap_or(50);
    let seed = args.seed.unwrap_or(1);
    let max_generations = args.max_generations.unwrap_or(500);
    let line = summarize("parity", runs, seed, |seed| {
        run(&params, seed, max_generations)
    });
    println!("{line}");
}

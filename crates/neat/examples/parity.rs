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
use common::{RunResult, fail, plain_main};

use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Population};

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

/// The first line of `--help`.
const TITLE: &str = "3-bit parity with NEAT: many seeded runs, one summary line.";
/// What the summary line holds.
const SUMMARY: &str = "solved=S/N mean_evals=... median_evals=... mean_hidden=... mean_ms=...";

fn main() {
    let text = (TITLE, SUMMARY, "target_species=10");
    plain_main("parity", text, (50, 500), run);
}

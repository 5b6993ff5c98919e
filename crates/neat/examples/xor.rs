//! XOR, the classic NEAT benchmark (Stanley & Miikkulainen 2002).
//!
//! `cargo run --release -p vivae-neat --example xor -- --runs 100 --seed 1`
//!
//! Population 150, fitness (4 − Σ|error|)², solved when all four outputs are on the
//! right side of 0.5. Evaluations are counted up to and including the first genome
//! that solves (as if evaluated one by one). Parameters are Stanley's XOR settings
//! where our operators match his: the `NeatParams::plain_neat` preset.

mod common;
use common::{RunResult, override_param, summarize};

use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Network, Population};

const CASES: [([f64; 3], f64); 4] = [
    ([0.0, 0.0, 1.0], 0.0),
    ([0.0, 1.0, 1.0], 1.0),
    ([1.0, 0.0, 1.0], 1.0),
    ([1.0, 1.0, 1.0], 0.0),
];

/// Fitness and whether all four cases are on the right side of 0.5; `net` is
/// any network, recompiled for `g` in place (no allocation per genome).
fn evaluate(net: &mut FeedForwardNetwork, g: &Genome) -> (f64, bool) {
    net.recompile(g);
    let mut out = [0.0];
    let mut err = 0.0;
    let mut solved = true;
    for (input, target) in CASES {
        net.activate(&input, &mut out);
        err += (out[0] - target).abs();
        solved &= (out[0] > 0.5) == (target > 0.5);
    }
    ((4.0 - err).powi(2), solved)
}

fn run(params: &NeatParams, seed: u64, max_generations: u32) -> RunResult {
    let mut pop =
        Population::new(params.clone(), GenomeSpec::plain(3, 1), seed).expect("valid parameters");
    let mut fitness = Vec::with_capacity(params.population_size);
    let mut net = FeedForwardNetwork::from_genome(&pop.genomes()[0]);
    for _ in 0..max_generations {
        // One network per genome gives both its fitness and whether it solves;
        // evaluated in order on this thread (150 tiny networks are far too
        // little work to be worth waking a thread pool for).
        fitness.clear();
        let mut first_solver = None;
        for (i, g) in pop.genomes().iter().enumerate() {
            let (f, solved) = evaluate(&mut net, g);
            fitness.push(f);
            if solved && first_solver.is_none() {
                first_solver = Some(i);
            }
        }
        pop.set_fitnesses(fitness.clone())
            .expect("one fitness per genome");
        if std::env::var_os("XOR_TRACE").is_some() {
            eprintln!("{:?}", pop.stats());
        }
        if let Some(i) = first_solver {
            let gen_evals = pop.generation() as usize * pop.params().population_size;
            return RunResult {
                evals: Some(gen_evals + i + 1),
                hidden: pop.genomes()[i].num_hidden(),
            };
        }
        pop.next_generation();
    }
    RunResult {
        evals: None,
        hidden: 0,
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

//! Visual discrimination ("boxes", Stanley, D'Ambrosio & Gauci 2009): find
//! the larger of two objects, evolved at 11×11 and re-sampled at 33×33 and
//! 55×55 without further evolution.
//!
//! `cargo run --release -p vivae-neat --example boxes -- --runs 20 --seed 1`
//!
//! The task is the library's (`vivae_neat::benchmarks::boxes`, which `vivae
//! reproduce boxes` runs too); this example is its command line.

mod common;
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize, usage};

use vivae_neat::NeatParams;
use vivae_neat::benchmarks::boxes::{Resampled, run};

/// The first line of `--help`.
const TITLE: &str = "Visual discrimination (boxes) with HyperNEAT: evolved at 11x11, re-sampled at 33x33 and 55x55.";
/// What the summary line holds.
const SUMMARY: &str = "solved=S/N mean_evals=... acc11=... dist11=... acc33=... ...";

fn main() {
    let help = usage("boxes", TITLE, 20, 200, "", SUMMARY);
    let Some(args) = args_or_exit("boxes", &help, &[], &[]) else {
        return;
    };
    let params =
        apply_overrides(NeatParams::paper_cppn(), &args.sets).unwrap_or_else(|e| fail("boxes", &e));
    let runs = args.runs.unwrap_or(20);
    let seed = args.seed.unwrap_or(1);
    let gens = args.max_generations.unwrap_or(200);
    let mut all: Vec<Resampled> = Vec::new();
    let line = summarize("boxes", runs, seed, |seed| {
        let r = run(&params, seed, gens).unwrap_or_else(|e| fail("boxes", &e.to_string()));
        all.push(r.resampled);
        RunResult {
            evals: r.evals,
            hidden: r.hidden,
            generalisation: None,
        }
    });
    let mean = |f: &dyn Fn(&Resampled) -> f64| {
        vivae_neat::stats::mean(&all.iter().map(f).collect::<Vec<_>>()).unwrap_or(0.0)
    };
    let mut extra = String::new();
    for (r, n) in [(0, 11), (1, 33), (2, 55)] {
        extra += &format!(
            " acc{n}={:.3} dist{n}={:.3}",
            mean(&|x| x[r].1),
            mean(&|x| x[r].0)
        );
    }
    println!("{line}{extra}");
}

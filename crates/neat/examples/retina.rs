//! The left & right retina problem (Verbancsics & Stanley 2011; Risi &
//! Stanley 2012), a benchmark for modular networks.
//!
//! `cargo run --release -p vivae-neat --example retina -- --mode leo --runs 20 --seed 1`
//!
//! The task, its modes and options are the library's
//! (`vivae_neat::benchmarks::retina`, which `vivae reproduce retina` runs
//! too); this example is its command line.

mod common;
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize};

use vivae_neat::NeatParams;
use vivae_neat::benchmarks::retina::{Mode, Pixels, Placement, Substrate, run};
use vivae_neat::hyperneat::HyperParams;
use vivae_neat::hyperneat::es::EsParams;

const USAGE: &str = "\
The left & right retina problem with HyperNEAT, LEO and ES-HyperNEAT.

Usage: cargo run --release -p vivae-neat --example retina -- [OPTIONS]

Options:
  --mode M              hyperneat (default), leo, leo-seed, es, es-leo or neat
  --runs N              runs, with seeds S, S+1, ... (default 20)
  --seed S              seed of the first run (default 1)
  --max-generations G   generations before a run counts as unsolved (default 500)
  --pixels P            01 (default: off 0, on 1) or pm3 (off -3, on +3, as AHNI)
  --amplitude A         largest substrate weight (default 3; AHNI uses 6)
  --retina R            line (default: 8 pixels along y = -1) or grid (4x2 grid,
                        layers 4x2 -> 4x2 -> 4x1 -> 2 as AHNI)
  --set FIELD=JSON      override one NeatParams field (repeatable)
  -h, --help            print this help

Prints `retina-MODE: solved=S/N mean_evals=... mean_best_accuracy=... mean_substrate_hidden=...`
on stdout and one line per run on stderr.
";

fn main() {
    let Some(args) = args_or_exit(
        "retina",
        USAGE,
        &[],
        &["--mode", "--pixels", "--amplitude", "--retina"],
    ) else {
        return;
    };
    let mode = Mode::parse(args.option("--mode").unwrap_or("hyperneat"))
        .unwrap_or_else(|e| fail("retina", &e));
    let pixels = Pixels::parse(args.option("--pixels").unwrap_or("01"))
        .unwrap_or_else(|e| fail("retina", &e));
    let placement = Placement::parse(args.option("--retina").unwrap_or("line"))
        .unwrap_or_else(|e| fail("retina", &e));
    let mut hyper = HyperParams::default();
    if let Some(a) = args.option("--amplitude") {
        hyper.amplitude = a
            .parse()
            .map_err(|_| format!("--amplitude needs a number, got `{a}`"))
            .and_then(|amplitude| {
                let h = HyperParams { amplitude, ..hyper };
                h.validate()
                    .map(|()| amplitude)
                    .map_err(|e| format!("--amplitude {a}: {e}"))
            })
            .unwrap_or_else(|e| fail("retina", &e));
    }
    let base = if mode == Mode::Neat {
        NeatParams::plain_neat()
    } else {
        NeatParams::paper_cppn()
    };
    let params = apply_overrides(base, &args.sets).unwrap_or_else(|e| fail("retina", &e));
    let sub = Substrate {
        placement,
        hyper,
        es: EsParams {
            expression: hyper,
            ..EsParams::default()
        },
    };
    let runs = args.runs.unwrap_or(20);
    let seed = args.seed.unwrap_or(1);
    let gens = args.max_generations.unwrap_or(500);
    let (mut substrate_hidden, mut best_right) = (Vec::new(), Vec::new());
    let line = summarize(mode.name(), runs, seed, |seed| {
        let r = run(&params, mode, &sub, pixels, seed, gens)
            .unwrap_or_else(|e| fail("retina", &e.to_string()));
        substrate_hidden.push(r.substrate_hidden as f64);
        best_right.push(r.best_right as f64 / 512.0);
        RunResult {
            evals: r.evals,
            hidden: r.hidden,
            generalisation: None,
        }
    });
    let mean = |v: &[f64]| vivae_neat::stats::mean(v).unwrap_or(0.0);
    println!(
        "{line} mean_best_accuracy={:.3} mean_substrate_hidden={:.1}",
        mean(&best_right),
        mean(&substrate_hidden)
    );
}

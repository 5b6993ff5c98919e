//! The left & right retina problem (Verbancsics & Stanley 2011; Risi &
//! Stanley 2012), a benchmark for modular networks.
//!
//! `cargo run --release -p vivae-neat --example retina -- --mode leo --runs 20 --seed 1`
//!
//! A 4×2 retina: the left 2×2 half and the right 2×2 half each show one of
//! 16 patterns, 8 of which are "objects" (the sets below, as in the
//! `gymnasium-retinatask` package). Output 0 says whether the left half shows
//! an object, output 1 the right half, on all 256 images. Fitness
//! `1000/(1 + E²)`, E the summed |output − label| over both outputs and all
//! images (outputs mapped from (−1, 1) to (0, 1)); solved when every output
//! is on the right side of 0.5. Evaluations are counted up to and including
//! the first solving genome. Besides the summary, the line gives the mean
//! over runs of the best share of right answers and of the hidden nodes of
//! the substrate network that first reached it.
//!
//! Our substrate is two-dimensional (the CPPN sees `(x1, y1, x2, y2)`), so the
//! retina is laid out along a line: the left half's four pixels at x < 0,
//! the right half's at x > 0, all at y = −1; outputs at (∓0.5, 1).
//! `--mode`:
//! * `hyperneat`: plain HyperNEAT, layers 8 → 8 → 4 → 2 at y = −1, −⅓, ⅓, 1,
//!   weight threshold 0.2;
//! * `leo`: the same with a link expression output (LEO), no seed;
//! * `leo-seed`: LEO with the Gaussian locality seed along x;
//! * `es`: ES-HyperNEAT (paper defaults) from the 8 inputs to the 2 outputs;
//! * `es-leo`: ES-HyperNEAT with LEO and the locality seed;
//! * `neat`: no substrate, a plain NEAT network on the 8 pixels and a bias
//!   (direct encoding, `NeatParams::plain_neat` unless `--set` says
//!   otherwise): a check that the task, fitness and success criterion are
//!   solvable as defined here.
//!
//! Closer to the public reproduction AHNI (see docs/hyperneat-benchmarks.md):
//! `--pixels pm3` gives off pixels −3 and on pixels +3 (default `01`: 0 and
//! 1); `--amplitude A` sets the substrate's largest weight (default 3, AHNI
//! 6); `--retina grid` lays the retina as a 4×2 grid (columns x = −1, −⅓, ⅓,
//! 1, rows y = −1 and −⅔) and, for the layered modes, the layers as AHNI's
//! 4×2 → 4×2 → 4×1 → 2 (hidden grid at y = −⅓ and 0, hidden row at y = ⅓).

mod common;
#[path = "common/retina_task.rs"]
mod retina_task;
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize};
use retina_task::{Pixels, Placement, images};

use vivae_neat::hyperneat::es::{EsLayout, EsParams, decode_es_genome};
use vivae_neat::hyperneat::{
    HyperParams, LayeredLayout, SparseNetwork, decode_layered, leo_seeded_genomes,
};
use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Network, Population};

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    HyperNeat,
    Leo,
    LeoSeed,
    Es,
    EsLeo,
    Neat,
}

impl Mode {
    fn parse(s: &str) -> Result<Mode, String> {
        match s {
            "hyperneat" => Ok(Mode::HyperNeat),
            "leo" => Ok(Mode::Leo),
            "leo-seed" => Ok(Mode::LeoSeed),
            "es" => Ok(Mode::Es),
            "es-leo" => Ok(Mode::EsLeo),
            "neat" => Ok(Mode::Neat),
            other => Err(format!(
                "--mode {other}: expected hyperneat, leo, leo-seed, es, es-leo or neat"
            )),
        }
    }
    fn name(self) -> &'static str {
        match self {
            Mode::HyperNeat => "retina-hyperneat",
            Mode::Leo => "retina-leo",
            Mode::LeoSeed => "retina-leo-seed",
            Mode::Es => "retina-es",
            Mode::EsLeo => "retina-es-leo",
            Mode::Neat => "retina-neat",
        }
    }
    fn leo(self) -> bool {
        matches!(self, Mode::Leo | Mode::LeoSeed | Mode::EsLeo)
    }
    fn seeded(self) -> bool {
        matches!(self, Mode::LeoSeed | Mode::EsLeo)
    }
}

const OUTPUTS: [[f64; 2]; 2] = [[-0.5, 1.0], [0.5, 1.0]];

/// The substrate: where the retina lies and the substrate's weight expression.
struct Substrate {
    placement: Placement,
    hyper: HyperParams,
    es: EsParams,
}

/// Builds the substrate network of `g` for `mode`.
fn network(g: &Genome, mode: Mode, sub: &Substrate) -> SparseNetwork {
    let leo_output = mode.leo().then_some(2);
    if matches!(mode, Mode::Es | Mode::EsLeo) {
        let layout = EsLayout {
            inputs: sub.placement.inputs(),
            outputs: OUTPUTS.to_vec(),
            weight_output: 0,
            bias_output: Some(1),
            leo_output,
        };
        return decode_es_genome(g, &layout, &sub.es).expect("valid ES layout");
    }
    let row = |n: usize, y: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| [-1.0 + 2.0 * i as f64 / (n - 1) as f64, y])
            .collect()
    };
    let hidden = match sub.placement {
        Placement::Line => vec![row(8, -1.0 / 3.0), row(4, 1.0 / 3.0)],
        Placement::Grid => vec![
            [row(4, 0.0), row(4, -1.0 / 3.0)].concat(),
            row(4, 1.0 / 3.0),
        ],
    };
    let layout = LayeredLayout {
        layers: [vec![sub.placement.inputs()], hidden, vec![OUTPUTS.to_vec()]].concat(),
        weight_output: 0,
        bias_output: Some(1),
        leo_output,
    };
    let mut cppn = FeedForwardNetwork::from_genome(g);
    decode_layered(&mut cppn, &layout, &sub.hyper).expect("valid layered layout")
}

/// Fitness `1000/(1 + E²)` and how many of the 512 answers are right; a
/// substrate's outputs in (−1, 1) are mapped to (0, 1).
fn evaluate_substrate(net: &mut SparseNetwork, images: &[([f64; 8], [bool; 2])]) -> (f64, usize) {
    evaluate(net, images, |x| *x, |y| (y + 1.0) / 2.0)
}

/// The same for a plain NEAT network: the pixels and a bias of 1 in, its
/// sigmoid outputs in (0, 1) as they are.
fn evaluate_direct(net: &mut FeedForwardNetwork, images: &[([f64; 8], [bool; 2])]) -> (f64, usize) {
    evaluate(
        net,
        images,
        |x| [x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], 1.0],
        |y| y,
    )
}

/// Fitness `1000/(1 + E²)` and how many of the 512 answers are right, with
/// `input` building the network's inputs and `to_unit` mapping an output to (0, 1).
fn evaluate<N: Network, const I: usize>(
    net: &mut N,
    images: &[([f64; 8], [bool; 2])],
    input: impl Fn(&[f64; 8]) -> [f64; I],
    to_unit: impl Fn(f64) -> f64,
) -> (f64, usize) {
    let mut error = 0.0;
    let mut right = 0;
    let mut out = [0.0; 2];
    for (x, labels) in images {
        net.reset();
        net.activate(&input(x), &mut out);
        for (&y, &label) in out.iter().zip(labels) {
            let a = to_unit(y);
            error += (a - f64::from(u8::from(label))).abs();
            right += usize::from((a > 0.5) == label);
        }
    }
    (1000.0 / (1.0 + error * error), right)
}

/// The generation-0 population: minimal CPPNs, or LEO-seeded ones.
fn initial_population(params: &NeatParams, mode: Mode, seed: u64) -> Population {
    if mode == Mode::Neat {
        return Population::new(params.clone(), GenomeSpec::plain(9, 2), seed)
            .expect("valid parameters");
    }
    let spec = GenomeSpec {
        outputs: if mode.leo() { 3 } else { 2 },
        ..GenomeSpec::cppn()
    };
    if !mode.seeded() {
        return Population::new(params.clone(), spec, seed).expect("valid parameters");
    }
    let genomes = leo_seeded_genomes(&spec, params, params.population_size, seed ^ 0x5eed, 2);
    Population::from_genomes(params.clone(), spec, genomes, seed).expect("valid seeded genomes")
}

/// What a run leaves besides the summary: the best number of right answers
/// (of 512) and the hidden nodes of the substrate that first gave it.
struct Extra {
    best_right: usize,
    substrate_hidden: usize,
}

/// One run: evaluations to the first solver, its CPPN's hidden nodes, and [`Extra`].
fn run(
    params: &NeatParams,
    mode: Mode,
    sub: &Substrate,
    pixels: Pixels,
    seed: u64,
    gens: u32,
) -> (RunResult, Extra) {
    let images = images(pixels);
    let mut pop = initial_population(params, mode, seed);
    let (mut best_right, mut best_hidden) = (0, 0);
    for _ in 0..gens {
        let mut fitness = Vec::with_capacity(pop.genomes().len());
        let mut first = None;
        for (i, g) in pop.genomes().iter().enumerate() {
            let (f, right, hidden) = if mode == Mode::Neat {
                let mut net = FeedForwardNetwork::from_genome(g);
                let (f, right) = evaluate_direct(&mut net, &images);
                (f, right, g.num_hidden())
            } else {
                let mut net = network(g, mode, sub);
                let (f, right) = evaluate_substrate(&mut net, &images);
                (f, right, net.num_hidden())
            };
            fitness.push(f);
            if right > best_right {
                (best_right, best_hidden) = (right, hidden);
            }
            if right == 512 && first.is_none() {
                first = Some(i);
            }
        }
        pop.set_fitnesses(fitness).expect("one fitness per genome");
        if let Some(i) = first {
            let evals = pop.generation() as usize * pop.params().population_size + i + 1;
            let hidden = pop.genomes()[i].num_hidden();
            let extra = Extra {
                best_right,
                substrate_hidden: best_hidden,
            };
            return (
                RunResult {
                    evals: Some(evals),
                    hidden,
                    generalisation: None,
                },
                extra,
            );
        }
        pop.next_generation();
    }
    let extra = Extra {
        best_right,
        substrate_hidden: best_hidden,
    };
    (RunResult::unsolved(), extra)
}

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
        let (result, extra) = run(&params, mode, &sub, pixels, seed, gens);
        substrate_hidden.push(extra.substrate_hidden as f64);
        best_right.push(extra.best_right as f64 / 512.0);
        result
    });
    let mean = |v: &[f64]| vivae_neat::stats::mean(v).unwrap_or(0.0);
    println!(
        "{line} mean_best_accuracy={:.3} mean_substrate_hidden={:.1}",
        mean(&best_right),
        mean(&substrate_hidden)
    );
}

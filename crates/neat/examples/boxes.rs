//! Visual discrimination ("boxes", Stanley, D'Ambrosio & Gauci 2009): find
//! the larger of two objects, evolved at 11×11 and re-sampled at 33×33 and
//! 55×55 without further evolution.
//!
//! `cargo run --release -p vivae-neat --example boxes -- --runs 20 --seed 1`
//!
//! An 11×11 visual field shows a 1×1 and a 3×3 box; an 11×11 target field
//! of the same geometry answers with its most active node, which should be
//! the centre of the large box. One CPPN output paints every visual →
//! target weight (queried `(x1, y1)` target, `(x2, y2)` source; threshold
//! 0.2, amplitude 3); a target node's activation is the weighted sum of the
//! lit visual nodes. 75 trials: the small box at the 25 positions of a 5×5
//! grid (cells 1, 3, …, 9), the large box 5 cells right, down or diagonally
//! from it, wrapping around the field (and clipped at its edge), as in the
//! paper. Fitness (ours) `100/(1 + d̄)`, d̄ the mean distance in cells from
//! the chosen node to the large box's centre; accuracy: the share of trials
//! whose chosen node lies in the large box's centre cell. Solved: all 75 at
//! 11×11. At resolution `11k` the same scene is drawn with `k×k` pixels per
//! cell and the same CPPN is queried at the finer node positions.

mod common;
use common::{RunResult, apply_overrides, args_or_exit, fail, summarize};

use vivae_neat::hyperneat::{BatchCppn, HyperParams};
use vivae_neat::{Genome, GenomeSpec, NeatParams, Population};

const CELLS: usize = 11;

/// A trial in cell units: the small box's cell and the large box's centre cell.
struct Trial {
    small: (usize, usize),
    big: (usize, usize),
}

fn trials() -> Vec<Trial> {
    let grid = [1, 3, 5, 7, 9];
    let mut t = Vec::new();
    for &sy in &grid {
        for &sx in &grid {
            for (dx, dy) in [(5, 0), (0, 5), (5, 5)] {
                t.push(Trial {
                    small: (sx, sy),
                    big: ((sx + dx) % CELLS, (sy + dy) % CELLS),
                });
            }
        }
    }
    t
}

/// The pixels (row-major, `n = 11k` wide) a trial lights.
fn lit(trial: &Trial, n: usize) -> Vec<usize> {
    let k = n / CELLS;
    let mut cells = vec![trial.small];
    let (cx, cy) = (trial.big.0 as isize, trial.big.1 as isize);
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (x, y) = (cx + dx, cy + dy);
            if (0..CELLS as isize).contains(&x) && (0..CELLS as isize).contains(&y) {
                cells.push((x as usize, y as usize));
            }
        }
    }
    let mut pixels = Vec::new();
    for (x, y) in cells {
        for py in y * k..(y + 1) * k {
            pixels.extend((x * k..(x + 1) * k).map(|px| py * n + px));
        }
    }
    pixels
}

/// Node positions of an `n × n` field in CPPN space, row-major.
fn positions(n: usize) -> Vec<[f64; 2]> {
    let c = |i: usize| -1.0 + (2 * i + 1) as f64 / n as f64;
    (0..n * n).map(|j| [c(j % n), c(j / n)]).collect()
}

/// A genome's answers at resolution `n`: (mean distance in cells, trials hit).
fn score(g: &Genome, n: usize, trials: &[Trial]) -> (f64, usize) {
    let mut cppn = BatchCppn::new(g).expect("feed-forward CPPN");
    let params = HyperParams::default();
    let nodes = positions(n);
    let k = n / CELLS;
    let mut columns: Vec<Option<Vec<f64>>> = vec![None; n * n];
    let mut act = vec![0.0; n * n];
    let (mut distance, mut hits) = (0.0, 0);
    for t in trials {
        act.fill(0.0);
        for s in lit(t, n) {
            let column = columns[s].get_or_insert_with(|| {
                let mut w = vec![0.0; n * n];
                cppn.query_targets(0, &nodes, nodes[s], &mut w);
                w.iter_mut()
                    .for_each(|o| *o = params.express(*o).unwrap_or(0.0));
                w
            });
            act.iter_mut().zip(column.iter()).for_each(|(a, w)| *a += w);
        }
        let best = (0..n * n).fold(0, |b, j| if act[j] > act[b] { j } else { b });
        let (ox, oy) = (best % n, best / n);
        let at = |p: usize| (p as f64 + 0.5) / k as f64 - 0.5;
        let (dx, dy) = (at(ox) - t.big.0 as f64, at(oy) - t.big.1 as f64);
        distance += (dx * dx + dy * dy).sqrt();
        hits += usize::from(ox / k == t.big.0 && oy / k == t.big.1);
    }
    (distance / trials.len() as f64, hits)
}

/// One run's champion at 11, 33 and 55: (mean distance, accuracy) each.
type Resampled = [(f64, f64); 3];

/// One run: evolve at 11×11 (stopping once solved), then re-sample the champion.
fn run(params: &NeatParams, seed: u64, gens: u32) -> (RunResult, Resampled) {
    let trials = trials();
    let spec = GenomeSpec {
        outputs: 1,
        ..GenomeSpec::cppn()
    };
    let mut pop = Population::new(params.clone(), spec, seed).expect("valid parameters");
    let mut solved = None;
    for _ in 0..gens {
        let scores: Vec<(f64, usize)> = pop
            .genomes()
            .iter()
            .map(|g| score(g, CELLS, &trials))
            .collect();
        let fitness = scores.iter().map(|&(d, _)| 100.0 / (1.0 + d)).collect();
        pop.set_fitnesses(fitness).expect("one fitness per genome");
        if let Some(i) = scores.iter().position(|&(_, h)| h == trials.len()) {
            let evals = pop.generation() as usize * pop.params().population_size + i + 1;
            solved = Some((evals, pop.genomes()[i].clone()));
            break;
        }
        pop.next_generation();
    }
    let (evals, champion) = match solved {
        Some((e, g)) => (Some(e), g),
        None => (None, pop.best_ever().expect("evaluated").genome.clone()),
    };
    let resampled = [1, 3, 5].map(|k| {
        let (d, h) = score(&champion, CELLS * k, &trials);
        (d, h as f64 / trials.len() as f64)
    });
    let hidden = champion.num_hidden();
    (
        RunResult {
            evals,
            hidden,
            generalisation: None,
        },
        resampled,
    )
}

const USAGE: &str = "\
Visual discrimination (boxes) with HyperNEAT: evolved at 11x11, re-sampled at 33x33 and 55x55.

Usage: cargo run --release -p vivae-neat --example boxes -- [OPTIONS]

Options:
  --runs N              runs, with seeds S, S+1, ... (default 20)
  --seed S              seed of the first run (default 1)
  --max-generations G   generations before a run counts as unsolved (default 200)
  --set FIELD=JSON      override one NeatParams field (repeatable)
  -h, --help            print this help

Prints `boxes: solved=S/N mean_evals=... acc11=... dist11=... acc33=... ...`
on stdout and one line per run on stderr.
";

fn main() {
    let Some(args) = args_or_exit("boxes", USAGE, &[], &[]) else {
        return;
    };
    let params =
        apply_overrides(NeatParams::paper_cppn(), &args.sets).unwrap_or_else(|e| fail("boxes", &e));
    let runs = args.runs.unwrap_or(20);
    let seed = args.seed.unwrap_or(1);
    let gens = args.max_generations.unwrap_or(200);
    let mut all: Vec<Resampled> = Vec::new();
    let line = summarize("boxes", runs, seed, |seed| {
        let (result, resampled) = run(&params, seed, gens);
        all.push(resampled);
        result
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

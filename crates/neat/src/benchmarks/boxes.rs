//! Visual discrimination ("boxes", Stanley, D'Ambrosio & Gauci 2009, "A
//! hypercube-based encoding for evolving large-scale neural networks",
//! Artificial Life 15(2)): find the larger of two objects, evolved at 11×11
//! and re-sampled at 33×33 and 55×55 without further evolution; the task of
//! `cargo run -p vivae-neat --example boxes` and `vivae reproduce boxes`
//! (docs/hyperneat-benchmarks.md).
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

use crate::hyperneat::{BatchCppn, HyperParams};
use crate::{Genome, GenomeSpec, NeatError, NeatParams, Population};

/// The field's width in cells at the evolved resolution.
pub const CELLS: usize = 11;

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
pub type Resampled = [(f64, f64); 3];

/// One run's outcome.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxesRun {
    /// Evaluations up to and including the first genome solving all 75
    /// trials at 11×11, `None` when unsolved.
    pub evals: Option<usize>,
    /// Hidden nodes of the champion's CPPN (the solver, else the best ever).
    pub hidden: usize,
    /// The champion at 11×11, 33×33 and 55×55: (mean distance, accuracy).
    pub resampled: Resampled,
}

/// One run: evolve at 11×11 for at most `gens` generations (stopping once
/// solved), then re-sample the champion.
pub fn run(params: &NeatParams, seed: u64, gens: u32) -> Result<BoxesRun, NeatError> {
    let trials = trials();
    let spec = GenomeSpec {
        outputs: 1,
        ..GenomeSpec::cppn()
    };
    let mut pop = Population::new(params.clone(), spec, seed)?;
    let mut solved = None;
    for _ in 0..gens {
        let scores: Vec<(f64, usize)> = pop
            .genomes()
            .iter()
            .map(|g| score(g, CELLS, &trials))
            .collect();
        let fitness = scores.iter().map(|&(d, _)| 100.0 / (1.0 + d)).collect();
        pop.set_fitnesses(fitness)?;
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
    Ok(BoxesRun {
        evals,
        hidden: champion.num_hidden(),
        resampled,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_trials_are_the_papers_75_and_a_run_resamples_its_champion() {
        let t = trials();
        assert_eq!(t.len(), 75);
        assert!(t.iter().all(|t| t.small != t.big));
        let r = run(&NeatParams::paper_cppn(), 1, 2).unwrap();
        assert_eq!(
            run(&NeatParams::paper_cppn(), 1, 2).unwrap(),
            r,
            "deterministic"
        );
        for (d, acc) in r.resampled {
            assert!(d >= 0.0 && (0.0..=1.0).contains(&acc), "{r:?}");
        }
        if let Some(e) = r.evals {
            assert!(e <= 200 && r.resampled[0].1 == 1.0, "{r:?}");
        }
    }
}

//! The strategies' own work per generation at population 1,000 with an
//! archive of 10,000: novelty search's k-NN sparseness and archive update,
//! MAP-Elites' archive insertion (grid and CVT), NSGA-II's non-dominated
//! sort and crowding; and the k-NN itself against brute force as the
//! archive grows. NEAT's breeding (shared by every strategy) is the `neat`
//! bench's `reproduction`.

use divan::{Bencher, black_box};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use vivae_neat::driver::{Evaluation, Strategy};
use vivae_neat::strategies::knn::{KdTree, Nearest, brute_force_sparseness};
use vivae_neat::strategies::nsga2::{
    crowding_distances, fast_non_dominated_sort, non_dominated_fronts,
};
use vivae_neat::strategies::{Cells, MapElites, MapElitesParams, NoveltyParams, NoveltySearch};
use vivae_neat::{GenomeSpec, NeatParams, Population};

fn main() {
    divan::main();
}

const POPULATION: usize = 1000;
const ARCHIVE: usize = 10_000;

/// `n` points of `dims` coordinates, uniform in [0, 800) like end positions on a map.
fn points(n: usize, dims: usize, seed: u64) -> Vec<f64> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n * dims).map(|_| rng.random::<f64>() * 800.0).collect()
}

/// One evaluation per genome, with the given behaviours.
fn evaluations(behaviours: &[f64], dims: usize) -> Vec<Evaluation> {
    behaviours
        .chunks_exact(dims)
        .enumerate()
        .map(|(i, b)| Evaluation {
            fitness: i as f64,
            metrics: vec![],
            behaviour: b.to_vec(),
        })
        .collect()
}

fn params() -> NeatParams {
    NeatParams {
        population_size: POPULATION,
        ..NeatParams::default()
    }
}

/// Novelty search's `tell` (sparseness of 1,000 behaviours against each
/// other and 10,000 archived ones, archive update, threshold) for
/// behaviours of `dims` coordinates (2: an end position).
#[divan::bench(args = [2, 8])]
fn novelty_tell(bencher: Bencher, dims: usize) {
    let novelty = NoveltyParams {
        threshold: 1e-9,
        raise_factor: 1.0,
        ..NoveltyParams::default()
    };
    let population = Population::new(params(), GenomeSpec::cppn(), 1).unwrap();
    let mut ns = NoveltySearch::new(population, novelty).unwrap();
    for round in 0..ARCHIVE / POPULATION {
        ns.tell(&evaluations(&points(POPULATION, dims, round as u64), dims))
            .unwrap();
    }
    assert_eq!(ns.archive().len(), ARCHIVE);
    let told = evaluations(&points(POPULATION, dims, 99), dims);
    bencher
        .with_inputs(|| ns.clone())
        .bench_local_refs(|ns| ns.tell(black_box(&told)).unwrap());
}

/// The sparseness (k = 15) of the last 1,000 of `all` (points of `dims`
/// coordinates) against all the others, by the k-d tree built each time,
/// as every generation does.
fn kd_tree_sparseness(all: &[f64], dims: usize) -> f64 {
    let tree = KdTree::new(dims, all.to_vec());
    let mut nearest = Nearest::new(15);
    (tree.len() - POPULATION..tree.len())
        .map(|i| {
            tree.nearest_k(tree.point(i), Some(i), &mut nearest);
            nearest.mean_distance()
        })
        .sum()
}

/// The same by brute force.
fn brute_force(all: &[f64], dims: usize) -> f64 {
    let n = all.len() / dims;
    (n - POPULATION..n)
        .map(|i| brute_force_sparseness(dims, all, i, 15))
        .sum()
}

/// Sparseness of 1,000 end positions against `archive` others by the k-d tree.
#[divan::bench(args = [1_000, 10_000, 40_000])]
fn sparseness_kd_tree(bencher: Bencher, archive: usize) {
    let all = points(archive + POPULATION, 2, 5);
    bencher.bench_local(|| kd_tree_sparseness(black_box(&all), 2));
}

/// The same by brute force: grows linearly with the archive.
#[divan::bench(args = [1_000, 10_000, 40_000])]
fn sparseness_brute_force(bencher: Bencher, archive: usize) {
    let all = points(archive + POPULATION, 2, 5);
    bencher.bench_local(|| brute_force(black_box(&all), 2));
}

/// Sparseness of 1,000 behaviours of 8 uniform coordinates (the k-d tree's
/// worst case) against 10,000, by the tree and by brute force.
#[divan::bench(args = ["kd_tree", "brute_force"])]
fn sparseness_8d(bencher: Bencher, how: &str) {
    let all = points(ARCHIVE + POPULATION, 8, 5);
    let f = if how == "kd_tree" {
        kd_tree_sparseness
    } else {
        brute_force
    };
    bencher.bench_local(|| f(black_box(&all), 8));
}

/// A MAP-Elites archive of 10,000 cells, filled (generation 0 and 9 more
/// told), ready to be told a batch of 1,000.
fn map_elites(cells: Cells) -> (MapElites, Vec<Evaluation>) {
    let map = MapElitesParams {
        batch_size: POPULATION,
        ..MapElitesParams::default()
    };
    let mut me = MapElites::new(params(), GenomeSpec::cppn(), map, cells, 1).unwrap();
    for round in 0..10 {
        me.ask();
        me.tell(&evaluations(&points(POPULATION, 2, round), 2))
            .unwrap();
    }
    me.prepare();
    (me, evaluations(&points(POPULATION, 2, 99), 2))
}

/// MAP-Elites' `tell` (cell lookup and insertion of 1,000 genomes) into 100 × 100 grid cells.
#[divan::bench]
fn map_elites_tell_grid(bencher: Bencher) {
    let cells = Cells::grid(vec![0.0; 2], vec![800.0; 2], vec![100, 100]).unwrap();
    let (me, told) = map_elites(cells);
    bencher
        .with_inputs(|| me.clone())
        .bench_local_refs(|me| me.tell(black_box(&told)).unwrap());
}

/// The same into 10,000 CVT cells (nearest-centroid lookup).
#[divan::bench]
fn map_elites_tell_cvt(bencher: Bencher) {
    let cells = Cells::cvt(&[0.0; 2], &[800.0; 2], ARCHIVE, 50_000, 5, 1).unwrap();
    let (me, told) = map_elites(cells);
    bencher
        .with_inputs(|| me.clone())
        .bench_local_refs(|me| me.tell(black_box(&told)).unwrap());
}

/// Building the 10,000 CVT centroids (once per run): 50,000 samples, 5 Lloyd iterations.
#[divan::bench(sample_count = 5)]
fn cvt_centroids(bencher: Bencher) {
    bencher.bench_local(|| Cells::cvt(&[0.0; 2], &[800.0; 2], ARCHIVE, 50_000, 5, 1).unwrap());
}

/// NSGA-II's selection work on parents ∪ children (2,000): the fast
/// non-dominated sort and every front's crowding distances, for
/// `objectives` objectives.
#[divan::bench(args = [2, 3])]
fn nsga2_sort_and_crowding(bencher: Bencher, objectives: usize) {
    let values = points(2 * POPULATION, objectives, 3);
    let rows: Vec<&[f64]> = values.chunks_exact(objectives).collect();
    let mut crowd = vec![0.0; rows.len()];
    bencher.bench_local(|| {
        for front in non_dominated_fronts(black_box(&rows)) {
            crowding_distances(&front, &rows, &mut crowd);
        }
        crowd[0]
    });
}

/// Deb's O(M·N²) fast non-dominated sort on the same 2,000, for comparison.
#[divan::bench(args = [2, 3])]
fn nsga2_debs_sort(bencher: Bencher, objectives: usize) {
    let values = points(2 * POPULATION, objectives, 3);
    let rows: Vec<&[f64]> = values.chunks_exact(objectives).collect();
    bencher.bench_local(|| fast_non_dominated_sort(black_box(&rows)).len());
}

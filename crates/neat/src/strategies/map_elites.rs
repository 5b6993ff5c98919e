//! MAP-Elites (Mouret & Clune 2015, "Illuminating search spaces by mapping elites").
//!
//! The behaviour space is cut into cells, a regular grid or a centroidal
//! Voronoi tessellation (CVT, Vassiliades et al. 2018); each cell keeps the
//! fittest genome whose behaviour fell in it. Every generation, a batch of
//! children is bred from elites picked uniformly at random, by NEAT's
//! crossover (with [`MapElitesParams::crossover_probability`]) and mutation
//! over one innovation history; generation 0 is a batch of minimal genomes.

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};

use super::knn::KdTree;
use super::{Breeding, argmax, check_count, invalid, record_best};
use crate::driver::{Batch, Evaluation, Strategy, finite_or_zero};
use crate::error::NeatError;
use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;
use crate::population::{BestEver, GenerationStats};

/// Most cells an archive may have (each holds an optional genome).
pub const MAX_CELLS: usize = 1_000_000;
/// Most samples a CVT may be built from.
pub const MAX_SAMPLES: usize = 10_000_000;

/// How the behaviour space is cut into cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Cells {
    /// `bins[d]` equal cells from `lower[d]` to `upper[d]` along each
    /// dimension d (the first most significant in the cell index); a
    /// behaviour outside the bounds falls in the nearest edge cell.
    Grid {
        /// Lower bound per dimension.
        lower: Vec<f64>,
        /// Upper bound per dimension.
        upper: Vec<f64>,
        /// Cells per dimension.
        bins: Vec<usize>,
    },
    /// A behaviour's cell is its nearest centroid (the lowest index on a tie).
    Cvt(KdTree),
}

impl Cells {
    /// A regular grid (see [`Cells::Grid`]); bounds finite with `lower < upper`.
    pub fn grid(lower: Vec<f64>, upper: Vec<f64>, bins: Vec<usize>) -> Result<Cells, NeatError> {
        check_bounds(&lower, &upper)?;
        if bins.len() != lower.len() || bins.contains(&0) {
            return Err(invalid(
                "bins",
                format!("{bins:?}"),
                "one count ≥ 1 per dimension",
            ));
        }
        let cells = bins.iter().try_fold(1usize, |n, &b| n.checked_mul(b));
        if cells.is_none_or(|n| n > MAX_CELLS) {
            return Err(invalid(
                "bins",
                format!("{bins:?}"),
                "more than 1,000,000 cells",
            ));
        }
        Ok(Cells::Grid { lower, upper, bins })
    }

    /// A CVT of `cells` centroids in the box `lower`..`upper`: `samples`
    /// points drawn uniformly from a `Pcg64` seeded with `seed`, the first
    /// `cells` of them as initial centroids, then `iterations` of Lloyd's
    /// algorithm (each centroid moves to the mean of the samples nearest to
    /// it; one with none stays). The same arguments give the same bits.
    pub fn cvt(
        lower: &[f64],
        upper: &[f64],
        cells: usize,
        samples: usize,
        iterations: usize,
        seed: u64,
    ) -> Result<Cells, NeatError> {
        check_bounds(lower, upper)?;
        if cells == 0 || samples < cells || cells > MAX_CELLS || samples > MAX_SAMPLES {
            let value = format!("{cells} cells from {samples} samples");
            let reason = "need 1 ≤ cells ≤ samples, at most 1,000,000 cells and 10,000,000 samples";
            return Err(invalid("cells", value, reason));
        }
        let dims = lower.len();
        let mut rng = Pcg64::seed_from_u64(seed);
        let points: Vec<f64> = (0..samples * dims)
            .map(|i| {
                let d = i % dims;
                lower[d] + (upper[d] - lower[d]) * rng.random::<f64>()
            })
            .collect();
        let mut tree = KdTree::new(dims, points[..cells * dims].to_vec());
        let (mut sums, mut counts) = (vec![0.0; cells * dims], vec![0usize; cells]);
        for _ in 0..iterations {
            sums.fill(0.0);
            counts.fill(0);
            for p in points.chunks_exact(dims) {
                let c = tree.nearest(p).unwrap_or(0);
                counts[c] += 1;
                for (s, x) in sums[c * dims..(c + 1) * dims].iter_mut().zip(p) {
                    *s += x;
                }
            }
            let centroids = (0..cells * dims).map(|i| match counts[i / dims] {
                0 => tree.point(i / dims)[i % dims],
                n => sums[i] / n as f64,
            });
            let centroids: Vec<f64> = centroids.collect();
            tree.reset(centroids);
        }
        Ok(Cells::Cvt(tree))
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        match self {
            Cells::Grid { bins, .. } => bins.iter().product(),
            Cells::Cvt(tree) => tree.len(),
        }
    }

    /// Whether there are no cells (never, once built).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Coordinates of a behaviour.
    pub fn dims(&self) -> usize {
        match self {
            Cells::Grid { bins, .. } => bins.len(),
            Cells::Cvt(tree) => tree.dims(),
        }
    }

    /// The cell of `behaviour` (of [`Cells::dims`] coordinates).
    pub fn cell_of(&self, behaviour: &[f64]) -> usize {
        match self {
            Cells::Grid { lower, upper, bins } => {
                let mut cell = 0;
                for (d, &x) in behaviour.iter().enumerate() {
                    let t = (x - lower[d]) / (upper[d] - lower[d]) * bins[d] as f64;
                    // NaN goes to 0 with the cast; ±∞ to the edge cells.
                    let i = (t.max(0.0) as usize).min(bins[d] - 1);
                    cell = cell * bins[d] + i;
                }
                cell
            }
            Cells::Cvt(tree) => tree.nearest(behaviour).unwrap_or(0),
        }
    }

    fn check(&self) -> Result<(), NeatError> {
        match self {
            Cells::Grid { lower, upper, bins } => {
                Cells::grid(lower.clone(), upper.clone(), bins.clone()).map(|_| ())
            }
            Cells::Cvt(tree) if tree.is_empty() => Err(invalid("cells", 0, "no centroids")),
            Cells::Cvt(_) => Ok(()),
        }
    }
}

/// Bounds of a behaviour box: as many lower as upper, finite, `lower < upper`.
fn check_bounds(lower: &[f64], upper: &[f64]) -> Result<(), NeatError> {
    let ok = !lower.is_empty()
        && lower.len() == upper.len()
        && lower
            .iter()
            .zip(upper)
            .all(|(l, u)| l.is_finite() && u.is_finite() && l < u);
    if ok {
        Ok(())
    } else {
        let value = format!("{lower:?}..{upper:?}");
        Err(invalid(
            "bounds",
            value,
            "finite, lower < upper, ≥ 1 dimension",
        ))
    }
}

/// MAP-Elites' own settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapElitesParams {
    /// Genomes evaluated per generation (generation 0 included).
    pub batch_size: usize,
    /// Probability that a child is a crossover of two elites rather than a
    /// mutant of one.
    pub crossover_probability: f64,
    /// Subtracted from every elite's fitness in the QD-score (pyribs'
    /// `qd_offset`), so that it is a sum of non-negative values.
    pub qd_offset: f64,
}

impl Default for MapElitesParams {
    /// Batches of 100, a tenth of them crossovers, no QD offset.
    fn default() -> Self {
        MapElitesParams {
            batch_size: 100,
            crossover_probability: 0.1,
            qd_offset: 0.0,
        }
    }
}

/// The best genome found for one cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Elite {
    /// The genome.
    pub genome: Genome,
    /// Its fitness.
    pub fitness: f64,
    /// Its behaviour (non-finite coordinates as 0).
    pub behaviour: Vec<f64>,
    /// The generation in which it was evaluated.
    pub generation: u32,
}

/// The archive at a glance (for `generations.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapElitesStats {
    /// Cells holding an elite.
    pub filled: usize,
    /// Filled cells over all cells.
    pub coverage: f64,
    /// Σ (fitness − qd_offset) over the elites.
    pub qd_score: f64,
    /// Fitness of the best elite.
    pub best: Option<f64>,
}

/// What the batch just told gave.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Told {
    fitness: Vec<f64>,
    /// Elites the batch placed (new cells or better than the incumbent).
    inserted: usize,
}

/// The serialised state of [`MapElites`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct State {
    spec: GenomeSpec,
    params: NeatParams,
    map: MapElitesParams,
    cells: Cells,
    archive: Vec<Option<Elite>>,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    batch: Vec<Genome>,
    told: Option<Told>,
    best: Option<BestEver>,
}

/// MAP-Elites over NEAT genomes (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "State")]
pub struct MapElites(State);

impl TryFrom<State> for MapElites {
    type Error = NeatError;

    fn try_from(s: State) -> Result<Self, NeatError> {
        s.params.validate()?;
        s.spec.validate()?;
        check_params(&s.map)?;
        s.cells.check()?;
        if s.archive.len() != s.cells.len() {
            return Err(invalid("archive", s.archive.len(), "one entry per cell"));
        }
        let dims = s.cells.dims();
        let elite_ok = |e: &Elite| {
            e.fitness.is_finite() && e.behaviour.len() == dims && e.generation <= s.generation
        };
        if !s.archive.iter().flatten().all(elite_ok) {
            return Err(invalid(
                "archive",
                "an elite",
                "inconsistent with the cells",
            ));
        }
        if s.batch.is_empty()
            || s.told
                .as_ref()
                .is_some_and(|t| t.fitness.len() != s.batch.len())
        {
            return Err(invalid(
                "batch",
                s.batch.len(),
                "empty or not matching its fitness",
            ));
        }
        // Telling a batch always fills a cell: breeding needs one.
        let told = s.told.is_some() || s.generation > 0;
        if told && s.archive.iter().all(Option::is_none) {
            return Err(invalid("archive", 0, "empty after a batch was told"));
        }
        Ok(MapElites(s))
    }
}

fn check_params(p: &MapElitesParams) -> Result<(), NeatError> {
    if p.batch_size == 0 {
        return Err(invalid("batch_size", 0, "must be at least 1"));
    }
    if !(0.0..=1.0).contains(&p.crossover_probability) {
        let value = p.crossover_probability;
        return Err(invalid("crossover_probability", value, "must be in [0, 1]"));
    }
    if !p.qd_offset.is_finite() {
        return Err(invalid("qd_offset", p.qd_offset, "must be finite"));
    }
    Ok(())
}

impl MapElites {
    /// An empty archive over `cells`; generation 0 is `map.batch_size`
    /// minimal genomes drawn from a `Pcg64` seeded with `seed` (also the run
    /// seed of every evaluation context).
    pub fn new(
        params: NeatParams,
        spec: GenomeSpec,
        map: MapElitesParams,
        cells: Cells,
        seed: u64,
    ) -> Result<MapElites, NeatError> {
        params.validate()?;
        spec.validate()?;
        check_params(&map)?;
        cells.check()?;
        let mut rng = Pcg64::seed_from_u64(seed);
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        let batch = Breeding {
            spec: &spec,
            params: &params,
            tracker: &mut tracker,
            rng: &mut rng,
        }
        .minimal(map.batch_size);
        Ok(MapElites(State {
            archive: vec![None; cells.len()],
            spec,
            params,
            map,
            cells,
            seed,
            generation: 0,
            rng,
            tracker,
            batch,
            told: None,
            best: None,
        }))
    }

    /// The cells.
    pub fn cells(&self) -> &Cells {
        &self.0.cells
    }

    /// The settings.
    pub fn params(&self) -> &MapElitesParams {
        &self.0.map
    }

    /// Every elite with its cell index, in cell order.
    pub fn elites(&self) -> impl Iterator<Item = (usize, &Elite)> {
        (self.0.archive.iter().enumerate()).filter_map(|(i, e)| e.as_ref().map(|e| (i, e)))
    }

    /// Elites placed by the batch just told (0 before `tell`).
    pub fn inserted(&self) -> usize {
        self.0.told.as_ref().map_or(0, |t| t.inserted)
    }

    /// Coverage, QD-score and best fitness of the archive.
    pub fn archive_stats(&self) -> MapElitesStats {
        let (mut filled, mut qd_score, mut best) = (0, 0.0, None::<f64>);
        for (_, e) in self.elites() {
            filled += 1;
            qd_score += e.fitness - self.0.map.qd_offset;
            best = Some(best.map_or(e.fitness, |b| b.max(e.fitness)));
        }
        MapElitesStats {
            filled,
            coverage: filled as f64 / self.0.archive.len() as f64,
            qd_score,
            best,
        }
    }
}

/// Places a genome in its cell if the cell is empty or it is strictly
/// fitter than the cell's elite; says whether it did.
pub fn insert(archive: &mut [Option<Elite>], cell: usize, candidate: Elite) -> bool {
    let slot = &mut archive[cell];
    if slot.as_ref().is_none_or(|e| candidate.fitness > e.fitness) {
        *slot = Some(candidate);
        true
    } else {
        false
    }
}

impl Strategy for MapElites {
    fn ask(&mut self) -> Batch<'_> {
        self.prepare();
        Batch::new(&self.0.batch, self.0.seed, self.0.generation)
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        let s = &mut self.0;
        check_count(evaluations.len(), s.batch.len())?;
        let dims = s.cells.dims();
        if let Some(e) = evaluations.iter().find(|e| e.behaviour.len() != dims) {
            let reason = "the behaviour must have as many coordinates as the cells";
            return Err(invalid("behaviour", e.behaviour.len(), reason));
        }
        let fitness: Vec<f64> = evaluations.iter().map(Evaluation::finite_fitness).collect();
        let mut inserted = 0;
        for ((genome, e), &f) in s.batch.iter().zip(evaluations).zip(&fitness) {
            let behaviour: Vec<f64> = e.behaviour.iter().map(|&x| finite_or_zero(x)).collect();
            let cell = s.cells.cell_of(&behaviour);
            let elite = Elite {
                genome: genome.clone(),
                fitness: f,
                behaviour,
                generation: s.generation,
            };
            inserted += usize::from(insert(&mut s.archive, cell, elite));
        }
        record_best(&mut s.best, &s.batch, &fitness, s.generation);
        s.told = Some(Told { fitness, inserted });
        Ok(())
    }

    fn prepare(&mut self) {
        let s = &mut self.0;
        if s.told.take().is_none() {
            return;
        }
        let occupied: Vec<&Elite> = s.archive.iter().flatten().collect();
        let mut breeding = Breeding {
            spec: &s.spec,
            params: &s.params,
            tracker: &mut s.tracker,
            rng: &mut s.rng,
        };
        s.batch.clear();
        for _ in 0..s.map.batch_size {
            let a = occupied[breeding.rng.random_range(0..occupied.len())];
            let b = (breeding.rng.random_bool(s.map.crossover_probability))
                .then(|| occupied[breeding.rng.random_range(0..occupied.len())]);
            let child = breeding.child((&a.genome, a.fitness), b.map(|b| (&b.genome, b.fitness)));
            s.batch.push(child);
        }
        s.generation += 1;
    }

    fn generation(&self) -> u32 {
        self.0.generation
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        let f = &self.0.told.as_ref()?.fitness;
        argmax(f).map(|i| (&self.0.batch[i], f[i]))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.0.best.as_ref()
    }

    fn stats(&self) -> GenerationStats {
        let fitness = self.0.told.as_ref().map_or(&[][..], |t| &t.fitness);
        GenerationStats::of_batch(self.0.generation, &self.0.batch, fitness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::{prop, prop_assert_eq, proptest};

    #[test]
    fn grid_cells_are_row_major_and_clamped() {
        let cells = Cells::grid(vec![0.0, -1.0], vec![10.0, 1.0], vec![5, 2]).unwrap();
        assert_eq!(cells.len(), 10);
        assert_eq!(cells.cell_of(&[0.0, -1.0]), 0);
        assert_eq!(
            cells.cell_of(&[3.9, 0.5]),
            2 + 1,
            "row 1 of 2 cells, column 1"
        );
        assert_eq!(
            cells.cell_of(&[10.0, 1.0]),
            9,
            "the upper bound is in the last cell"
        );
        assert_eq!(
            cells.cell_of(&[-5.0, 7.0]),
            1,
            "outside: the nearest edge cell"
        );
        assert_eq!(cells.cell_of(&[f64::NAN, f64::INFINITY]), 1);
        assert!(Cells::grid(vec![0.0], vec![0.0], vec![3]).is_err());
        assert!(Cells::grid(vec![0.0], vec![1.0], vec![0]).is_err());
        let huge = Cells::grid(vec![0.0; 2], vec![1.0; 2], vec![1_000_000, 1_000_000]);
        assert!(huge.is_err(), "refused, not allocated");
        assert!(Cells::cvt(&[0.0], &[1.0], 10, usize::MAX, 1, 0).is_err());
    }

    #[test]
    fn cvt_is_deterministic_and_its_centroids_spread_over_the_box() {
        let make = || Cells::cvt(&[0.0, 0.0], &[1.0, 2.0], 16, 2000, 10, 5).unwrap();
        let (a, b) = (make(), make());
        assert_eq!(a, b);
        let Cells::Cvt(tree) = &a else { unreachable!() };
        assert_eq!(tree.len(), 16);
        // Lloyd's centroids are means of samples in the box; with 16 cells
        // over 2000 samples each one's region holds some of them.
        for i in 0..16 {
            let c = tree.point(i);
            assert!(
                (0.0..=1.0).contains(&c[0]) && (0.0..=2.0).contains(&c[1]),
                "{c:?}"
            );
            assert_eq!(a.cell_of(c), i, "a centroid is in its own cell");
        }
        let other = Cells::cvt(&[0.0, 0.0], &[1.0, 2.0], 16, 2000, 10, 6).unwrap();
        assert_ne!(a, other, "the seed matters");
    }

    fn elite(fitness: f64) -> Elite {
        let spec = GenomeSpec::plain(1, 1);
        let mut rng = Pcg64::seed_from_u64(0);
        let mut tracker = InnovationTracker::new(2);
        let genome = Genome::minimal(&spec, &NeatParams::plain_neat(), &mut tracker, &mut rng);
        Elite {
            genome,
            fitness,
            behaviour: vec![fitness],
            generation: 0,
        }
    }

    proptest! {
        #[test]
        fn insertion_keeps_the_first_best_per_cell(
            offers in prop::collection::vec((0usize..6, -3i32..3), 0..60),
        ) {
            let mut archive = vec![None; 6];
            // Each offer marked by its position (as its generation).
            for (k, &(cell, f)) in offers.iter().enumerate() {
                insert(&mut archive, cell, Elite { generation: k as u32, ..elite(f64::from(f)) });
            }
            for (cell, slot) in archive.iter().enumerate() {
                let here = || offers.iter().enumerate().filter(|(_, o)| o.0 == cell);
                let best = here().map(|(_, o)| o.1).max();
                let first = here().find(|(_, o)| Some(o.1) == best).map(|(k, _)| k as u32);
                let kept = slot.as_ref().map(|e| (e.fitness, e.generation));
                prop_assert_eq!(kept, best.map(f64::from).zip(first));
            }
        }
    }

    #[test]
    fn checkpoints_that_contradict_themselves_are_refused() {
        let cells = Cells::cvt(&[0.0, -1.0], &[1.0, 1.0], 5, 50, 3, 2).unwrap();
        let (params, spec) = (NeatParams::plain_neat(), GenomeSpec::plain(2, 1));
        let mut me = MapElites::new(params, spec, MapElitesParams::default(), cells, 3).unwrap();
        let n = me.ask().genomes.len();
        let told = |i: usize| Evaluation {
            behaviour: vec![i as f64 * 0.01, 0.0],
            ..Evaluation::fitness(i as f64)
        };
        me.tell(&(0..n).map(told).collect::<Vec<_>>()).unwrap();
        let reread = |edit: &dyn Fn(&mut State)| {
            let mut state = me.0.clone();
            edit(&mut state);
            serde_json::from_str::<MapElites>(&serde_json::to_string(&state).unwrap())
        };
        assert_eq!(reread(&|_| ()).unwrap(), me);
        assert!(
            reread(&|s| {
                s.archive.pop();
            })
            .is_err(),
            "fewer entries than cells"
        );
        let other_dimension = |s: &mut State| {
            let elite = s.archive.iter_mut().flatten().next().unwrap();
            elite.behaviour.push(1.0);
        };
        assert!(reread(&other_dimension).is_err());
        assert!(reread(&|s| s.batch.clear()).is_err(), "an empty batch");
        assert!(
            reread(&|s| s.archive.fill(None)).is_err(),
            "told, yet no elite"
        );
        assert!(reread(&|s| s.map.batch_size = 0).is_err());
        // A CVT's centroids are checked when read, too.
        let mut json: String = serde_json::to_string(&me).unwrap();
        let at = json.find("\"points\":[").unwrap() + "\"points\":[".len();
        json.insert_str(at, "0.5,");
        assert!(
            serde_json::from_str::<MapElites>(&json).is_err(),
            "a stray coordinate"
        );
    }
}

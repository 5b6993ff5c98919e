//! MAP-Elites (Mouret & Clune 2015, "Illuminating search spaces by mapping elites").
//!
//! The behaviour space is cut into cells, a regular grid or a centroidal
//! Voronoi tessellation (CVT, Vassiliades et al. 2018); each cell keeps the
//! fittest genome whose behaviour fell in it. Every generation, a batch of
//! children is bred from elites picked uniformly at random, by NEAT's
//! crossover (with [`MapElitesParams::crossover_probability`]) and mutation
//! over one innovation history; generation 0 is a batch of minimal genomes.

use rand::RngExt;
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};

pub use super::archive::cvt::MAX_SAMPLES;
pub use super::archive::elites::{Elite, MapElitesStats, insert};
use super::archive::elites::{archive_stats, check_archive};
pub use super::archive::grid::{Cells, MAX_CELLS};
use super::told::{self, own_batch_state, own_batch_strategy, told_batch_accessors};
use super::{Breeding, check_count, check_neat, first_batch, invalid};
use crate::driver::{Evaluation, Strategy, finite_or_zero};
use crate::error::NeatError;
use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;
use crate::population::BestEver;

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

own_batch_state!(State, Told);

own_batch_strategy! {
    /// MAP-Elites over NEAT genomes (see the module docs).
    pub struct MapElites(State);
}

impl State {
    /// Checks a restored state's settings, cells, archive and batch.
    fn check_own(&self) -> Result<(), NeatError> {
        check_params(&self.map)?;
        self.cells.check()?;
        check_archive(&self.archive, &self.cells, self.generation)?;
        if self.batch.is_empty() {
            return Err(invalid("batch", 0, "empty or not matching its fitness"));
        }
        // Telling a batch always fills a cell: breeding needs one.
        let told = self.told.is_some() || self.generation > 0;
        if told && self.archive.iter().all(Option::is_none) {
            return Err(invalid("archive", 0, "empty after a batch was told"));
        }
        Ok(())
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
        check_neat(&params, &spec)?;
        check_params(&map)?;
        cells.check()?;
        let (rng, tracker, batch) = first_batch(&spec, &params, seed, map.batch_size);
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
        archive_stats(&self.0.archive, self.0.map.qd_offset)
    }
}

impl Strategy for MapElites {
    told_batch_accessors!();

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
        let told = Told { fitness, inserted };
        told::record(&mut s.told, &mut s.best, &s.batch, s.generation, told);
        Ok(())
    }

    fn prepare(&mut self) {
        let s = &mut self.0;
        if s.told.take().is_none() {
            return;
        }
        let occupied: Vec<&Elite> = s.archive.iter().flatten().collect();
        // Elites drawn uniformly.
        let pick = |rng: &mut Pcg64| {
            let e = occupied[rng.random_range(0..occupied.len())];
            (&e.genome, e.fitness)
        };
        let next = (&mut s.batch, &mut s.generation);
        let size = (s.map.batch_size, s.map.crossover_probability);
        Breeding::new(&s.spec, &s.params, &mut s.tracker, &mut s.rng).next_batch(next, size, pick);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

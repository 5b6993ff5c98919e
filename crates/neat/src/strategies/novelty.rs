//! Novelty search (Lehman & Stanley 2011, "Abandoning objectives").
//!
//! A genome's novelty is the sparseness of its behaviour: the mean distance
//! to its k nearest neighbours among the current generation and an archive
//! of past behaviours. NEAT's speciated reproduction then selects on novelty
//! (or on a mix of novelty and fitness, [`NoveltyParams::fitness_weight`])
//! in place of fitness. A behaviour whose novelty exceeds the threshold ρ_min
//! enters the archive; ρ_min adapts as in Lehman's reference implementation:
//! lowered by 5% after 10 generations without an addition (down to a floor),
//! raised by 20% when more than 4 enter in one generation.
//!
//! The fitness the task reports is still what the driver sees
//! ([`Strategy::champion`], [`Strategy::best_ever`], target fitness), so a
//! run stops when novelty has found a solution.

use serde::{Deserialize, Serialize};

use super::knn::{KdTree, Nearest};
use super::{check_count, invalid, record_best};
use crate::driver::{Batch, Evaluation, Strategy, finite_or_zero};
use crate::error::NeatError;
use crate::genome::Genome;
use crate::population::{BestEver, GenerationStats, Population};

/// Novelty search's own settings (NEAT's are the population's).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoveltyParams {
    /// Neighbours k in the sparseness (the paper: 15).
    pub k: usize,
    /// Initial archive threshold ρ_min, in behaviour-space units.
    pub threshold: f64,
    /// ρ_min is never lowered below this.
    pub threshold_floor: f64,
    /// Generations without an archive addition before ρ_min is lowered (10).
    pub lower_after: u32,
    /// Factor lowering ρ_min (0.95).
    pub lower_factor: f64,
    /// More additions than this in one generation raise ρ_min (4).
    pub raise_above: usize,
    /// Factor raising ρ_min (1.2).
    pub raise_factor: f64,
    /// Weight w of fitness in the selection score `(1 − w)·novelty + w·fitness`,
    /// both min–max normalised over the generation; 0 is pure novelty search.
    pub fitness_weight: f64,
}

impl Default for NoveltyParams {
    /// The paper's rules, with ρ_min = 1 (set it to the scale of the behaviours).
    fn default() -> Self {
        NoveltyParams {
            k: 15,
            threshold: 1.0,
            threshold_floor: 0.05,
            lower_after: 10,
            lower_factor: 0.95,
            raise_above: 4,
            raise_factor: 1.2,
            fitness_weight: 0.0,
        }
    }
}

impl NoveltyParams {
    /// Checks every setting's range.
    pub fn validate(&self) -> Result<(), NeatError> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if self.k == 0 {
            return Err(invalid("k", self.k, "must be at least 1"));
        }
        if !positive(self.threshold) || !positive(self.threshold_floor) {
            let value = format!("{} (floor {})", self.threshold, self.threshold_floor);
            return Err(invalid("threshold", value, "must be finite and > 0"));
        }
        if !(self.lower_factor > 0.0 && self.lower_factor <= 1.0) {
            return Err(invalid(
                "lower_factor",
                self.lower_factor,
                "must be in (0, 1]",
            ));
        }
        if !(self.raise_factor >= 1.0 && self.raise_factor.is_finite()) {
            return Err(invalid(
                "raise_factor",
                self.raise_factor,
                "must be finite and ≥ 1",
            ));
        }
        if !(0.0..=1.0).contains(&self.fitness_weight) {
            return Err(invalid(
                "fitness_weight",
                self.fitness_weight,
                "must be in [0, 1]",
            ));
        }
        Ok(())
    }
}

/// What the generation just told measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Told {
    fitness: Vec<f64>,
    novelty: Vec<f64>,
    added: usize,
}

/// The serialised state of a [`NoveltySearch`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct State {
    population: Population,
    novelty: NoveltyParams,
    /// Coordinates per behaviour (0 until the first generation is told).
    dims: usize,
    /// Archived behaviours, `dims` coordinates each, end to end.
    archive: Vec<f64>,
    threshold: f64,
    /// Generations since the last archive addition.
    idle: u32,
    told: Option<Told>,
    best: Option<BestEver>,
}

/// Novelty search over a NEAT population (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "State")]
pub struct NoveltySearch(State);

impl TryFrom<State> for NoveltySearch {
    type Error = NeatError;

    fn try_from(s: State) -> Result<Self, NeatError> {
        s.novelty.validate()?;
        let n = s.population.genomes().len();
        if (s.dims == 0 && !s.archive.is_empty())
            || (s.dims > 0 && !s.archive.len().is_multiple_of(s.dims))
        {
            return Err(invalid("archive", s.archive.len(), "not whole behaviours"));
        }
        if !(s.threshold.is_finite() && s.threshold > 0.0) {
            return Err(invalid("threshold", s.threshold, "must be finite and > 0"));
        }
        if let Some(t) = &s.told
            && (t.fitness.len() != n || t.novelty.len() != n || !s.population.is_evaluated())
        {
            return Err(invalid(
                "told",
                t.fitness.len(),
                "does not match the population",
            ));
        }
        if s.best
            .as_ref()
            .is_some_and(|b| !b.fitness.is_finite() || b.generation > s.population.generation())
        {
            return Err(invalid("best", "record", "non-finite or from the future"));
        }
        Ok(NoveltySearch(s))
    }
}

impl NoveltySearch {
    /// Novelty search breeding `population` (its NEAT parameters and species).
    pub fn new(population: Population, novelty: NoveltyParams) -> Result<NoveltySearch, NeatError> {
        novelty.validate()?;
        Ok(NoveltySearch(State {
            population,
            threshold: novelty.threshold,
            novelty,
            dims: 0,
            archive: Vec::new(),
            idle: 0,
            told: None,
            best: None,
        }))
    }

    /// The NEAT population (its fitness, once told, is the selection score).
    pub fn population(&self) -> &Population {
        &self.0.population
    }

    /// The settings.
    pub fn params(&self) -> &NoveltyParams {
        &self.0.novelty
    }

    /// The archive's behaviours, in the order they entered.
    pub fn archive(&self) -> impl ExactSizeIterator<Item = &[f64]> {
        self.0.archive.chunks_exact(self.0.dims.max(1))
    }

    /// The archive threshold ρ_min in force.
    pub fn threshold(&self) -> f64 {
        self.0.threshold
    }

    /// Novelty of each genome of the batch just told (empty before `tell`).
    pub fn novelty(&self) -> &[f64] {
        self.0.told.as_ref().map_or(&[], |t| &t.novelty)
    }

    /// Behaviours archived from the batch just told.
    pub fn added(&self) -> usize {
        self.0.told.as_ref().map_or(0, |t| t.added)
    }

    /// Checks the batch's behaviours and returns them end to end (non-finite
    /// coordinates count as 0).
    fn behaviours(&mut self, evaluations: &[Evaluation]) -> Result<Vec<f64>, NeatError> {
        let dims = match self.0.dims {
            0 => evaluations.first().map_or(0, |e| e.behaviour.len()),
            dims => dims,
        };
        let mut out = Vec::with_capacity(evaluations.len() * dims);
        for e in evaluations {
            if e.behaviour.len() != dims || dims == 0 {
                let reason = "every evaluation needs a behaviour of the same dimension";
                return Err(invalid("behaviour", e.behaviour.len(), reason));
            }
            out.extend(e.behaviour.iter().map(|&x| finite_or_zero(x)));
        }
        self.0.dims = dims;
        Ok(out)
    }

    /// Novelty of each of the `behaviours` against the archive and each other.
    fn sparseness(&self, behaviours: &[f64]) -> Vec<f64> {
        let dims = self.0.dims;
        let offset = self.0.archive.len() / dims;
        let points = self.0.archive.iter().chain(behaviours).copied();
        let tree = KdTree::new(dims, points.collect());
        let mut nearest = Nearest::new(self.0.novelty.k);
        (0..behaviours.len() / dims)
            .map(|i| {
                let q = &behaviours[i * dims..(i + 1) * dims];
                tree.nearest_k(q, Some(offset + i), &mut nearest);
                nearest.mean_distance()
            })
            .collect()
    }

    /// Archives the behaviours more novel than ρ_min, then adapts ρ_min;
    /// returns how many entered.
    fn archive_novel(&mut self, behaviours: &[f64], novelty: &[f64]) -> usize {
        let dims = self.0.dims;
        let s = &mut self.0;
        let mut added = 0;
        for (b, &n) in behaviours.chunks_exact(dims).zip(novelty) {
            if n > s.threshold {
                s.archive.extend_from_slice(b);
                added += 1;
            }
        }
        let p = &s.novelty;
        if added == 0 {
            s.idle += 1;
            if s.idle >= p.lower_after {
                s.threshold = (s.threshold * p.lower_factor).max(p.threshold_floor);
                s.idle = 0;
            }
        } else {
            s.idle = 0;
        }
        if added > p.raise_above {
            s.threshold *= p.raise_factor;
        }
        added
    }
}

/// `(1 − w)·novelty + w·fitness`, each min–max normalised; pure novelty when w = 0.
fn selection_scores(novelty: &[f64], fitness: &[f64], w: f64) -> Vec<f64> {
    if w == 0.0 {
        return novelty.to_vec();
    }
    let normalised = |xs: &[f64]| -> Vec<f64> {
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let range = hi - lo;
        xs.iter()
            .map(|&x| if range > 0.0 { (x - lo) / range } else { 0.0 })
            .collect()
    };
    let (n, f) = (normalised(novelty), normalised(fitness));
    n.iter()
        .zip(&f)
        .map(|(n, f)| (1.0 - w) * n + w * f)
        .collect()
}

impl Strategy for NoveltySearch {
    fn ask(&mut self) -> Batch<'_> {
        self.prepare();
        let p = &self.0.population;
        Batch::new(p.genomes(), p.seed(), p.generation())
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        check_count(evaluations.len(), self.0.population.genomes().len())?;
        let behaviours = self.behaviours(evaluations)?;
        let fitness: Vec<f64> = evaluations.iter().map(Evaluation::finite_fitness).collect();
        let novelty = self.sparseness(&behaviours);
        let added = self.archive_novel(&behaviours, &novelty);
        let scores = selection_scores(&novelty, &fitness, self.0.novelty.fitness_weight);
        let s = &mut self.0;
        s.population.set_fitnesses(scores)?;
        let generation = s.population.generation();
        record_best(&mut s.best, s.population.genomes(), &fitness, generation);
        s.told = Some(Told {
            fitness,
            novelty,
            added,
        });
        Ok(())
    }

    fn prepare(&mut self) {
        if self.0.told.take().is_some() {
            self.0.population.next_generation();
        }
    }

    fn generation(&self) -> u32 {
        self.0.population.generation()
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        let f = &self.0.told.as_ref()?.fitness;
        let i = super::argmax(f)?;
        Some((&self.0.population.genomes()[i], f[i]))
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.0.best.as_ref()
    }

    fn stats(&self) -> GenerationStats {
        let p = &self.0.population;
        let fitness = self.0.told.as_ref().map_or(&[][..], |t| &t.fitness);
        GenerationStats {
            species: p.species().len(),
            compatibility_threshold: p.compatibility_threshold(),
            ..GenerationStats::of_batch(p.generation(), p.genomes(), fitness)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{GenomeSpec, NeatParams};

    fn search(novelty: NoveltyParams) -> NoveltySearch {
        let params = NeatParams {
            population_size: 4,
            ..NeatParams::plain_neat()
        };
        let population = Population::new(params, GenomeSpec::plain(2, 1), 3).unwrap();
        NoveltySearch::new(population, novelty).unwrap()
    }

    fn told(points: &[[f64; 2]], fitness: &[f64]) -> Vec<Evaluation> {
        points
            .iter()
            .zip(fitness)
            .map(|(b, &f)| Evaluation {
                fitness: f,
                metrics: vec![],
                behaviour: b.to_vec(),
            })
            .collect()
    }

    #[test]
    fn novelty_is_the_mean_distance_to_the_k_nearest_and_the_novel_are_archived() {
        let mut ns = search(NoveltyParams {
            k: 2,
            threshold: 2.0,
            ..NoveltyParams::default()
        });
        ns.ask();
        // A 3-4-5 triangle and a far point.
        let points = [[0.0, 0.0], [3.0, 0.0], [0.0, 4.0], [30.0, 40.0]];
        ns.tell(&told(&points, &[1.0, 2.0, 3.0, 0.5])).unwrap();
        let far = (2329f64.sqrt() + 2196f64.sqrt()) / 2.0;
        assert_eq!(ns.novelty(), [3.5, 4.0, 4.5, far]);
        assert_eq!(ns.archive().count(), 4, "all above ρ_min = 2");
        assert_eq!(
            ns.champion().map(|(_, f)| f),
            Some(3.0),
            "fitness, not novelty"
        );
        assert_eq!(ns.population().fitnesses(), ns.novelty());

        // Next generation: the archive takes part; duplicates of archived
        // points are at distance 0 from them.
        ns.ask();
        ns.tell(&told(&points, &[0.0; 4])).unwrap();
        let far = 2196f64.sqrt() / 2.0;
        assert_eq!(ns.novelty(), [1.5, 1.5, 2.0, far]);
        assert_eq!(ns.added(), 1, "only the far point is above ρ_min = 2");
        assert_eq!(ns.archive().last(), Some(&[30.0, 40.0][..]));
    }

    #[test]
    fn threshold_follows_the_papers_rules() {
        let mut ns = search(NoveltyParams {
            k: 1,
            threshold: 1.0,
            raise_above: 2,
            lower_after: 2,
            ..NoveltyParams::default()
        });
        let spread = [[0.0, 0.0], [5.0, 0.0], [10.0, 0.0], [15.0, 0.0]];
        ns.ask();
        ns.tell(&told(&spread, &[0.0; 4])).unwrap();
        assert_eq!(ns.added(), 4);
        assert_eq!(ns.threshold(), 1.2, "more than 2 added: raised by 20%");
        let same = [[0.0, 0.0]; 4];
        for expect in [1.2, 1.2 * 0.95, 1.2 * 0.95, 1.2 * 0.95 * 0.95] {
            ns.ask();
            ns.tell(&told(&same, &[0.0; 4])).unwrap();
            assert_eq!((ns.added(), ns.threshold()), (0, expect));
        }
    }

    #[test]
    fn fitness_weight_mixes_normalised_scores() {
        let scores = selection_scores(&[0.0, 2.0, 4.0], &[10.0, 30.0, 20.0], 0.25);
        assert_eq!(scores, [0.0, 0.75 * 0.5 + 0.25, 0.75 + 0.25 * 0.5]);
        assert_eq!(selection_scores(&[1.0, 2.0], &[5.0, 0.0], 0.0), [1.0, 2.0]);
    }

    #[test]
    fn behaviours_of_another_dimension_are_refused() {
        let mut ns = search(NoveltyParams::default());
        ns.ask();
        let mut evaluations = told(&[[0.0, 0.0]; 4], &[0.0; 4]);
        evaluations[2].behaviour.push(1.0);
        assert!(matches!(
            ns.tell(&evaluations),
            Err(NeatError::InvalidParam {
                field: "behaviour",
                ..
            })
        ));
    }

    /// `state` edited by `edit`, written and read back as a strategy.
    fn reread(
        state: &State,
        edit: impl Fn(&mut State),
    ) -> Result<NoveltySearch, serde_json::Error> {
        let mut state = state.clone();
        edit(&mut state);
        serde_json::from_str(&serde_json::to_string(&state).unwrap())
    }

    #[test]
    fn checkpoints_that_contradict_themselves_are_refused() {
        let mut ns = search(NoveltyParams::default());
        ns.ask();
        ns.tell(&told(&[[0.0, 1.0]; 4], &[0.0; 4])).unwrap();
        let state = &ns.0;
        assert_eq!(reread(state, |_| ()).unwrap(), ns);
        assert!(
            reread(state, |s| s.archive.push(0.5)).is_err(),
            "half a behaviour"
        );
        assert!(reread(state, |s| s.threshold = 0.0).is_err());
        assert!(reread(state, |s| s.novelty.k = 0).is_err());
        let fewer = |s: &mut State| {
            s.told.as_mut().unwrap().novelty.pop();
        };
        assert!(reread(state, fewer).is_err(), "novelty for fewer genomes");
    }
}

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

use super::archive::novelty::NoveltyArchive;
pub use super::archive::novelty::{NoveltyMetric, NoveltyParams};
use super::told::{self, ToldBatch, impl_told, told_batch_accessors};
use super::{check_count, invalid};
use crate::driver::{Evaluation, Strategy, finite_or_zero};
use crate::error::NeatError;
use crate::population::{BestEver, GenerationStats, Population};

/// What the generation just told measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Told {
    fitness: Vec<f64>,
    novelty: Vec<f64>,
    added: usize,
}

impl_told!(Told);

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
            && (t.novelty.len() != n || !s.population.is_evaluated())
        {
            return Err(invalid(
                "told",
                t.fitness.len(),
                "does not match the population",
            ));
        }
        s.told_batch().check()?;
        Ok(NoveltySearch(s))
    }
}

impl State {
    /// The population's genomes, their generation, what was told of them
    /// and the best ever.
    fn told_batch(&self) -> ToldBatch<'_, Told> {
        let p = &self.population;
        let batch = (p.seed(), p.generation(), p.genomes());
        ToldBatch::new(batch, &self.told, &self.best)
    }

    /// The archive, borrowed.
    fn archive(&mut self) -> NoveltyArchive<'_> {
        NoveltyArchive {
            dims: self.dims,
            points: &mut self.archive,
            threshold: &mut self.threshold,
            idle: &mut self.idle,
            params: &self.novelty,
        }
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
    told_batch_accessors!(without_stats);

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        check_count(evaluations.len(), self.0.population.genomes().len())?;
        let behaviours = self.behaviours(evaluations)?;
        let fitness: Vec<f64> = evaluations.iter().map(Evaluation::finite_fitness).collect();
        let s = &mut self.0;
        let novelty = s.archive().sparseness(&behaviours);
        let added = s.archive().add_novel(&behaviours, &novelty);
        let scores = selection_scores(&novelty, &fitness, s.novelty.fitness_weight);
        s.population.set_fitnesses(scores)?;
        let (generation, genomes) = (s.population.generation(), s.population.genomes());
        let told = Told {
            fitness,
            novelty,
            added,
        };
        told::record(&mut s.told, &mut s.best, genomes, generation, told);
        Ok(())
    }

    fn prepare(&mut self) {
        if self.0.told.take().is_some() {
            self.0.population.next_generation();
        }
    }

    fn stats(&self) -> GenerationStats {
        let p = &self.0.population;
        GenerationStats {
            species: p.species().len(),
            compatibility_threshold: p.compatibility_threshold(),
            ..self.0.told_batch().stats()
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

//! Novelty search's archive: past behaviours, the sparseness of new ones
//! against them (k nearest neighbours, [`super::knn`]) and the archive
//! threshold ρ_min, adapted as in Lehman's reference implementation: lowered
//! after generations without an addition (down to a floor), raised when many
//! enter at once.

use serde::{Deserialize, Serialize};

use super::knn::{KdTree, Nearest};
use crate::error::NeatError;
use crate::strategies::invalid;

/// Novelty search's own settings (NEAT's are the population's); unset keys
/// of a serialised one take their defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NoveltyParams {
    /// Nearest neighbours (population and archive) whose mean distance is a
    /// behaviour's novelty (Lehman & Stanley 2011: 15).
    pub k: usize,
    /// Initial archive threshold ρ_min: a behaviour more novel than this is archived.
    ///
    /// Unit: behaviour units.
    pub threshold: f64,
    /// ρ_min is never lowered below this.
    ///
    /// Unit: behaviour units.
    pub threshold_floor: f64,
    /// Generations without an archive addition before ρ_min is lowered (Lehman & Stanley: 10).
    pub lower_after: u32,
    /// Factor lowering ρ_min (Lehman & Stanley: 0.95).
    pub lower_factor: f64,
    /// More additions than this in one generation raise ρ_min (Lehman & Stanley: 4).
    pub raise_above: usize,
    /// Factor raising ρ_min (Lehman & Stanley: 1.2).
    pub raise_factor: f64,
    /// Weight w of fitness in the selection score (1 − w)·novelty + w·fitness
    /// (both min–max normalised per generation); 0 = pure novelty search.
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

/// Novelty search's archive, borrowed from the strategy's serialised fields.
pub(crate) struct NoveltyArchive<'a> {
    /// Coordinates per behaviour.
    pub dims: usize,
    /// Archived behaviours, `dims` coordinates each, end to end.
    pub points: &'a mut Vec<f64>,
    /// The archive threshold ρ_min in force.
    pub threshold: &'a mut f64,
    /// Generations since the last addition.
    pub idle: &'a mut u32,
    /// The settings: k and the rules adapting ρ_min.
    pub params: &'a NoveltyParams,
}

impl NoveltyArchive<'_> {
    /// Novelty of each of the `behaviours` (end to end): the mean distance
    /// to its k nearest among the archive and the other behaviours.
    pub fn sparseness(&self, behaviours: &[f64]) -> Vec<f64> {
        let dims = self.dims;
        let offset = self.points.len() / dims;
        let points = self.points.iter().chain(behaviours).copied();
        let tree = KdTree::new(dims, points.collect());
        let mut nearest = Nearest::new(self.params.k);
        (0..behaviours.len() / dims)
            .map(|i| {
                let q = &behaviours[i * dims..(i + 1) * dims];
                tree.nearest_k(q, Some(offset + i), &mut nearest);
                nearest.mean_distance()
            })
            .collect()
    }

    /// Archives the behaviours more novel than ρ_min, then adapts ρ_min by
    /// the settings' rules; returns how many entered.
    pub fn add_novel(&mut self, behaviours: &[f64], novelty: &[f64]) -> usize {
        let mut added = 0;
        for (b, &n) in behaviours.chunks_exact(self.dims).zip(novelty) {
            if n > *self.threshold {
                self.points.extend_from_slice(b);
                added += 1;
            }
        }
        let (threshold, idle, p) = (&mut *self.threshold, &mut *self.idle, self.params);
        if added == 0 {
            *idle += 1;
            if *idle >= p.lower_after {
                *threshold = (*threshold * p.lower_factor).max(p.threshold_floor);
                *idle = 0;
            }
        } else {
            *idle = 0;
        }
        if added > p.raise_above {
            *threshold *= p.raise_factor;
        }
        added
    }
}

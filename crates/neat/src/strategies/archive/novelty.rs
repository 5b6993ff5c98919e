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
    /// The distance between two behaviours: Euclidean, or the mean absolute
    /// coordinate difference of Lehman's released maze code.
    #[serde(skip_serializing_if = "NoveltyMetric::is_euclidean")]
    pub metric: NoveltyMetric,
}

/// How far apart two behaviours are, for sparseness and the archive threshold.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum NoveltyMetric {
    /// √Σ (aᵢ − bᵢ)².
    #[default]
    Euclidean,
    /// Σ |aᵢ − bᵢ| / dims: `hist_diff` in Lehman's `histogram.h`, which his
    /// maze experiment (`maze_novelty_metric`, noveltyexp.cpp) uses.
    MeanAbsolute,
}

impl NoveltyMetric {
    /// Whether this is the default, which a serialised config leaves out
    /// (so configs written before the key existed keep their checksums).
    fn is_euclidean(&self) -> bool {
        *self == NoveltyMetric::Euclidean
    }

    /// The distance between `a` and `b`.
    pub fn distance(self, a: &[f64], b: &[f64]) -> f64 {
        match self {
            NoveltyMetric::Euclidean => super::knn::squared_distance(a, b).sqrt(),
            NoveltyMetric::MeanAbsolute => {
                a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len().max(1) as f64
            }
        }
    }
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
            metric: NoveltyMetric::Euclidean,
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
        if self.params.metric != NoveltyMetric::Euclidean {
            return self.sparseness_brute_force(behaviours);
        }
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

    /// [`Self::sparseness`] under any metric, every pair visited (the k-d
    /// tree prunes by Euclidean bounds only); the k nearest distances are
    /// summed in ascending order so that equal neighbour sets give equal bits.
    fn sparseness_brute_force(&self, behaviours: &[f64]) -> Vec<f64> {
        let (dims, k, metric) = (self.dims, self.params.k, self.params.metric);
        let offset = self.points.len() / dims;
        let all: Vec<&[f64]> = self
            .points
            .chunks_exact(dims)
            .chain(behaviours.chunks_exact(dims))
            .collect();
        let mut d = Vec::with_capacity(all.len());
        (0..behaviours.len() / dims)
            .map(|i| {
                let q = all[offset + i];
                d.clear();
                d.extend(
                    (all.iter().enumerate())
                        .filter(|&(j, _)| j != offset + i)
                        .map(|(_, p)| metric.distance(q, p)),
                );
                let n = k.min(d.len());
                if n == 0 {
                    return 0.0;
                }
                if n < d.len() {
                    d.select_nth_unstable_by(n - 1, f64::total_cmp);
                }
                d[..n].sort_unstable_by(f64::total_cmp);
                d[..n].iter().sum::<f64>() / n as f64
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// `f` of a 2-d archive holding `archive`, with k and the metric as given.
    fn with_archive<R>(
        (metric, k): (NoveltyMetric, usize),
        archive: &[f64],
        f: impl FnOnce(&NoveltyArchive<'_>) -> R,
    ) -> R {
        let params = NoveltyParams {
            k,
            metric,
            ..NoveltyParams::default()
        };
        let (mut points, mut threshold, mut idle) = (archive.to_vec(), 1.0, 0);
        f(&NoveltyArchive {
            dims: 2,
            points: &mut points,
            threshold: &mut threshold,
            idle: &mut idle,
            params: &params,
        })
    }

    #[test]
    fn mean_absolute_metric_is_lehmans_hist_diff() {
        // (0, 0) and (3, 4): Euclidean 5, mean absolute (3 + 4) / 2.
        assert_eq!(
            NoveltyMetric::Euclidean.distance(&[0.0, 0.0], &[3.0, 4.0]),
            5.0
        );
        assert_eq!(
            NoveltyMetric::MeanAbsolute.distance(&[0.0, 0.0], &[3.0, 4.0]),
            3.5
        );
        // Behaviour (0, 0) against an archived (3, 4) and a behaviour (1, 0), k = 2.
        let behaviours = [0.0, 0.0, 1.0, 0.0];
        let s = with_archive((NoveltyMetric::MeanAbsolute, 2), &[3.0, 4.0], |a| {
            a.sparseness(&behaviours)
        });
        assert_eq!(s, vec![(0.5 + 3.5) / 2.0, (0.5 + 3.0) / 2.0]);
    }

    #[test]
    fn unset_metric_is_not_written() {
        let json = serde_json::to_string(&NoveltyParams::default()).unwrap();
        assert!(!json.contains("metric"), "{json}");
        let p: NoveltyParams = serde_json::from_str(r#"{"metric": "mean-absolute"}"#).unwrap();
        assert_eq!(p.metric, NoveltyMetric::MeanAbsolute);
    }

    proptest! {
        /// The brute-force path under the Euclidean metric gives the k-d tree's bits.
        #[test]
        fn brute_force_matches_the_tree(
            pts in prop::collection::vec(-50.0f64..50.0, 2..80),
            k in 1usize..20,
            split in 0usize..40,
        ) {
            let pts = &pts[..pts.len() / 2 * 2];
            let split = (split * 2).min(pts.len() - 2);
            let (archive, behaviours) = pts.split_at(split);
            let (brute, tree) = with_archive((NoveltyMetric::Euclidean, k), archive, |a| {
                (a.sparseness_brute_force(behaviours), a.sparseness(behaviours))
            });
            prop_assert_eq!(brute, tree);
        }
    }
}

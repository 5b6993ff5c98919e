//! The `[strategy]` section of a config: which search runs (NEAT, novelty
//! search, MAP-Elites or NSGA-II) and each one's settings. Every strategy
//! breeds with NEAT's operators and `[neat]` parameters, and evaluates
//! `neat.population_size` genomes per generation.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::strategies::{Measure, NoveltyParams, Objective};

/// Names of the metrics an evaluation carries when measured, in order.
pub const METRICS: [&str; 2] = ["contacts", "on_road"];

/// Which behaviour descriptor an episode reports (see [`crate::tasks::driving::descriptors`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum BehaviourKind {
    /// The robots' mean end position over the arena's size.
    #[default]
    EndPosition,
    /// Every robot's end position over the arena's size, concatenated.
    EndPositions,
    /// Mean signed side of the road and mean speed over `v_max`.
    SideSpeed,
    /// The robots' mean position over the arena's size at
    /// [`TRAJECTORY_SAMPLES`] evenly spaced times, the last at the end.
    Trajectory,
}

/// Positions a `trajectory` behaviour samples: 5, so 10 coordinates (as
/// Lehman & Stanley sampled their biped's path, a handful of points).
pub const TRAJECTORY_SAMPLES: usize = 5;

impl BehaviourKind {
    /// Coordinates of the descriptor for `robots` robots.
    pub fn dims(self, robots: usize) -> usize {
        match self {
            BehaviourKind::EndPositions => 2 * robots,
            BehaviourKind::Trajectory => 2 * TRAJECTORY_SAMPLES,
            BehaviourKind::EndPosition | BehaviourKind::SideSpeed => 2,
        }
    }

    /// The box every descriptor lies in: (lower, upper) per coordinate.
    pub fn bounds(self, robots: usize) -> (Vec<f64>, Vec<f64>) {
        let n = self.dims(robots);
        match self {
            BehaviourKind::SideSpeed => (vec![-1.0, 0.0], vec![1.0, 1.0]),
            _ => (vec![0.0; n], vec![1.0; n]),
        }
    }

    /// Column names of the descriptor's `dims` coordinates.
    pub fn coordinate_names(self, dims: usize) -> Vec<String> {
        match self {
            BehaviourKind::EndPosition => vec!["x".into(), "y".into()],
            BehaviourKind::SideSpeed => vec!["side".into(), "speed".into()],
            BehaviourKind::EndPositions => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2))
                .collect(),
            // The sample's number from 1 (the end is the last).
            BehaviourKind::Trajectory => (0..dims)
                .map(|i| format!("{}{}", ["x", "y"][i % 2], i / 2 + 1))
                .collect(),
        }
    }

    /// The name as configs write it.
    pub fn name(self) -> &'static str {
        match self {
            BehaviourKind::EndPosition => "end-position",
            BehaviourKind::EndPositions => "end-positions",
            BehaviourKind::SideSpeed => "side-speed",
            BehaviourKind::Trajectory => "trajectory",
        }
    }
}

impl std::str::FromStr for BehaviourKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        [
            BehaviourKind::EndPosition,
            BehaviourKind::EndPositions,
            BehaviourKind::SideSpeed,
            BehaviourKind::Trajectory,
        ]
        .into_iter()
        .find(|k| k.name() == s)
        .ok_or_else(|| {
            format!("'{s}': expected end-position, end-positions, side-speed or trajectory")
        })
    }
}

/// The name of the search strategy a run uses (`strategy.kind`): one of the
/// strategies registered in [`crate::search`], which checks it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(transparent)]
pub struct StrategyName(pub String);

impl StrategyName {
    /// The default strategy's name: NEAT selecting on fitness, the paper's.
    pub const NEAT: &'static str = "neat";

    /// The name as configs and the command line write it.
    pub fn name(&self) -> &str {
        &self.0
    }
}

impl Default for StrategyName {
    fn default() -> Self {
        StrategyName(Self::NEAT.into())
    }
}

impl From<&str> for StrategyName {
    fn from(name: &str) -> Self {
        StrategyName(name.into())
    }
}

impl std::fmt::Display for StrategyName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::str::FromStr for StrategyName {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Ok(StrategyName(s.to_string()))
    }
}

/// The search strategy and its settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct StrategyConfig {
    /// Search algorithm: neat, novelty, map-elites or nsga2.
    ///
    /// Paper: neat.
    pub kind: StrategyName,
    /// Behaviour descriptor for novelty and map-elites: end-position (mean
    /// end position over the arena's size), end-positions (each robot's,
    /// concatenated), side-speed (mean side of the road, mean speed over
    /// v_max) or trajectory (mean position at 5 evenly spaced times).
    pub behaviour: BehaviourKind,
    /// Novelty search (unit of the thresholds: behaviour units, e.g. arena
    /// sizes for end positions).
    pub novelty: NoveltyParams,
    /// MAP-Elites.
    pub map_elites: MapElitesConfig,
    /// NSGA-II.
    pub nsga2: Nsga2Config,
}

impl Default for StrategyConfig {
    fn default() -> Self {
        StrategyConfig {
            kind: StrategyName::default(),
            behaviour: BehaviourKind::default(),
            novelty: novelty_defaults(),
            map_elites: MapElitesConfig::default(),
            nsga2: Nsga2Config::default(),
        }
    }
}

impl StrategyConfig {
    /// Whether this is the default (NEAT, every setting at its default): a
    /// config that is written without its `[strategy]` section.
    pub fn is_default(&self) -> bool {
        *self == StrategyConfig::default()
    }
}

/// Novelty search's settings in a run: the library's, with ρ_min and its
/// floor on the scale of the descriptors of runs (arena sizes, shares), not
/// the library's default of 1.
pub fn novelty_defaults() -> NoveltyParams {
    NoveltyParams {
        threshold: 0.05,
        threshold_floor: 0.005,
        ..NoveltyParams::default()
    }
}

/// How MAP-Elites cuts the behaviour space into cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CellsKind {
    /// A regular grid of `bins` cells per dimension.
    #[default]
    Grid,
    /// A centroidal Voronoi tessellation of `cvt_cells` cells.
    Cvt,
}

/// MAP-Elites' settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MapElitesConfig {
    /// Cells: grid (regular, over the descriptor's box) or cvt (a centroidal
    /// Voronoi tessellation, for many dimensions).
    pub cells: CellsKind,
    /// Grid cells per behaviour dimension, one count per dimension or one for all.
    pub bins: Vec<usize>,
    /// CVT cells.
    pub cvt_cells: usize,
    /// Uniform samples the CVT is computed from (Lloyd's algorithm).
    pub cvt_samples: usize,
    /// Iterations of Lloyd's algorithm computing the CVT.
    pub cvt_iterations: usize,
    /// Probability that a child is the crossover of two elites rather than a mutant of one.
    pub crossover_probability: f64,
    /// Subtracted from every elite's fitness in the QD-score (Σ (fitness − offset)).
    ///
    /// Unit: fitness units.
    pub qd_offset: f64,
}

impl Default for MapElitesConfig {
    fn default() -> Self {
        MapElitesConfig {
            cells: CellsKind::Grid,
            bins: vec![10],
            cvt_cells: 100,
            cvt_samples: 10_000,
            cvt_iterations: 20,
            crossover_probability: 0.1,
            qd_offset: 0.0,
        }
    }
}

impl MapElitesConfig {
    /// Bins per dimension for a descriptor of `dims` coordinates.
    pub fn bins_for(&self, dims: usize) -> Vec<usize> {
        match self.bins.as_slice() {
            [one] => vec![*one; dims],
            many => many.to_vec(),
        }
    }
}

/// NSGA-II's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Nsga2Config {
    /// Objectives: fitness or a metric (contacts, on_road), maximised, or
    /// minimised when written with a leading minus (-contacts).
    pub objectives: Vec<String>,
    /// Probability that a child is the crossover of two tournament winners rather than a mutant.
    pub crossover_probability: f64,
}

impl Default for Nsga2Config {
    fn default() -> Self {
        Nsga2Config {
            objectives: vec!["fitness".into(), "-contacts".into()],
            crossover_probability: 0.5,
        }
    }
}

/// The objective `name` (`fitness`, `contacts`, `on_road`, optionally with a leading `-`).
pub fn objective(name: &str) -> Option<Objective> {
    objective_among(name, &METRICS)
}

/// The objective `name`: `fitness` or one of a task's `metrics`, optionally
/// with a leading `-` (minimised).
pub fn objective_among(name: &str, metrics: &[&str]) -> Option<Objective> {
    let (maximise, what) = match name.strip_prefix('-') {
        Some(rest) => (false, rest),
        None => (true, name),
    };
    let measure = match what {
        "fitness" => Measure::Fitness,
        other => Measure::Metric(metrics.iter().position(|m| *m == other)?),
    };
    Some(Objective { measure, maximise })
}

/// Checks the settings of the `[strategy]` section `s` of a config whose
/// task measures `metrics` (sizes that depend on the robots are checked when
/// the run starts; the strategy's name and what it asks of the run, by
/// [`crate::search::check`]); the error names the key.
pub fn validate(s: &StrategyConfig, metrics: &[&str]) -> Result<(), String> {
    let bad = |key: &str, value: &dyn std::fmt::Debug, why: &str| {
        Err(format!("strategy.{key} = {value:?}: {why}"))
    };
    if let Err(vivae_neat::NeatError::InvalidParam {
        field,
        value,
        reason,
    }) = s.novelty.validate()
    {
        return bad(&format!("novelty.{field}"), &value, reason);
    }
    let m = &s.map_elites;
    if m.bins.is_empty() || m.bins.contains(&0) {
        return bad(
            "map_elites.bins",
            &m.bins,
            "one count ≥ 1 per dimension, or one for all",
        );
    }
    if m.cvt_cells == 0 || m.cvt_samples < m.cvt_cells {
        return bad(
            "map_elites.cvt_cells",
            &m.cvt_cells,
            "need 1 ≤ cvt_cells ≤ cvt_samples",
        );
    }
    if !(0.0..=1.0).contains(&m.crossover_probability) {
        return bad(
            "map_elites.crossover_probability",
            &m.crossover_probability,
            "must be in [0, 1]",
        );
    }
    if !m.qd_offset.is_finite() {
        return bad("map_elites.qd_offset", &m.qd_offset, "must be finite");
    }
    let n = &s.nsga2;
    if n.objectives.is_empty() {
        return bad("nsga2.objectives", &n.objectives, "at least one objective");
    }
    if let Some(o) = (n.objectives.iter()).find(|o| objective_among(o, metrics).is_none()) {
        return Err(format!(
            "strategy.nsga2.objectives = {o:?}: expected fitness or {}, each optionally with a leading -",
            metrics.join(" or ")
        ));
    }
    if !(0.0..=1.0).contains(&n.crossover_probability) {
        return bad(
            "nsga2.crossover_probability",
            &n.crossover_probability,
            "must be in [0, 1]",
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objectives_parse_with_their_direction() {
        let o = objective("-contacts").unwrap();
        assert_eq!((o.measure, o.maximise), (Measure::Metric(0), false));
        assert_eq!(objective("fitness").unwrap().measure, Measure::Fitness);
        assert_eq!(objective("on_road").unwrap().measure, Measure::Metric(1));
        assert!(objective("speed").is_none() && objective("--fitness").is_none());
    }

    #[test]
    fn bad_settings_name_their_key() {
        let validate =
            |s: &StrategyConfig| validate(s, &METRICS).map_err(|message| Message { message });
        struct Message {
            message: String,
        }
        let mut s = StrategyConfig::default();
        s.nsga2.objectives = vec!["speed".into()];
        let e = validate(&s).unwrap_err().message;
        assert!(
            e.starts_with("strategy.nsga2.objectives = \"speed\""),
            "{e}"
        );
        let mut s = StrategyConfig::default();
        s.novelty.k = 0;
        assert!(
            validate(&s)
                .unwrap_err()
                .message
                .starts_with("strategy.novelty.k")
        );
        s = StrategyConfig::default();
        s.map_elites.bins = vec![4, 0];
        assert!(
            validate(&s)
                .unwrap_err()
                .message
                .contains("map_elites.bins")
        );
        assert!(validate(&StrategyConfig::default()).is_ok());
    }
}

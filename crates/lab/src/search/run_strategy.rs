//! What a run needs of its strategy beside ask and tell ([`RunStrategy`]),
//! and what the program shows of it: its figure and its part of the report.

use std::path::Path;

use serde::Serialize;
use vivae_neat::driver::Evaluation;
use vivae_neat::{Genome, Population};

use crate::config::Config;
use crate::error::Result;
use crate::search::{BehaviourSpace, StrategyEntry};

/// A strategy's part of a run's report: its archive or front as saved with
/// the last checkpoint (the program adds its columns of `generations.csv`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct StrategyReport {
    /// The strategy's name (its `strategy.kind`).
    pub kind: &'static str,
    /// The heading of its section of the report, when it has neither an
    /// archive nor a front (those are headed by what they hold).
    pub heading: String,
    /// What its section shows, under the heading.
    pub note: String,
    /// A map-elites archive on a 2-D grid, drawn as a heat map.
    pub grid: Option<GridReport>,
    /// Why a map-elites archive is not drawn as a heat map, if it is not.
    pub grid_note: String,
    /// Names of the behaviour coordinates.
    pub behaviour_names: Vec<String>,
    /// The archive's elites: `[cell, fitness, generation, behaviour]`.
    pub elites: Vec<(usize, f64, u32, Vec<f64>)>,
    /// An nsga2 run's objectives, as configs write them (the program names
    /// their axes).
    pub objectives: Vec<String>,
    /// Its Pareto front: `[member, fitness, objectives]`, fittest first.
    pub front: Vec<(usize, f64, Vec<f64>)>,
}

/// A 2-D grid of MAP-Elites cells (cell = x bin × `bins[1]` + y bin).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridReport {
    /// Lower bound of each coordinate.
    pub lower: [f64; 2],
    /// Upper bound of each coordinate.
    pub upper: [f64; 2],
    /// Cells along each coordinate.
    pub bins: [usize; 2],
}

/// What a run needs of its search strategy beside ask and tell.
pub trait RunStrategy {
    /// Its registration.
    fn entry(&self) -> &'static StrategyEntry;

    /// The NEAT population inside, for strategies that breed one.
    fn population(&self) -> Option<&Population> {
        None
    }

    /// The genomes of the batch to evaluate next.
    fn batch(&self) -> Vec<Genome>;

    /// The batch's task fitnesses once told, in batch order.
    fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        evaluations.iter().map(Evaluation::finite_fitness).collect()
    }

    /// Its values of [`StrategyEntry::extra_columns`] for the generation just
    /// told, each with its leading comma.
    fn extra_fields(&self) -> String {
        String::new()
    }

    /// Its `key=value` fields of the summary line, each with a leading space.
    fn summary_fields(&self) -> String {
        String::new()
    }

    /// Writes its own files into the run directory `dir` (with each
    /// checkpoint); `space` is the task's behaviour descriptors'.
    fn write_outputs(&self, _dir: &Path, _config: &Config, _space: &BehaviourSpace) -> Result<()> {
        Ok(())
    }

    /// What its end-of-run figure shows after `generation`, if it has one
    /// (the program draws it); `space` is the task's behaviour descriptors'.
    fn figure(
        &self,
        _config: &Config,
        _space: &BehaviourSpace,
        _generation: u32,
    ) -> Option<StrategyFigure> {
        None
    }
}

/// A strategy's end-of-run figure, as data: the program draws each kind.
#[derive(Debug, Clone, PartialEq)]
pub enum StrategyFigure {
    /// An archive on a 2-D grid of cells, as a heat map of its elites' fitness.
    Grid(GridFigure),
    /// A population scored on two objectives, and its Pareto front.
    Front(FrontFigure),
}

/// A 2-D grid archive to draw as a heat map.
#[derive(Debug, Clone, PartialEq)]
pub struct GridFigure {
    /// The figure's title.
    pub title: String,
    /// Names of the two behaviour coordinates (x, then y).
    pub axes: [String; 2],
    /// Lower bound of each coordinate.
    pub lower: [f64; 2],
    /// Upper bound of each coordinate.
    pub upper: [f64; 2],
    /// Cells along each coordinate.
    pub bins: [usize; 2],
    /// `(cell, fitness)` of every elite; cell = x bin × `bins[1]` + y bin.
    pub elites: Vec<(usize, f64)>,
}

/// A population scored on two objectives and its Pareto front, to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontFigure {
    /// The figure's title.
    pub title: String,
    /// The two objectives as configs write them (`fitness`, `-contacts`).
    pub objectives: [String; 2],
    /// Every scored member's two objective values.
    pub population: Vec<[f64; 2]>,
    /// The front's members' values, fittest first (as `front.csv` numbers them).
    pub front: Vec<[f64; 2]>,
}

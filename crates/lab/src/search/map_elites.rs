//! MAP-Elites (Mouret & Clune 2015): a grid or CVT archive of elites over the
//! behaviour box. It adds the archive's fill, coverage, QD score and best to
//! `generations.csv`, and writes the archive (`archive.csv`, `archive.jsonl`)
//! with each checkpoint.

use std::fmt::Write as _;
use std::path::Path;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::driver::Strategy;
use vivae_neat::strategies::{Cells, MapElites, MapElitesParams};
use vivae_neat::{Genome, NeatError};

use crate::search::StrategyConfig;
use crate::config::Config;
use crate::error::Result;
use crate::io::{bad_input, write_atomic};
use crate::search::files;
use crate::search::files::{ArchiveLine, jsonl};
use crate::search::{
    BehaviourSpace, GridFigure, GridReport, Needs, RunStrategy, Search, Start, StrategyEntry,
    StrategyFigure, StrategyReport, TaskFacts, bad_setting, behaviour_line, state_of,
};

/// MAP-Elites' registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "map-elites",
    needs: Needs {
        behaviour: true,
        metrics: false,
    },
    takes_population: false,
    variant: "MapElites",
    from_state: state_of::<MapElites>,
    extra_columns: ",filled_cells,coverage,qd_score,archive_best",
    build,
    header_line: behaviour_line,
    report,
    files: &[files::ARCHIVE, files::ARCHIVE_GENOMES],
    settings: None,
};

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

/// Checks `[strategy.map_elites]` (the bins' count against the behaviour's
/// dimensions is checked when the run starts); the error names the key.
pub(super) fn validate(m: &MapElitesConfig) -> std::result::Result<(), String> {
    let bad = |key: &str, value: &dyn std::fmt::Debug, why: &str| {
        Err(bad_setting(&format!("map_elites.{key}"), value, why))
    };
    if m.bins.is_empty() || m.bins.contains(&0) {
        return bad(
            "bins",
            &m.bins,
            "one count ≥ 1 per dimension, or one for all",
        );
    }
    if m.cvt_cells == 0 || m.cvt_samples < m.cvt_cells {
        return bad(
            "cvt_cells",
            &m.cvt_cells,
            "need 1 ≤ cvt_cells ≤ cvt_samples",
        );
    }
    if !(0.0..=1.0).contains(&m.crossover_probability) {
        return bad(
            "crossover_probability",
            &m.crossover_probability,
            "must be in [0, 1]",
        );
    }
    if !m.qd_offset.is_finite() {
        return bad("qd_offset", &m.qd_offset, "must be finite");
    }
    Ok(())
}

/// A grid of a task's cell width over its behaviour's extent: one bin count
/// per extent given (rounded up, so the cells cover it).
pub(super) fn fit_to(m: &mut MapElitesConfig, task: &TaskFacts<'_>) {
    if let Some(cell) = task.cell
        && !task.extent.is_empty()
    {
        m.bins = (task.extent.iter())
            .map(|e| (e / cell).ceil() as usize)
            .collect();
    }
}

/// The archive as saved with the last checkpoint: its elites and, on a
/// 2-D grid, the grid the report draws as a heat map.
fn report(dir: &Path, config: &Config, space: &BehaviourSpace) -> Result<Option<StrategyReport>> {
    let s = &StrategyConfig::of(config);
    let elites = crate::search::files::read_archive(dir)?.unwrap_or_default();
    let dims = space.dims();
    let bins = s.map_elites.bins_for(dims);
    let mut data = StrategyReport {
        kind: STRATEGY.kind,
        behaviour_names: space.names.clone(),
        ..StrategyReport::default()
    };
    match (s.map_elites.cells, &space.lower[..], &space.upper[..], &bins[..]) {
        (CellsKind::Grid, &[l0, l1], &[u0, u1], &[b0, b1]) => {
            data.grid = Some(GridReport {
                lower: [l0, l1],
                upper: [u0, u1],
                bins: [b0, b1],
            });
        }
        (CellsKind::Cvt, ..) => {
            data.grid_note = format!(
                "CVT cells ({} of them) are not a grid: no heat map; the elites are listed below",
                s.map_elites.cvt_cells
            );
        }
        _ => {
            data.grid_note = format!(
                "a {dims}-dimensional grid is not drawn as a heat map (only 2 dimensions are); the elites are listed below"
            );
        }
    }
    data.elites = (elites.into_iter())
        .map(|e| (e.cell, e.fitness, e.generation, e.behaviour))
        .collect();
    Ok(Some(data))
}

fn build(
    Start {
        config,
        spec,
        space,
        ..
    }: Start<'_>,
) -> Result<Search> {
    let neat = config.neat.clone();
    let m = &StrategyConfig::of(config).map_elites;
    let map = MapElitesParams {
        batch_size: neat.population_size,
        crossover_probability: m.crossover_probability,
        qd_offset: m.qd_offset,
    };
    let cells = cells(config, space)?;
    let refused = |e: NeatError| bad_input(format!("strategy.map-elites: {e}"));
    let seed = config.experiment.seed;
    Ok(Search::of(
        MapElites::new(neat, spec, map, cells, seed).map_err(refused)?,
    ))
}

/// The MAP-Elites cells of `config` over the box of the descriptors of `space`.
fn cells(config: &Config, space: &BehaviourSpace) -> Result<Cells> {
    let s = &StrategyConfig::of(config);
    let m = &s.map_elites;
    let (lower, upper) = (space.lower.clone(), space.upper.clone());
    let dims = lower.len();
    let bins = m.bins_for(dims);
    let refused = |e: NeatError| bad_input(format!("strategy.map_elites: {e}"));
    match m.cells {
        CellsKind::Grid if bins.len() != dims => Err(bad_input(format!(
            "strategy.map_elites.bins = {:?}: behaviour {} has {dims} dimensions; give one count per dimension or one for all",
            m.bins,
            s.behaviour.name()
        ))),
        CellsKind::Grid => Cells::grid(lower, upper, bins).map_err(refused),
        CellsKind::Cvt => Cells::cvt(
            &lower,
            &upper,
            m.cvt_cells,
            m.cvt_samples,
            m.cvt_iterations,
            config.experiment.seed,
        )
        .map_err(refused),
    }
}

impl RunStrategy for MapElites {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn batch(&self) -> Vec<Genome> {
        self.clone().ask().genomes.to_vec()
    }

    fn extra_fields(&self) -> String {
        let s = self.archive_stats();
        let best = s.best.map_or_else(String::new, |b| b.to_string());
        format!(",{},{},{},{best}", s.filled, s.coverage, s.qd_score)
    }

    fn summary_fields(&self) -> String {
        let s = self.archive_stats();
        format!(
            " filled_cells={} coverage={:.4} qd_score={:.3}",
            s.filled, s.coverage, s.qd_score
        )
    }

    /// On a 2-D grid: the archive as a heat map.
    fn figure(
        &self,
        config: &Config,
        space: &BehaviourSpace,
        _generation: u32,
    ) -> Option<StrategyFigure> {
        let Cells::Grid { lower, upper, bins } = self.cells() else {
            return None;
        };
        let ([l0, l1], [u0, u1], [b0, b1]) = (&lower[..], &upper[..], &bins[..]) else {
            return None;
        };
        let behaviour = StrategyConfig::of(config).behaviour;
        let [x, y] = &space.names[..] else {
            return None;
        };
        let s = self.archive_stats();
        Some(StrategyFigure::Grid(GridFigure {
            title: format!(
                "MAP-Elites archive ({}): {} of {} cells, QD-score {:.1}",
                behaviour.name(),
                s.filled,
                b0 * b1,
                s.qd_score
            ),
            axes: [x.clone(), y.clone()],
            lower: [*l0, *l1],
            upper: [*u0, *u1],
            bins: [*b0, *b1],
            elites: self.elites().map(|(c, e)| (c, e.fitness)).collect(),
        }))
    }

    /// The archive: `archive.csv` (cells, behaviour, fitness, generation)
    /// and `archive.jsonl` (with genomes).
    fn write_outputs(&self, dir: &Path, _config: &Config, space: &BehaviourSpace) -> Result<()> {
        let lines: Vec<ArchiveLine> = (self.elites())
            .map(|(cell, e)| ArchiveLine {
                cell,
                fitness: e.fitness,
                generation: e.generation + 1,
                behaviour: e.behaviour.clone(),
                genome: e.genome.clone(),
            })
            .collect();
        let mut csv = format!("cell,{},fitness,generation\n", space.names.join(","));
        for l in &lines {
            let b: Vec<String> = l.behaviour.iter().map(f64::to_string).collect();
            let _ = writeln!(
                csv,
                "{},{},{},{}",
                l.cell,
                b.join(","),
                l.fitness,
                l.generation
            );
        }
        write_atomic(&dir.join(files::ARCHIVE), csv.as_bytes())?;
        write_atomic(&dir.join(files::ARCHIVE_GENOMES), jsonl(&lines)?.as_bytes())
    }
}

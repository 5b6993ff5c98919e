//! The run-directory files of the strategies beyond NEAT: their fields of
//! `generations.csv` and of the summary line, MAP-Elites' archive lines
//! (`archive.jsonl`) and NSGA-II's Pareto front lines (`front.jsonl`), as
//! each strategy's file writes them with each checkpoint, and read back to
//! replay one member.
//!
//! A NEAT run has none of them: its files are as they always were.

use std::path::Path;

use serde::{Deserialize, Serialize};
use vivae_neat::Genome;

use crate::config::Config;
use crate::error::{Error, Result};
use crate::search::{BehaviourSpace, Search};

/// MAP-Elites runs: every elite's cell, behaviour, fitness and generation.
pub const ARCHIVE: &str = "archive.csv";
/// MAP-Elites runs: every elite with its genome, one JSON line each.
pub const ARCHIVE_GENOMES: &str = "archive.jsonl";
/// NSGA-II runs: the Pareto front's objectives and fitness.
pub const FRONT: &str = "front.csv";
/// NSGA-II runs: the Pareto front with its genomes, one JSON line each.
pub const FRONT_GENOMES: &str = "front.jsonl";

/// The values of the strategy's extra columns of `generations.csv` for the
/// generation just told, with their leading commas.
pub fn extra_fields(search: &Search) -> String {
    search.strategy().extra_fields()
}

/// `key=value` fields of the summary line for the strategy's state, each
/// with a leading space: `strategy=…`, then the strategy's own (its archive's
/// or front's size).
pub fn summary_fields(search: &Search) -> String {
    let s = search.strategy();
    format!(" strategy={}{}", s.entry().kind, s.summary_fields())
}

/// One elite of a MAP-Elites archive, as a line of `archive.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArchiveLine {
    /// The cell's index.
    pub cell: usize,
    /// The elite's fitness.
    pub fitness: f64,
    /// Generation (1-based, of this run) in which it was evaluated.
    pub generation: u32,
    /// Its behaviour descriptor.
    pub behaviour: Vec<f64>,
    /// Its CPPN genome.
    pub genome: Genome,
}

/// One member of an NSGA-II Pareto front, as a line of `front.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrontLine {
    /// Its index in the front (fittest first).
    pub member: usize,
    /// Its fitness.
    pub fitness: f64,
    /// Its value of each objective, as measured (in `strategy.nsga2.objectives` order).
    pub objectives: Vec<f64>,
    /// Its CPPN genome.
    pub genome: Genome,
}

/// Writes the strategy's own files of `search` into the run directory `dir`
/// (`space`: the task's behaviour descriptors').
pub fn write_outputs(
    dir: &Path,
    config: &Config,
    space: &BehaviourSpace,
    search: &Search,
) -> Result<()> {
    search.strategy().write_outputs(dir, config, space)
}

/// `lines` as JSON lines.
pub(crate) fn jsonl<T: Serialize>(lines: &[T]) -> Result<String> {
    let mut out = String::new();
    for l in lines {
        let text = serde_json::to_string(l).map_err(|e| Error::Serialize {
            what: "an archive line",
            reason: e.to_string(),
        })?;
        out.push_str(&text);
        out.push('\n');
    }
    Ok(out)
}

/// Every elite of the MAP-Elites archive of the run in `dir`
/// (`archive.jsonl`, cell order), genomes checked; `None` when the run has
/// no archive (not a map-elites run, or before its first checkpoint).
pub fn read_archive(dir: &Path) -> Result<Option<Vec<ArchiveLine>>> {
    read_lines(&dir.join(ARCHIVE_GENOMES), |l: &ArchiveLine| &l.genome)
}

/// Every member of the NSGA-II Pareto front of the run in `dir`
/// (`front.jsonl`, fittest first), genomes checked; `None` when the run
/// has no front.
pub fn read_front(dir: &Path) -> Result<Option<Vec<FrontLine>>> {
    read_lines(&dir.join(FRONT_GENOMES), |l: &FrontLine| &l.genome)
}

/// The JSON lines of `path`, each genome (`genome_of`) checked; `None` if there is no such file.
fn read_lines<T: serde::de::DeserializeOwned>(
    path: &Path,
    genome_of: impl Fn(&T) -> &Genome,
) -> Result<Option<Vec<T>>> {
    let text = match crate::io::read_regular_text(path, crate::rundir::MAX_RUN_FILE_BYTES) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(Error::io("read", path)(e)),
    };
    let bad = |line: usize, why: String| Error::RunFile {
        path: path.to_path_buf(),
        reason: format!("line {}: {why}", line + 1),
    };
    let mut lines = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l: T = serde_json::from_str(line).map_err(|e| bad(i, e.to_string()))?;
        genome_of(&l).check().map_err(|e| bad(i, e.to_string()))?;
        lines.push(l);
    }
    Ok(Some(lines))
}

/// A member of a run's archive or front to replay.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Member {
    /// The elite of this cell of a MAP-Elites archive.
    Elite(usize),
    /// This member of an NSGA-II Pareto front (0 = the fittest).
    Front(usize),
}

/// The genome, fitness and (1-based) generation of `member` of the run in `dir`.
pub fn read_member(dir: &Path, member: Member) -> Result<(Genome, f64, u32)> {
    let (name, wanted) = match member {
        Member::Elite(c) => (ARCHIVE_GENOMES, c),
        Member::Front(m) => (FRONT_GENOMES, m),
    };
    let path = dir.join(name);
    let text = crate::io::read_regular_text(&path, crate::rundir::MAX_RUN_FILE_BYTES).map_err(
        |e| match e.kind() {
            std::io::ErrorKind::NotFound => crate::io::bad_input(format!(
                "{}: no such file (only a run whose strategy keeps {} has one)",
                path.display(),
                match member {
                    Member::Elite(_) => "an archive",
                    Member::Front(_) => "a Pareto front",
                }
            )),
            _ => Error::io("read", &path)(e),
        },
    )?;
    let bad = |line: usize, why: String| Error::RunFile {
        path: path.clone(),
        reason: format!("line {}: {why}", line + 1),
    };
    let mut known = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let (key, genome, fitness, generation) = match member {
            Member::Elite(_) => {
                let l: ArchiveLine =
                    serde_json::from_str(line).map_err(|e| bad(i, e.to_string()))?;
                (l.cell, l.genome, l.fitness, l.generation)
            }
            Member::Front(_) => {
                let l: FrontLine = serde_json::from_str(line).map_err(|e| bad(i, e.to_string()))?;
                (l.member, l.genome, l.fitness, 0)
            }
        };
        if key == wanted {
            genome.check().map_err(|e| bad(i, e.to_string()))?;
            return Ok((genome, fitness, generation));
        }
        known.push(key);
    }
    let listed = match known.len() {
        0 => "it is empty".to_string(),
        n if n <= 12 => format!("it has {known:?}"),
        n => format!("it has {n}, from {} to {}", known[0], known[n - 1]),
    };
    Err(crate::io::bad_input(format!(
        "{}: no {} {wanted} ({listed})",
        path.display(),
        match member {
            Member::Elite(_) => "elite in cell",
            Member::Front(_) => "front member",
        }
    )))
}

//! The run directory: its file names and formats, and every read and write
//! of them. A run directory holds `config.toml`, `scenario.svg` (or
//! `scenarios/` for a multi-map run), `generations.csv`, `population.csv`,
//! `timing.csv`, `best-genomes.jsonl`, `champion.json`, `checkpoints/` and,
//! at the end, `figures/` and `report.html` (then `figures/drawn-generations.txt`,
//! the record that they are complete). CSV files are appended once per
//! generation; a checkpoint records their lengths, so resuming truncates
//! whatever a crash left after the last checkpoint and the finished files
//! are byte-identical to an uninterrupted run's. Other modules and the
//! program ask this one; none of them names a file of a run itself.

use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use vivae_neat::{Genome, Population};

use crate::search::Search;

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{
    bad_input, fnv1a, load_scenario, read_config, read_text, safe_file_stem, write_atomic,
};
use crate::maps::{TrainingMap, is_multi_map};

/// File names inside a run directory.
pub mod files {
    /// The fully resolved configuration.
    pub const CONFIG: &str = "config.toml";
    /// The scenario the run uses.
    pub const SCENARIO: &str = "scenario.svg";
    /// Per-generation statistics.
    pub const GENERATIONS: &str = "generations.csv";
    /// Every individual's fitness per generation (Fig. 8).
    pub const POPULATION: &str = "population.csv";
    /// Wall-clock time per generation.
    pub const TIMING: &str = "timing.csv";
    /// The best genome ever.
    pub const CHAMPION: &str = "champion.json";
    /// Checkpoint folder.
    pub const CHECKPOINTS: &str = "checkpoints";
    /// Figure folder.
    pub const FIGURES: &str = "figures";
    /// A copy of the population a run starts from (retrain).
    pub const INIT_POPULATION: &str = "init-population.json";
    /// Each generation's best genome and species sizes, one JSON line per generation.
    pub const BEST_GENOMES: &str = "best-genomes.jsonl";
    /// The self-contained HTML report of the run.
    pub const REPORT: &str = "report.html";
    /// MAP-Elites runs: every elite's cell, behaviour, fitness and generation.
    pub const ARCHIVE: &str = "archive.csv";
    /// MAP-Elites runs: every elite with its genome, one JSON line each.
    pub const ARCHIVE_GENOMES: &str = "archive.jsonl";
    /// NSGA-II runs: the Pareto front's objectives and fitness.
    pub const FRONT: &str = "front.csv";
    /// NSGA-II runs: the Pareto front with its genomes, one JSON line each.
    pub const FRONT_GENOMES: &str = "front.jsonl";
    /// In `figures/`: how many generations the figures and `report.html`
    /// show, written last once they are all drawn ([`super::mark_drawn`]).
    pub const DRAWN: &str = "drawn-generations.txt";
}

pub(crate) const GENERATIONS_HEADER: &str = "generation,best,mean,median,worst,species,mean_cppn_nodes,mean_cppn_links,best_substrate_links,possible_substrate_links\n";

/// The header of `generations.csv` for a run of strategy `kind`: NEAT's
/// columns, then the strategy's own.
pub(crate) fn generations_header(config: &Config) -> String {
    let base = GENERATIONS_HEADER.trim_end_matches('\n');
    let task = match config.experiment.task {
        crate::config::TaskKind::Driving => "",
        crate::config::TaskKind::Maze => crate::maze_run::COLUMNS,
    };
    format!("{base}{}{task}\n", config.strategy.kind.extra_columns())
}

pub(crate) const POPULATION_HEADER: &str = "generation,rank,fitness\n";

pub(crate) const TIMING_HEADER: &str = "generation,seconds,robot_steps_per_second\n";

/// The best genome ever: what `champion.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Champion {
    /// Format marker, always `vivae-champion`.
    pub format: String,
    /// Generation (1-based, of this run) in which it was evaluated.
    pub generation: u32,
    /// Its fitness (average speed, px/step).
    pub fitness: f64,
    /// The run's resolved config (substrate, sensors, physics, steps, robots),
    /// so that the file alone rebuilds the controller; `None` in files written
    /// before it was recorded. Its scenario is relative to the file's folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub config: Option<Config>,
    /// The CPPN genome.
    pub genome: Genome,
}

impl Champion {
    /// The config a champion file records: the run's, without the settings
    /// (threads, checkpoints) that change how a run is executed but not its results.
    pub fn recorded_config(config: &Config) -> Config {
        Config {
            run: crate::config::RunConfig::default(),
            ..config.clone()
        }
    }
}

/// Reads a genome source for `replay`: a run directory (its champion and
/// `config.toml`) or a champion JSON file (the config it records; the default
/// config for files that record none). Returns the folder outputs go beside.
pub fn load_genome_source(source: &Path) -> Result<(Champion, Config, PathBuf)> {
    if source.is_dir() {
        let champion = read_champion(&source.join(files::CHAMPION))?;
        let config = read_config(&source.join(files::CONFIG))?;
        Ok((champion, config, source.to_path_buf()))
    } else {
        let champion = read_champion(source)?;
        let base = source.parent().map(Path::to_path_buf).unwrap_or_default();
        let config = match &champion.config {
            Some(recorded) => {
                let mut config = recorded.clone();
                // As in a config file, a relative scenario is relative to the file's folder.
                let scenario = &mut config.experiment.scenario;
                if !scenario.is_empty() && Path::new(scenario.as_str()).is_relative() {
                    *scenario = base.join(&*scenario).to_string_lossy().into_owned();
                }
                for map in &mut config.experiment.scenarios {
                    *map = crate::io::resolve_map(&base, map);
                }
                config.experiment.init_population.clear();
                config
            }
            None => Config::default(),
        };
        Ok((champion, config, base))
    }
}

/// Reads `champion.json` (or any file in its format); the genome is checked as it is read.
pub fn read_champion(path: &Path) -> Result<Champion> {
    let text = read_text(path)?;
    let invalid = |reason: String| Error::Genome {
        path: path.to_path_buf(),
        reason,
    };
    let champion: Champion = serde_json::from_str(&text)
        .map_err(|e| invalid(format!("not a vivae champion genome: {e}")))?;
    if champion.format != "vivae-champion" {
        return Err(invalid(format!(
            "format is {:?}, expected \"vivae-champion\"",
            champion.format
        )));
    }
    if let Some(config) = &champion.config {
        config
            .validate()
            .map_err(|e| invalid(format!("its recorded config: {e}")))?;
    }
    // The genome validated itself while being deserialised.
    Ok(champion)
}

/// One generation's record (a row of `generations.csv`).
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationRecord {
    /// Generation, 1-based.
    pub generation: u32,
    /// Generations the run will have in all.
    pub total: u32,
    /// Best fitness.
    pub best: f64,
    /// Mean fitness.
    pub mean: f64,
    /// Median fitness.
    pub median: f64,
    /// Worst fitness.
    pub worst: f64,
    /// Species.
    pub species: usize,
    /// Mean CPPN nodes.
    pub mean_nodes: f64,
    /// Mean enabled CPPN links.
    pub mean_links: f64,
    /// Links the generation's best CPPN expresses in the substrate.
    pub best_links: usize,
    /// Links the substrate could have.
    pub possible_links: usize,
    /// Wall time of the generation.
    pub seconds: f64,
    /// Simulated robot-steps per second of wall time.
    pub robot_steps_per_second: f64,
    /// Best fitness of the run so far.
    pub best_ever: f64,
}

impl GenerationRecord {
    /// The record's row of `generations.csv`.
    pub fn generations_row(&self) -> String {
        let r = self;
        GenerationRow {
            generation: r.generation,
            best: r.best,
            mean: r.mean,
            median: r.median,
            worst: r.worst,
            species: r.species,
            mean_cppn_nodes: r.mean_nodes,
            mean_cppn_links: r.mean_links,
            best_substrate_links: r.best_links,
            possible_substrate_links: r.possible_links,
        }
        .to_csv()
    }

    /// The record's row of `timing.csv`.
    pub fn timing_row(&self) -> String {
        format!(
            "{},{:.6},{:.0}\n",
            self.generation, self.seconds, self.robot_steps_per_second
        )
    }
}

/// The rows of `population.csv` for a generation's fitnesses `sorted` best first.
pub fn population_rows(generation: u32, sorted: &[f64]) -> String {
    let mut rows = String::with_capacity(sorted.len() * 24);
    for (rank, f) in sorted.iter().enumerate() {
        let _ = writeln!(rows, "{generation},{},{f}", rank + 1);
    }
    rows
}

/// One line of `best-genomes.jsonl`: a generation's best genome and its species.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GenerationBest {
    /// Generation, 1-based.
    pub generation: u32,
    /// The best genome's fitness.
    pub fitness: f64,
    /// `[species id, members]` of every species, in the population's order.
    pub species: Vec<(u32, usize)>,
    /// The generation's best CPPN genome.
    pub genome: Genome,
}

/// A line as stored: a genome equal to the previous line's (the usual case,
/// by elitism) is stored as a reference to that line's generation.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BestLine {
    pub(crate) generation: u32,
    pub(crate) fitness: f64,
    pub(crate) species: Vec<(u32, usize)>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) genome: Option<Genome>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) same_as: Option<u32>,
}

/// Largest run file read whole (`best-genomes.jsonl`, `population.csv`),
/// in bytes: these grow with the run, past [`crate::io::MAX_INPUT_BYTES`].
pub const MAX_RUN_FILE_BYTES: u64 = 1 << 30;

/// Reads a run file that grows with the run: a regular file only (a FIFO
/// put in its place is refused at once, not waited on), of bounded size.
fn read_run_file(path: &Path) -> std::io::Result<String> {
    crate::io::read_regular_text(path, MAX_RUN_FILE_BYTES)
}

/// Reads `best-genomes.jsonl`; a missing file is an empty history (older runs).
pub fn read_best_genomes(path: &Path) -> Result<Vec<GenerationBest>> {
    let text = match read_run_file(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => {
            return Err(bad_input(format!(
                "{}: {}",
                path.display(),
                crate::io::io_reason(&e)
            )));
        }
    };
    parse_best_genomes(&text, path, MAX_RUN_FILE_BYTES)
}

/// The lines of `best-genomes.jsonl` (read from `path`), their genomes
/// taking at most `budget` bytes in memory.
fn parse_best_genomes(text: &str, path: &Path, budget: u64) -> Result<Vec<GenerationBest>> {
    // A last line without its newline is still being written by a running evolution.
    let complete = text.rfind('\n').map_or("", |end| &text[..end]);
    let mut out: Vec<GenerationBest> = Vec::new();
    // The last line of each generation, so that `same_as` is not a search
    // of every line before it (quadratic: 600 000 lines took minutes).
    let mut line_of: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    // Bytes of the genomes read so far: `same_as` copies a genome, so a
    // small file could otherwise ask for gigabytes.
    let mut genome_bytes = 0u64;
    for (i, line) in complete.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |why: String| bad_input(format!("{}: line {}: {why}", path.display(), i + 1));
        let stored: BestLine = serde_json::from_str(line).map_err(|e| bad(e.to_string()))?;
        let genome = match (stored.genome, stored.same_as) {
            (Some(g), None) => {
                g.check().map_err(|e| bad(e.to_string()))?;
                g
            }
            (None, Some(k)) => line_of
                .get(&k)
                .map(|&j| out[j].genome.clone())
                .ok_or_else(|| bad(format!("same_as {k}: no such earlier generation")))?,
            _ => return Err(bad("needs exactly one of genome and same_as".into())),
        };
        genome_bytes += genome_size(&genome);
        if genome_bytes > budget {
            return Err(bad(format!(
                "its genomes would take more than {} MiB in memory (same_as repeats too large a genome too often)",
                budget >> 20
            )));
        }
        line_of.insert(stored.generation, out.len());
        out.push(GenerationBest {
            generation: stored.generation,
            fitness: stored.fitness,
            species: stored.species,
            genome,
        });
    }
    Ok(out)
}

/// Bytes `genome`'s genes take in memory.
fn genome_size(genome: &Genome) -> u64 {
    let nodes = std::mem::size_of_val(genome.nodes());
    let links = std::mem::size_of_val(genome.links());
    (nodes + links) as u64
}

/// Keeps the first `lines` lines of a file (creating it empty if missing).
pub(crate) fn truncate_lines(path: &Path, lines: u32) -> Result<()> {
    let text = match read_run_file(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(e) => {
            return Err(bad_input(format!(
                "{}: {}",
                path.display(),
                crate::io::io_reason(&e)
            )));
        }
    };
    let keep: usize = text
        .split_inclusive('\n')
        .take(lines as usize)
        .filter(|l| l.ends_with('\n'))
        .map(str::len)
        .sum();
    if keep != text.len() || !path.exists() {
        write_atomic(path, &text.as_bytes()[..keep])?;
    }
    Ok(())
}

/// State saved in a checkpoint besides the population.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Progress {
    /// Generations of this run evaluated so far.
    pub(crate) done: u32,
    /// `population.generation()` when this run started.
    pub(crate) start_generation: u32,
    /// Byte lengths of the CSV files after generation `done`.
    pub(crate) generations_len: u64,
    pub(crate) population_len: u64,
    pub(crate) timing_len: u64,
    /// Best individual of each figure generation (generation, fitness, genome).
    pub(crate) figure_genomes: Vec<(u32, f64, Genome)>,
    /// FNV-1a hash of `scenario.svg`: a replaced scenario is refused on resume.
    /// Absent in checkpoints written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) scenario_fnv: Option<u64>,
    /// FNV-1a hash of each training map's copy under `scenarios/` (multi-map
    /// runs only): an edited copy is refused on resume.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) maps_fnv: Option<Vec<u64>>,
    /// A maze run's evaluations and when it was solved (maze runs only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) maze: Option<crate::maze_run::MazeProgress>,
}

/// Refuses a run whose `config.toml` was edited since its newest checkpoint:
/// a run continues with the config it started with (its checkpoint's), so an
/// edit would otherwise be silently undone. Only `run.threads` (speed, not
/// results) and `experiment.generations` (set by `resume --generations`, which
/// rewrites `config.toml` before the next checkpoint records it) may differ;
/// a missing `config.toml` is rewritten.
pub(crate) fn check_config_unchanged(
    dir: &Path,
    checkpoint: &Path,
    recorded: &Config,
) -> Result<()> {
    let path = dir.join(files::CONFIG);
    let Ok(text) = crate::io::read_text(&path) else {
        return Ok(());
    };
    let expected = recorded.to_toml();
    if text == expected {
        return Ok(());
    }
    if let Ok(mut on_disk) = Config::from_toml(&text) {
        on_disk.run.threads = recorded.run.threads;
        on_disk.experiment.generations = recorded.experiment.generations;
        if on_disk == *recorded {
            return Ok(());
        }
    }
    let (line, differs) = text
        .lines()
        .zip(expected.lines().chain(std::iter::repeat("")))
        .enumerate()
        .find(|(_, (a, b))| a != b)
        .map(|(i, (a, _))| (i + 1, a.trim().to_string()))
        .unwrap_or((text.lines().count() + 1, "(end of file)".to_string()));
    Err(Error::Checkpoint {
        path,
        reason: format!(
            "differs from the run's newest checkpoint {} (line {line}: `{differs}`); a run resumes with the config it started with: undo the edit (extend a run with `resume --generations N`), or start a new run with `evolve --config`",
            checkpoint.display()
        ),
    })
}

/// A checkpoint: everything needed to continue the run exactly.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Checkpoint {
    pub(crate) config: Config,
    pub(crate) progress: Progress,
    /// A NEAT run's population ready to evaluate generation `done + 1`
    /// (stored exactly as before other strategies existed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) population: Option<Population>,
    /// Any other strategy's state, ready to evaluate generation `done + 1`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) search: Option<Search>,
}

impl Checkpoint {
    /// The checkpoint of `search` (a NEAT population goes to `population`).
    pub(crate) fn new(config: &Config, progress: &Progress, search: &Search) -> Checkpoint {
        let (population, search) = match search {
            Search::Neat(p) => (Some(p.clone()), None),
            other => (None, Some(other.clone())),
        };
        Checkpoint {
            config: config.clone(),
            progress: progress.clone(),
            population,
            search,
        }
    }

    /// The stored search, or why there is none.
    pub(crate) fn search(&self) -> std::result::Result<Search, &'static str> {
        match (&self.population, &self.search) {
            (Some(p), None) => Ok(Search::Neat(p.clone())),
            (None, Some(Search::Neat(_))) => Err("a NEAT population stored as `search`"),
            (None, Some(s)) => Ok(s.clone()),
            (None, None) => Err("neither a population nor a search strategy"),
            (Some(_), Some(_)) => Err("both a population and a search strategy"),
        }
    }

    /// The NEAT population inside (a NEAT or novelty run's), for `retrain`.
    fn into_population(self, path: &Path) -> Result<(Config, Population)> {
        let population = match self.search() {
            Ok(Search::Neat(p)) => Some(p),
            Ok(Search::Novelty(n)) => Some(n.population().clone()),
            _ => None,
        };
        population
            .map(|p| (self.config, p))
            .ok_or_else(|| Error::Checkpoint {
                path: path.to_path_buf(),
                reason: "holds no NEAT population (a map-elites or nsga2 run)".into(),
            })
    }
}

pub(crate) const CHECKPOINT_MAGIC: &str = "vivae-checkpoint v1";

pub(crate) fn encode_checkpoint(cp: &Checkpoint) -> Result<String> {
    let body = serde_json::to_string(cp).map_err(|e| Error::Serialize {
        what: "checkpoint",
        reason: e.to_string(),
    })?;
    Ok(format!(
        "{CHECKPOINT_MAGIC} {:016x}\n{body}",
        fnv1a(body.as_bytes())
    ))
}

pub(crate) fn decode_checkpoint(path: &Path) -> Result<Checkpoint> {
    decode_checkpoint_text(&crate::io::read_text(path)?, path)
}

/// Decodes checkpoint `text`; errors name `path`.
pub(crate) fn decode_checkpoint_text(text: &str, path: &Path) -> Result<Checkpoint> {
    let bad = |why: &str| Error::Checkpoint {
        path: path.to_path_buf(),
        reason: why.to_string(),
    };
    let (header, body) = text
        .split_once('\n')
        .ok_or_else(|| bad("not a vivae checkpoint (no header line)"))?;
    let checksum = header
        .strip_prefix(CHECKPOINT_MAGIC)
        .map(str::trim)
        .ok_or_else(|| bad("not a vivae checkpoint (bad header)"))?;
    let expected = u64::from_str_radix(checksum, 16)
        .map_err(|_| bad("not a vivae checkpoint (bad checksum field)"))?;
    if fnv1a(body.as_bytes()) != expected {
        return Err(bad("corrupt or truncated checkpoint (checksum mismatch)"));
    }
    let cp: Checkpoint =
        serde_json::from_str(body).map_err(|e| bad(&format!("unreadable checkpoint: {e}")))?;
    // The population validated itself while being deserialised.
    cp.config
        .validate()
        .map_err(|e| bad(&format!("checkpoint config: {e}")))?;
    Ok(cp)
}

/// Reads the population stored in a checkpoint file (for `retrain` and `init_population`).
pub fn population_from_checkpoint(path: &Path) -> Result<(Config, Population)> {
    decode_checkpoint(path)?.into_population(path)
}

/// Reads the config and population of checkpoint `text` (read from `path`,
/// which errors name); the entry point of the checkpoint fuzz target.
pub fn population_from_checkpoint_text(text: &str, path: &Path) -> Result<(Config, Population)> {
    decode_checkpoint_text(text, path)?.into_population(path)
}

/// Path of the newest checkpoint in a run directory.
pub fn latest_checkpoint(run_dir: &Path) -> Result<PathBuf> {
    let dir = run_dir.join(files::CHECKPOINTS);
    let entries = fs::read_dir(&dir).map_err(|e| Error::Checkpoint {
        path: run_dir.to_path_buf(),
        reason: format!(
            "not a vivae run directory ({}: {})",
            files::CHECKPOINTS,
            crate::io::io_reason(&e)
        ),
    })?;
    checkpoint_names(entries)
        .pop()
        .map(|n| dir.join(n))
        .ok_or_else(|| Error::Checkpoint {
            path: dir.clone(),
            reason: "no checkpoint to resume from".into(),
        })
}

pub(crate) fn write_checkpoint(
    dir: &Path,
    config: &Config,
    progress: &Progress,
    search: &Search,
) -> Result<()> {
    let cp = Checkpoint::new(config, progress, search);
    let dir = dir.join(files::CHECKPOINTS);
    let path = dir.join(format!("gen-{:06}.ckpt", progress.done));
    write_atomic(&path, encode_checkpoint(&cp)?.as_bytes())?;
    prune_checkpoints(&dir, config.run.checkpoint_keep)
}

impl Progress {
    pub(crate) fn start(start_generation: u32) -> Progress {
        Progress {
            done: 0,
            start_generation,
            generations_len: GENERATIONS_HEADER.len() as u64,
            population_len: POPULATION_HEADER.len() as u64,
            timing_len: TIMING_HEADER.len() as u64,
            figure_genomes: Vec::new(),
            scenario_fnv: None,
            maps_fnv: None,
            maze: None,
        }
    }
}

/// Appends `text` and returns the file's new length.
pub(crate) fn append(path: &Path, text: &str) -> Result<u64> {
    let mut f = fs::OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(Error::io("open", path))?;
    f.write_all(text.as_bytes())
        .map_err(Error::io("write", path))?;
    Ok(f.metadata().map_err(Error::io("read", path))?.len())
}

pub(crate) fn truncate(path: &Path, len: u64) -> Result<()> {
    let damaged = |reason: String| Error::Checkpoint {
        path: path.to_path_buf(),
        reason,
    };
    // Checked first: opening a FIFO for writing blocks until a reader appears.
    crate::io::open_regular(path).map_err(|e| damaged(crate::io::io_reason(&e)))?;
    let f = fs::OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(|e| damaged(crate::io::io_reason(&e)))?;
    let actual = f.metadata().map_err(Error::io("read", path))?.len();
    if actual < len {
        return Err(damaged(format!(
            "shorter ({actual} bytes) than its checkpoint says ({len} bytes)"
        )));
    }
    f.set_len(len).map_err(Error::io("truncate", path))
}

/// Checkpoint file names in a listing, oldest first (names sort by generation).
pub(crate) fn checkpoint_names(entries: fs::ReadDir) -> Vec<String> {
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("gen-") && n.ends_with(".ckpt"))
        .collect();
    names.sort();
    names
}

pub(crate) fn prune_checkpoints(dir: &Path, keep: usize) -> Result<()> {
    let names = checkpoint_names(fs::read_dir(dir).map_err(Error::io("list", dir))?);
    let excess = names.len().saturating_sub(keep);
    for n in &names[..excess] {
        let path = dir.join(n);
        fs::remove_file(&path).map_err(Error::io("prune", path))?;
    }
    Ok(())
}

/// Reads `population.csv` back: per generation, the fitnesses best first.
/// Refused (bad input naming the file, and the line): no header line, a
/// malformed row, generations out of order (1, 1, …, 2, 2, …), a fitness
/// that is not a finite number, no row at all.
pub fn read_population_csv(path: &Path) -> Result<Vec<Vec<f64>>> {
    // Not `read_text`: a long run's population.csv may pass its size limit.
    let text = read_run_file(path).map_err(Error::io("read", path))?;
    let refused = |reason: String| Error::RunFile {
        path: path.to_path_buf(),
        reason,
    };
    let malformed =
        |line: usize, what: &dyn std::fmt::Display| refused(format!("line {}: {what}", line + 1));
    let mut lines = text.lines().enumerate();
    if !lines
        .next()
        .is_some_and(|(_, h)| h.starts_with("generation,"))
    {
        return Err(refused(
            "not a vivae run file (no `generation,rank,fitness` header line)".into(),
        ));
    }
    let mut out: Vec<Vec<f64>> = Vec::new();
    for (i, line) in lines {
        let mut parts = line.split(',');
        let (Some(g), Some(_), Some(f)) = (parts.next(), parts.next(), parts.next()) else {
            return Err(malformed(i, &"expected generation,rank,fitness"));
        };
        let g: usize = g.parse().map_err(|e| malformed(i, &e))?;
        let f: f64 = f.parse().map_err(|e| malformed(i, &e))?;
        // In order, as written: the generation under way or the next one.
        // (A row may not skip ahead: generation 10⁹ would allocate 24 GB.)
        let (same, next) = (g != 0 && g == out.len(), g == out.len() + 1);
        if !(same || next) {
            let want = if out.is_empty() {
                "1".to_string()
            } else {
                format!("{} or {}", out.len(), out.len() + 1)
            };
            return Err(malformed(
                i,
                &format!("generation {g} where {want} was expected"),
            ));
        }
        if !f.is_finite() {
            return Err(malformed(i, &format!("fitness {f} is not a finite number")));
        }
        if next {
            out.push(Vec::new());
        }
        out[g - 1].push(f);
    }
    if out.is_empty() {
        return Err(refused("no generation recorded".into()));
    }
    Ok(out)
}

/// One row of `generations.csv`, as written and as read back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenerationRow {
    /// Generation, 1-based.
    pub generation: u32,
    /// Best fitness.
    pub best: f64,
    /// Mean fitness.
    pub mean: f64,
    /// Median fitness.
    pub median: f64,
    /// Worst fitness.
    pub worst: f64,
    /// Species.
    pub species: usize,
    /// Mean CPPN nodes.
    pub mean_cppn_nodes: f64,
    /// Mean enabled CPPN links.
    pub mean_cppn_links: f64,
    /// Links the generation's best CPPN expresses in the substrate.
    pub best_substrate_links: usize,
    /// Links the substrate could have.
    pub possible_substrate_links: usize,
}

impl GenerationRow {
    /// The row as a line of `generations.csv`.
    pub fn to_csv(&self) -> String {
        let r = self;
        format!(
            "{},{},{},{},{},{},{},{},{},{}\n",
            r.generation,
            r.best,
            r.mean,
            r.median,
            r.worst,
            r.species,
            r.mean_cppn_nodes,
            r.mean_cppn_links,
            r.best_substrate_links,
            r.possible_substrate_links
        )
    }

    /// The row of fields `f` (the header's order); `None` when one is missing or not a number.
    fn parse(f: &[&str]) -> Option<GenerationRow> {
        let x = |k: usize| f.get(k).and_then(|s| s.parse::<f64>().ok());
        let n = |k: usize| f.get(k).and_then(|s| s.parse::<usize>().ok());
        Some(GenerationRow {
            generation: f.first()?.parse().ok()?,
            best: x(1)?,
            mean: x(2)?,
            median: x(3)?,
            worst: x(4)?,
            species: n(5)?,
            mean_cppn_nodes: x(6)?,
            mean_cppn_links: x(7)?,
            best_substrate_links: n(8)?,
            possible_substrate_links: n(9)?,
        })
    }
}

/// One row of `timing.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimingRow {
    /// Generation, 1-based.
    pub generation: u32,
    /// Wall time of the generation.
    pub seconds: f64,
    /// Simulated robot-steps per second of wall time.
    pub robot_steps_per_second: f64,
}

impl TimingRow {
    /// The row of fields `f`; `None` when one is missing or not a number.
    fn parse(f: &[&str]) -> Option<TimingRow> {
        Some(TimingRow {
            generation: f.first()?.parse().ok()?,
            seconds: f.get(1)?.parse().ok()?,
            robot_steps_per_second: f.get(2)?.parse().ok()?,
        })
    }
}

/// Reads `generations.csv`: complete lines only (a running evolution may be
/// writing the last one), generations numbered 1, 2, … in order, every
/// number finite.
pub fn read_generations(path: &Path) -> Result<Vec<GenerationRow>> {
    read_rows(path, GenerationRow::parse, |r| {
        (
            r.generation,
            [r.best, r.mean, r.median, r.worst]
                .into_iter()
                .all(f64::is_finite),
        )
    })
}

/// The most wall-clock seconds `timing.csv` may add up to: 1e9 s, about 32
/// years. A larger sum is no real run's, and would blow up the axes drawn
/// from it (`vivae compare` would hang).
pub const MAX_RUN_SECONDS: f64 = 1e9;

/// Reads `timing.csv`, as [`read_generations`] does; seconds may not be
/// negative, and their sum up to each line not above [`MAX_RUN_SECONDS`].
pub fn read_timing(path: &Path) -> Result<Vec<TimingRow>> {
    let total = std::cell::Cell::new(0.0);
    read_rows(path, TimingRow::parse, |r| {
        total.set(total.get() + r.seconds);
        let valid = r.seconds.is_finite() && r.seconds >= 0.0 && total.get() <= MAX_RUN_SECONDS;
        (r.generation, valid)
    })
}

/// The rows of a run's CSV file at `path`, each parsed by `parse` and
/// checked by `check` (its generation, and whether its numbers are valid).
fn read_rows<T>(
    path: &Path,
    parse: impl Fn(&[&str]) -> Option<T>,
    check: impl Fn(&T) -> (u32, bool),
) -> Result<Vec<T>> {
    let text = read_text(path)?;
    let bad = |line: usize, reason: String| Error::Checkpoint {
        path: path.to_path_buf(),
        reason: format!("line {line}: {reason}"),
    };
    let complete = text.rfind('\n').map_or("", |end| &text[..=end]);
    let mut lines = complete.lines();
    if !lines.next().is_some_and(|h| h.starts_with("generation,")) {
        return Err(Error::Checkpoint {
            path: path.to_path_buf(),
            reason: "not a vivae run file (no `generation,...` header line)".into(),
        });
    }
    let mut out = Vec::new();
    for (i, line) in lines.enumerate() {
        let number = i + 2;
        let fields: Vec<&str> = line.split(',').collect();
        let row = parse(&fields).ok_or_else(|| bad(number, format!("malformed row {line:?}")))?;
        let (generation, valid) = check(&row);
        if generation as usize != out.len() + 1 {
            let want = out.len() + 1;
            return Err(bad(
                number,
                format!("generation {generation} where {want} was expected"),
            ));
        }
        if !valid {
            return Err(bad(number, format!("a number out of range in {line:?}")));
        }
        out.push(row);
    }
    Ok(out)
}

/// Forgets that `dir`'s figures and report are drawn: called before they are
/// redrawn, so that a crash while drawing leaves them marked as stale.
pub fn unmark_drawn(dir: &Path) -> Result<()> {
    let path = dir.join(files::FIGURES).join(files::DRAWN);
    match fs::remove_file(&path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::Io {
            action: "remove",
            path,
            error: e,
        }),
        _ => Ok(()),
    }
}

/// Records (atomically, after everything else) that `dir`'s figures and
/// `report.html` show its first `generations` generations.
pub fn mark_drawn(dir: &Path, generations: u32) -> Result<()> {
    let path = dir.join(files::FIGURES).join(files::DRAWN);
    write_atomic(&path, format!("{generations}\n").as_bytes())
}

/// How many generations `dir`'s figures and report show, if their drawing
/// finished; `None` when it did not (or predates the record): redraw them.
pub fn drawn_generations(dir: &Path) -> Option<u32> {
    let text = read_text(&dir.join(files::FIGURES).join(files::DRAWN)).ok()?;
    text.strip_suffix('\n')?.parse().ok()
}

/// Removes temporary files a killed process left behind (`.NAME.tmp-PID`).
pub(crate) fn remove_stale_temporaries(dir: &Path) {
    for d in [
        dir.to_path_buf(),
        dir.join(files::CHECKPOINTS),
        dir.join(files::FIGURES),
    ] {
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            let name = name.to_string_lossy();
            if name.starts_with('.') && name.contains(".tmp-") {
                let _ = fs::remove_file(e.path());
            }
        }
    }
}

/// An exclusive advisory lock (flock) on a run directory, released when
/// dropped or when the process exits in any way.
pub(crate) struct RunLock(#[allow(dead_code)] fs::File);

impl RunLock {
    /// Locks `dir`, or refuses (bad input) when another process holds it.
    pub(crate) fn acquire(dir: &Path) -> Result<RunLock> {
        use std::os::fd::AsRawFd;
        let file = fs::File::open(dir).map_err(Error::io("open", dir))?;
        // SAFETY: flock on a valid descriptor owned by `file`; no memory is touched.
        let rc = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
        if rc != 0 {
            let e = std::io::Error::last_os_error();
            if e.kind() == std::io::ErrorKind::WouldBlock {
                return Err(bad_input(format!(
                    "{}: another vivae process is writing this run directory",
                    dir.display()
                )));
            }
            return Err(Error::io("lock", dir)(e));
        }
        Ok(RunLock(file))
    }
}

/// Removes hidden `.NAME.tmp-PID` folders that runs killed before their first
/// checkpoint left in `parent`: those whose process is gone and whose lock is
/// free (both, so neither a live run's fresh folder nor a reused PID is hit).
pub(crate) fn remove_abandoned_builds(parent: &Path, name: &str) {
    let prefix = format!(".{name}.tmp-");
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|p| p.parse::<i32>().ok())
        else {
            continue;
        };
        // SAFETY: kill with signal 0 sends nothing; it only asks whether `pid` exists.
        let gone = pid > 0
            && unsafe { libc::kill(pid, 0) } != 0
            && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH);
        let path = entry.path();
        if gone
            && path.is_dir()
            && !path.is_symlink()
            && let Ok(lock) = RunLock::acquire(&path)
        {
            let _ = fs::remove_dir_all(&path);
            drop(lock);
        }
    }
}

/// Writes a new run's files and its first checkpoint into `dir`.
pub(crate) fn fill_new_run(
    dir: &Path,
    config: &mut Config,
    scenario_text: &str,
    search: &Search,
    progress: &Progress,
) -> Result<()> {
    let checkpoints = dir.join(files::CHECKPOINTS);
    fs::create_dir_all(&checkpoints).map_err(Error::io("create", checkpoints))?;
    write_atomic(&dir.join(files::SCENARIO), scenario_text.as_bytes())?;
    if !config.experiment.init_population.is_empty() {
        // Keep the starting population beside the config that names it.
        let init_cp = Checkpoint::new(config, progress, search);
        write_atomic(
            &dir.join(files::INIT_POPULATION),
            encode_checkpoint(&init_cp)?.as_bytes(),
        )?;
        config.experiment.init_population = files::INIT_POPULATION.into();
    }
    if !crate::maps::is_multi_map(config) {
        config.experiment.scenario = files::SCENARIO.into();
    }
    write_atomic(&dir.join(files::CONFIG), config.to_toml().as_bytes())?;
    let generations = generations_header(config);
    for (name, header) in [
        (files::GENERATIONS, generations.as_str()),
        (files::POPULATION, POPULATION_HEADER),
        (files::TIMING, TIMING_HEADER),
        (files::BEST_GENOMES, ""),
    ] {
        write_atomic(&dir.join(name), header.as_bytes())?;
    }
    write_checkpoint(dir, config, progress, search)
}

/// Copies the training maps of a multi-map run into `dir/scenarios/` with
/// their manifest, and points `experiment.scenarios` at the copies.
pub(crate) fn copy_maps(dir: &Path, config: &mut Config, maps: &[TrainingMap]) -> Result<()> {
    if maps.is_empty() {
        return Ok(());
    }
    let folder = dir.join(MAPS_DIR);
    fs::create_dir_all(&folder).map_err(Error::io("create", &folder))?;
    let names = copy_names(maps);
    for (name, m) in names.iter().zip(maps) {
        write_atomic(&folder.join(name), m.loaded.text.as_bytes())?;
    }
    write_atomic(&folder.join(MANIFEST), manifest(&names, maps).as_bytes())?;
    config.experiment.scenarios = names.iter().map(|n| format!("{}/{n}", MAPS_DIR)).collect();
    Ok(())
}

/// Checks that the CSV files, cut at the lengths the checkpoint records, end
/// exactly after its last generation: a checkpoint of another run, or one
/// with forged lengths, would otherwise cut a row in half.
pub(crate) fn check_csv_prefixes(dir: &Path, checkpoint: &Path, p: &Progress) -> Result<()> {
    for (name, len, count_rows) in [
        (files::GENERATIONS, p.generations_len, true),
        // One row per individual: only its end is read.
        (files::POPULATION, p.population_len, false),
        (files::TIMING, p.timing_len, true),
    ] {
        let path = dir.join(name);
        let mismatch = || Error::Checkpoint {
            path: checkpoint.to_path_buf(),
            reason: format!(
                "does not belong to this run: {name} does not end after generation {} at byte {len}",
                p.done
            ),
        };
        let Some((prefix, from_start)) = csv_prefix(&path, len, !count_rows)? else {
            // Shorter than recorded: `truncate` reports it with both lengths.
            continue;
        };
        if !prefix.ends_with(b"\n") {
            return Err(mismatch());
        }
        let body = &prefix[..prefix.len() - 1];
        let last = body.rsplit(|&b| b == b'\n').next().unwrap_or(b"");
        let last_generation = std::str::from_utf8(last)
            .ok()
            .and_then(|l| l.split(',').next())
            .and_then(|g| g.parse::<u32>().ok());
        let fits = match p.done {
            // Only the header: no row starts with a generation number.
            0 => last_generation.is_none() && (!from_start || !body.contains(&b'\n')),
            d => last_generation == Some(d),
        };
        let rows_fit =
            !count_rows || prefix.iter().filter(|&&b| b == b'\n').count() == p.done as usize + 1;
        if !fits || !rows_fit {
            return Err(mismatch());
        }
    }
    Ok(())
}

/// The first `len` bytes of `path` (only their last 64 KiB when `tail_only`),
/// and whether they start at the file's start; `None` when the file is shorter.
pub(crate) fn csv_prefix(
    path: &Path,
    len: u64,
    tail_only: bool,
) -> Result<Option<(Vec<u8>, bool)>> {
    use std::io::{Read, Seek, SeekFrom};
    let unreadable = |e: std::io::Error| Error::Checkpoint {
        path: path.to_path_buf(),
        reason: crate::io::io_reason(&e),
    };
    // Not a plain open: a FIFO in the file's place would block it forever.
    let (mut f, meta) = crate::io::open_regular(path).map_err(unreadable)?;
    let actual = meta.len();
    if actual < len || len > crate::io::MAX_INPUT_BYTES && !tail_only {
        return Ok(None);
    }
    let start = if tail_only {
        len.saturating_sub(64 << 10)
    } else {
        0
    };
    f.seek(SeekFrom::Start(start)).map_err(unreadable)?;
    let mut bytes = Vec::with_capacity((len - start) as usize);
    f.take(len - start)
        .read_to_end(&mut bytes)
        .map_err(unreadable)?;
    Ok(Some((bytes, start == 0)))
}

/// Folder of a multi-map run directory holding the copies of the training maps.
pub const MAPS_DIR: &str = "scenarios";
/// The manifest in [`MAPS_DIR`]: one line per map, `file fnv1a64 source`.
pub const MANIFEST: &str = "manifest.txt";

/// File names the copies of `maps` get in `scenarios/`: `LABEL.svg`, with
/// `-2`, `-3`, … after a label already taken.
pub fn copy_names(maps: &[TrainingMap]) -> Vec<String> {
    let mut names: Vec<String> = Vec::with_capacity(maps.len());
    for m in maps {
        let safe = safe_file_stem(&m.label);
        let mut name = format!("{safe}.svg");
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{safe}-{k}.svg");
            k += 1;
        }
        names.push(name);
    }
    names
}

/// The manifest's text for copies `names` of `maps`.
pub fn manifest(names: &[String], maps: &[TrainingMap]) -> String {
    let mut out = String::from("# file fnv1a64 source (the training maps, in evaluation order)\n");
    for (name, m) in names.iter().zip(maps) {
        let _ = writeln!(
            out,
            "{name} {:016x} {}",
            fnv1a(m.loaded.text.as_bytes()),
            m.loaded.scenario.source
        );
    }
    out
}

/// Loads the training maps of the run in `dir` (its config `config`): the
/// copies under `scenarios/` for a multi-map run, else `scenario.svg`.
/// With `hashes` (from the checkpoint), a copy whose text changed is refused.
pub fn load_run(dir: &Path, config: &Config, hashes: Option<&[u64]>) -> Result<Vec<TrainingMap>> {
    if !is_multi_map(config) {
        let path = dir.join(files::SCENARIO);
        return Ok(vec![TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        }]);
    }
    let names = &config.experiment.scenarios;
    if let Some(h) = hashes
        && h.len() != names.len()
    {
        return Err(Error::Checkpoint {
            path: dir.to_path_buf(),
            reason: format!(
                "the checkpoint records {} training maps, config.toml names {}",
                h.len(),
                names.len()
            ),
        });
    }
    let mut maps = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        // A run's maps are its own copies, `scenarios/FILE`. The config may
        // name them as written (relative to the run) or as `read_config`
        // resolved them (relative to the working directory, or absolute):
        // the file name finds the copy either way, and nothing outside it.
        let file = Path::new(name).file_name().unwrap_or_default();
        let path = dir.join(MAPS_DIR).join(file);
        let text = crate::io::read_text(&path)?;
        if let Some(h) = hashes
            && h[i] != fnv1a(text.as_bytes())
        {
            return Err(Error::Checkpoint {
                path,
                reason: format!(
                    "training map {} was edited since the run started (its hash is not the one the checkpoint records); restore it, or start a new run",
                    i + 1
                ),
            });
        }
        maps.push(TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        });
    }
    Ok(maps)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` written as a file of a fresh folder, read by `read`.
    fn read_back<T>(name: &str, text: &str, read: impl Fn(&Path) -> Result<T>) -> Result<T> {
        let dir = std::env::temp_dir().join(format!("vivae-rundir-{name}-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        fs::write(&path, text).unwrap();
        let out = read(&path);
        fs::remove_dir_all(&dir).unwrap();
        out
    }

    #[test]
    fn population_rows_out_of_order_are_refused_without_allocating_for_them() {
        // Found while writing the `rundir_reader` fuzz target (and confirmed
        // with it): this 40-byte file made `report` allocate 24 GB, one
        // empty generation per number skipped.
        let e = read_back(
            files::POPULATION,
            "generation,rank,fitness\n999999999,1,1\n",
            read_population_csv,
        )
        .unwrap_err();
        let message = e.to_string();
        assert!(e.is_bad_input(), "{e:?}");
        assert!(
            message.contains("line 2: generation 999999999 where 1 was expected"),
            "{message}"
        );
        for (text, line) in [
            ("1,1,0.5\n3,1,0.5\n", 3),
            ("1,1,0.5\n2,1,0.5\n1,2,0.1\n", 4),
            ("18446744073709551615,1,1\n", 2),
        ] {
            let e = read_back(
                files::POPULATION,
                &format!("generation,rank,fitness\n{text}"),
                read_population_csv,
            )
            .unwrap_err();
            assert!(
                e.to_string().contains(&format!("line {line}: generation")),
                "{e}"
            );
        }
        let ok = read_back(
            files::POPULATION,
            "generation,rank,fitness\n1,1,0.5\n1,2,0.25\n2,1,0.75\n",
            read_population_csv,
        )
        .unwrap();
        assert_eq!(ok, [vec![0.5, 0.25], vec![0.75]]);
    }

    #[test]
    fn best_genome_references_are_looked_up_not_searched_and_bounded_in_memory() {
        let genome: Genome = serde_json::from_str(
            r#"{"nodes":[{"id":0,"kind":"input","activation":"linear"},{"id":1,"kind":"output","activation":"linear"}],"links":[{"innovation":0,"from":0,"to":1,"weight":0.5,"enabled":true}]}"#,
        )
        .unwrap();
        let first =
            serde_json::json!({"generation": 1, "fitness": 1.0, "species": [], "genome": genome});
        let line =
            |k: u32| format!("{{\"generation\":{k},\"fitness\":1,\"species\":[],\"same_as\":1}}\n");
        // 200 000 lines that all name the first: read at once (it used to
        // search every earlier line for each, 2·10¹⁰ steps).
        let mut text = format!("{first}\n");
        for k in 2..=200_000 {
            text.push_str(&line(k));
        }
        let best = read_back(files::BEST_GENOMES, &text, read_best_genomes).unwrap();
        assert_eq!(best.len(), 200_000);
        assert_eq!(best[199_999].genome, genome);
        // Past the memory bound (here 1 MiB), refused, naming the line.
        let path = Path::new(files::BEST_GENOMES);
        let fits = (1u64 << 20) / genome_size(&genome);
        let e = parse_best_genomes(&text, path, 1 << 20).unwrap_err();
        assert!(e.is_bad_input(), "{e:?}");
        assert!(
            e.to_string().contains(&format!(
                "line {}: its genomes would take more than 1 MiB",
                fits + 1
            )),
            "{e}"
        );
    }
}

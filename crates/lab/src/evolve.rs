//! The evolution driver: run directories, per-generation records, checkpoints.
//!
//! A run directory holds `config.toml`, `scenario.svg`, `generations.csv`,
//! `population.csv`, `timing.csv`, `champion.json`, `checkpoints/` and, at the
//! end, `figures/`. CSV files are appended once per generation; a checkpoint
//! records their lengths, so resuming truncates whatever a crash left after
//! the last checkpoint and the finished files are byte-identical to an
//! uninterrupted run's. Wall-clock times live only in `timing.csv`, the one
//! file that is allowed to differ between two runs of the same config.

use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use serde::{Deserialize, Serialize};
use vivae_neat::driver::{
    CheckpointState, Checkpointer, DriverError, Evaluator, Evolution, GenerationReport, HookError,
    Observer, ParallelEvaluator, StopCriteria, StopReason,
};
use vivae_neat::{Genome, Population, stats};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::io::{bad_input, fnv1a, read_config, read_text, write_atomic};
use crate::training::Training;

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
}

const GENERATIONS_HEADER: &str = "generation,best,mean,median,worst,species,mean_cppn_nodes,mean_cppn_links,best_substrate_links,possible_substrate_links\n";
const POPULATION_HEADER: &str = "generation,rank,fitness\n";
const TIMING_HEADER: &str = "generation,seconds,robot_steps_per_second\n";

/// Generations whose best individual gets a trajectory figure (besides the champion).
pub const FIGURE_GENERATIONS: [u32; 2] = [1, 10];

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
struct BestLine {
    generation: u32,
    fitness: f64,
    species: Vec<(u32, usize)>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    genome: Option<Genome>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    same_as: Option<u32>,
}

/// Reads `best-genomes.jsonl`; a missing file is an empty history (older runs).
pub fn read_best_genomes(path: &Path) -> Result<Vec<GenerationBest>> {
    let text = match fs::read_to_string(path) {
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
    // A last line without its newline is still being written by a running evolution.
    let complete = text.rfind('\n').map_or("", |end| &text[..end]);
    let mut out: Vec<GenerationBest> = Vec::new();
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
            (None, Some(k)) => out
                .iter()
                .rev()
                .find(|b| b.generation == k)
                .map(|b| b.genome.clone())
                .ok_or_else(|| bad(format!("same_as {k}: no such earlier generation")))?,
            _ => return Err(bad("needs exactly one of genome and same_as".into())),
        };
        out.push(GenerationBest {
            generation: stored.generation,
            fitness: stored.fitness,
            species: stored.species,
            genome,
        });
    }
    Ok(out)
}

/// Keeps the first `lines` lines of a file (creating it empty if missing).
fn truncate_lines(path: &Path, lines: u32) -> Result<()> {
    let text = match fs::read_to_string(path) {
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
struct Progress {
    /// Generations of this run evaluated so far.
    done: u32,
    /// `population.generation()` when this run started.
    start_generation: u32,
    /// Byte lengths of the CSV files after generation `done`.
    generations_len: u64,
    population_len: u64,
    timing_len: u64,
    /// Best individual of each figure generation (generation, fitness, genome).
    figure_genomes: Vec<(u32, f64, Genome)>,
    /// FNV-1a hash of `scenario.svg`: a replaced scenario is refused on resume.
    /// Absent in checkpoints written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scenario_fnv: Option<u64>,
    /// FNV-1a hash of each training map's copy under `scenarios/` (multi-map
    /// runs only): an edited copy is refused on resume.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    maps_fnv: Option<Vec<u64>>,
}

/// Refuses a run whose `config.toml` was edited since its newest checkpoint:
/// a run continues with the config it started with (its checkpoint's), so an
/// edit would otherwise be silently undone. Only `run.threads` (speed, not
/// results) and `experiment.generations` (set by `resume --generations`, which
/// rewrites `config.toml` before the next checkpoint records it) may differ;
/// a missing `config.toml` is rewritten.
fn check_config_unchanged(dir: &Path, checkpoint: &Path, recorded: &Config) -> Result<()> {
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
struct Checkpoint {
    config: Config,
    progress: Progress,
    /// The population ready to evaluate generation `done + 1`.
    population: Population,
}

const CHECKPOINT_MAGIC: &str = "vivae-checkpoint v1";

fn encode_checkpoint(cp: &Checkpoint) -> Result<String> {
    let body = serde_json::to_string(cp).map_err(|e| Error::Serialize {
        what: "checkpoint",
        reason: e.to_string(),
    })?;
    Ok(format!(
        "{CHECKPOINT_MAGIC} {:016x}\n{body}",
        fnv1a(body.as_bytes())
    ))
}

fn decode_checkpoint(path: &Path) -> Result<Checkpoint> {
    decode_checkpoint_text(&crate::io::read_text(path)?, path)
}

/// Decodes checkpoint `text`; errors name `path`.
fn decode_checkpoint_text(text: &str, path: &Path) -> Result<Checkpoint> {
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
    let cp = decode_checkpoint(path)?;
    Ok((cp.config, cp.population))
}

/// Reads the config and population of checkpoint `text` (read from `path`,
/// which errors name); the entry point of the checkpoint fuzz target.
pub fn population_from_checkpoint_text(text: &str, path: &Path) -> Result<(Config, Population)> {
    let cp = decode_checkpoint_text(text, path)?;
    Ok((cp.config, cp.population))
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

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// All generations done.
    Finished,
    /// Stopped by the user after a generation; a checkpoint was written.
    Interrupted,
}

/// A run in a run directory.
pub struct Run {
    dir: PathBuf,
    /// Held while the run exists: one writer per run directory.
    _lock: RunLock,
    config: Config,
    training: Training,
    population: Population,
    progress: Progress,
    pool: Arc<rayon::ThreadPool>,
}

impl Run {
    /// Creates a new run directory and the initial checkpoint.
    ///
    /// `scenario_text` is copied to `scenario.svg`; `config.experiment.scenario`
    /// is rewritten to point at that copy so `config.toml` alone re-runs it.
    /// `init` is a population to start from (retrain) instead of a fresh one.
    pub fn create(
        dir: &Path,
        config: Config,
        training: Training,
        scenario_text: &str,
        init: Option<Population>,
        force: bool,
    ) -> Result<Run> {
        Run::create_on_maps(dir, config, training, scenario_text, &[], init, force)
    }

    /// [`Run::create`] for a run on several training maps (`maps`, from
    /// [`crate::maps::load`]; empty for a single-scenario run): `scenario_text`
    /// (the first map's) goes to `scenario.svg` as ever, and every map is
    /// copied to `scenarios/` with a manifest of their hashes;
    /// `experiment.scenarios` is rewritten to name the copies.
    pub fn create_on_maps(
        dir: &Path,
        mut config: Config,
        training: Training,
        scenario_text: &str,
        maps: &[crate::maps::TrainingMap],
        init: Option<Population>,
        force: bool,
    ) -> Result<Run> {
        let maps = if crate::maps::is_multi_map(&config) {
            maps
        } else {
            &[]
        };
        let population = match init {
            // Only the genomes carry over: fitness, species and the champion were
            // measured on another substrate and mean nothing here.
            Some(p) => Population::from_genomes(
                config.neat.clone(),
                training.primary().cppn_spec(),
                p.genomes().to_vec(),
                config.experiment.seed,
            )
            .map_err(|e| bad_input(format!("initial population: {e}")))?,
            None => Population::new(
                config.neat.clone(),
                training.primary().cppn_spec(),
                config.experiment.seed,
            )
            .map_err(|e| bad_input(format!("neat: {e}")))?,
        };
        // The run is built in a temporary sibling and renamed into place once its
        // first checkpoint exists: a kill or an error before that leaves no
        // directory that could neither be resumed nor re-run without --force.
        let old_lock = check_out_dir(dir, force)?;
        let parent = match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        crate::io::create_dirs_for(&parent, dir)?;
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "run".into());
        remove_abandoned_builds(&parent, &name);
        let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        if tmp.exists() {
            fs::remove_dir_all(&tmp).map_err(Error::io("clear", &tmp))?;
        }
        fs::create_dir(&tmp).map_err(Error::io("create", dir))?;
        // The lock is on the directory itself, so it survives the rename.
        let lock = match RunLock::acquire(&tmp) {
            Ok(l) => l,
            Err(e) => {
                let _ = fs::remove_dir_all(&tmp);
                return Err(e);
            }
        };
        let progress = Progress {
            scenario_fnv: Some(fnv1a(scenario_text.as_bytes())),
            maps_fnv: (!maps.is_empty()).then(|| {
                maps.iter()
                    .map(|m| fnv1a(m.loaded.text.as_bytes()))
                    .collect()
            }),
            ..Progress::start(population.generation())
        };
        let filled = copy_maps(&tmp, &mut config, maps)
            .and_then(|()| fill_new_run(&tmp, &mut config, scenario_text, &population, &progress));
        let placed = filled.and_then(|()| {
            if old_lock.is_some() {
                fs::remove_dir_all(dir).map_err(Error::io("clear", dir))?;
            }
            fs::rename(&tmp, dir).map_err(Error::io("create", dir))
        });
        if let Err(e) = placed {
            let _ = fs::remove_dir_all(&tmp);
            return Err(e);
        }
        drop(old_lock);
        Ok(Run {
            dir: dir.to_path_buf(),
            _lock: lock,
            pool: thread_pool(config.run.threads)?,
            config,
            training,
            population,
            progress,
        })
    }

    /// Opens an existing run at its newest checkpoint; `generations` extends (or
    /// shortens, if not yet reached) the total. Files written after that
    /// checkpoint are truncated back to it.
    pub fn resume(dir: &Path, generations: Option<u32>, threads: Option<usize>) -> Result<Run> {
        let path = latest_checkpoint(dir)?;
        // Locked before anything is read: another writer may be mid-generation.
        let lock = RunLock::acquire(dir)?;
        let mut cp = decode_checkpoint(&path)?;
        check_config_unchanged(dir, &path, &cp.config)?;
        if let Some(n) = generations {
            if n < cp.progress.done {
                return Err(bad_input(format!(
                    "--generations {n}: the run already has {} generations",
                    cp.progress.done
                )));
            }
            cp.config.experiment.generations = n;
        }
        let maps = crate::maps::load_run(dir, &cp.config, cp.progress.maps_fnv.as_deref())?;
        let scenario = crate::io::load_scenario(Some(&dir.join(files::SCENARIO)))?;
        let training = Training::new(&cp.config, &maps)?;
        // Everything is validated before anything in the directory changes.
        validate_progress(&path, &cp, training.primary())?;
        if let Some(h) = cp.progress.scenario_fnv
            && h != fnv1a(scenario.text.as_bytes())
        {
            return Err(Error::Checkpoint {
                path: dir.join(files::SCENARIO),
                reason: format!(
                    "changed since the run started (it does not match {})",
                    path.display()
                ),
            });
        }
        check_csv_prefixes(dir, &path, &cp.progress)?;
        remove_stale_temporaries(dir);
        for (name, len) in [
            (files::GENERATIONS, cp.progress.generations_len),
            (files::POPULATION, cp.progress.population_len),
            (files::TIMING, cp.progress.timing_len),
        ] {
            truncate(&dir.join(name), len)?;
        }
        truncate_lines(&dir.join(files::BEST_GENOMES), cp.progress.done)?;
        // The resolved config records the (possibly extended) total.
        write_atomic(&dir.join(files::CONFIG), cp.config.to_toml().as_bytes())?;
        Ok(Run {
            dir: dir.to_path_buf(),
            _lock: lock,
            // A thread count given at resume changes speed, not results: not recorded.
            pool: thread_pool(threads.unwrap_or(cp.config.run.threads))?,
            config: cp.config,
            training,
            population: cp.population,
            progress: cp.progress,
        })
    }

    /// The run directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The resolved configuration.
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// The experiment reported, drawn and replayed (the first map at the run's own resolution).
    pub fn experiment(&self) -> &Experiment {
        self.training.primary()
    }

    /// What genomes are evaluated on: every training map and resolution.
    pub fn training(&self) -> &Training {
        &self.training
    }

    /// Generations done so far.
    pub fn done(&self) -> u32 {
        self.progress.done
    }

    /// The population (ready for the next generation).
    pub fn population(&self) -> &Population {
        &self.population
    }

    /// Evolves until the configured number of generations or until `stop` is set
    /// (checked after each generation, which is finished first).
    pub fn run(
        &mut self,
        stop: &AtomicBool,
        on_generation: impl FnMut(&GenerationRecord),
    ) -> Result<Outcome> {
        let pool = Arc::clone(&self.pool);
        let evaluator = ParallelEvaluator::with_pool(self.training.clone(), &pool);
        self.run_on(evaluator, stop, on_generation)
    }

    /// The worker threads this run evaluates on (for an evaluator of the program's own).
    pub fn pool(&self) -> Arc<rayon::ThreadPool> {
        Arc::clone(&self.pool)
    }

    /// [`Run::run`] on a given evaluator (e.g. one that spreads each
    /// generation over the processes of an MPI job).
    pub fn run_on<E: Evaluator>(
        &mut self,
        evaluator: E,
        stop: &AtomicBool,
        on_generation: impl FnMut(&GenerationRecord),
    ) -> Result<Outcome> {
        let total = self.config.experiment.generations;
        let mut evolution =
            Evolution::resume(self.population.clone(), evaluator, self.progress.done);
        let mut recorder = Recorder {
            dir: &self.dir,
            config: &self.config,
            training: &self.training,
            progress: &mut self.progress,
            total,
            started: Instant::now(),
            last_best: read_best_genomes(&self.dir.join(files::BEST_GENOMES))?
                .pop()
                .map(|b| (b.generation, b.genome)),
            on_generation,
        };
        let criteria = StopCriteria::generations(total).or_interrupt(stop);
        let result = evolution.run_with(&criteria, &mut recorder);
        self.population = evolution.into_population();
        match result.map_err(driver_error)? {
            StopReason::Interrupted => Ok(Outcome::Interrupted),
            _ => Ok(Outcome::Finished),
        }
    }

    /// The best individual of each figure generation reached.
    pub fn figure_genomes(&self) -> impl Iterator<Item = (u32, f64, &Genome)> {
        self.progress
            .figure_genomes
            .iter()
            .map(|(g, f, genome)| (*g, *f, genome))
    }

    /// The champion (best ever) with its run-relative generation.
    pub fn champion(&self) -> Option<Champion> {
        champion(&self.population, &self.progress, &self.config)
    }
}

/// The champion (best ever) of `population` with its run-relative generation.
fn champion(population: &Population, progress: &Progress, config: &Config) -> Option<Champion> {
    population.best_ever().map(|best| Champion {
        format: "vivae-champion".into(),
        generation: best.generation - progress.start_generation + 1,
        fitness: best.fitness,
        config: Some(Champion::recorded_config(config)),
        genome: best.genome.clone(),
    })
}

/// The driver's error as ours; an error of our own observer comes back unchanged.
fn driver_error(e: DriverError) -> Error {
    match e {
        DriverError::Hook(hook) => match hook.downcast::<Error>() {
            Ok(ours) => *ours,
            Err(other) => Error::Evolution(other.to_string()),
        },
        other => Error::Evolution(other.to_string()),
    }
}

fn write_checkpoint(
    dir: &Path,
    config: &Config,
    progress: &Progress,
    population: &Population,
) -> Result<()> {
    let cp = Checkpoint {
        config: config.clone(),
        progress: progress.clone(),
        population: population.clone(),
    };
    let dir = dir.join(files::CHECKPOINTS);
    let path = dir.join(format!("gen-{:06}.ckpt", progress.done));
    write_atomic(&path, encode_checkpoint(&cp)?.as_bytes())?;
    prune_checkpoints(&dir, config.run.checkpoint_keep)
}

/// Writes a run directory's per-generation files and its checkpoints: the
/// observer and checkpointer of a run.
struct Recorder<'a, F> {
    dir: &'a Path,
    config: &'a Config,
    training: &'a Training,
    progress: &'a mut Progress,
    total: u32,
    /// When the generation under way started.
    started: Instant,
    /// The last line written to `best-genomes.jsonl`: (generation, genome).
    last_best: Option<(u32, Genome)>,
    on_generation: F,
}

impl<F: FnMut(&GenerationRecord)> Recorder<'_, F> {
    /// Appends one generation's rows and rewrites the champion.
    fn record(&mut self, report: &GenerationReport<'_>) -> Result<()> {
        let seconds = self.started.elapsed().as_secs_f64();
        let population = report.strategy;
        let generation = report.generation;
        let fitness = population.fitnesses();
        let sorted = stats::sorted_descending(&fitness);
        let stats = report.stats;
        let (best_genome, best) = population
            .champion()
            .map(|(g, f)| (g.clone(), f))
            .expect("an evaluated population has a champion");
        let controller = self.training.primary().controller(&best_genome)?;
        let n = sorted.len();
        let (mean, median) = stats::mean(&fitness)
            .zip(stats::median_of_sorted(&sorted))
            .expect("an evaluated population has fitnesses");
        let robot_steps = n as f64 * self.training.robot_steps() as f64;
        let record = GenerationRecord {
            generation,
            total: self.total,
            best,
            mean,
            median,
            worst: sorted[n - 1],
            species: stats.species,
            mean_nodes: stats.mean_nodes,
            mean_links: stats.mean_links,
            best_links: controller.expressed_links(),
            possible_links: controller.possible_links(),
            seconds,
            robot_steps_per_second: robot_steps / seconds.max(1e-9),
            best_ever: population.best_ever().map_or(best, |b| b.fitness),
        };
        let same_as = self
            .last_best
            .as_ref()
            .filter(|(_, g)| *g == best_genome)
            .map(|(k, _)| *k);
        let line = BestLine {
            generation,
            fitness: best,
            species: population
                .species()
                .iter()
                .map(|s| (s.id, s.members.len()))
                .collect(),
            genome: same_as.is_none().then(|| best_genome.clone()),
            same_as,
        };
        append(
            &self.dir.join(files::BEST_GENOMES),
            &(serde_json::to_string(&line).map_err(|e| Error::Serialize {
                what: "a best-genomes line",
                reason: e.to_string(),
            })? + "\n"),
        )?;
        // Referring to the previous line only keeps a resumed run's file identical.
        self.last_best = Some((generation, best_genome.clone()));
        if FIGURE_GENERATIONS.contains(&generation) {
            self.progress
                .figure_genomes
                .push((generation, best, best_genome));
        }

        let mut row = String::new();
        let r = &record;
        let _ = writeln!(
            row,
            "{},{},{},{},{},{},{},{},{},{}",
            r.generation,
            r.best,
            r.mean,
            r.median,
            r.worst,
            r.species,
            r.mean_nodes,
            r.mean_links,
            r.best_links,
            r.possible_links
        );
        self.progress.generations_len = append(&self.dir.join(files::GENERATIONS), &row)?;
        let mut rows = String::with_capacity(n * 24);
        for (rank, f) in sorted.iter().enumerate() {
            let _ = writeln!(rows, "{generation},{},{f}", rank + 1);
        }
        self.progress.population_len = append(&self.dir.join(files::POPULATION), &rows)?;
        let timing = format!(
            "{generation},{seconds:.6},{:.0}\n",
            record.robot_steps_per_second
        );
        self.progress.timing_len = append(&self.dir.join(files::TIMING), &timing)?;
        if let Some(champion) = champion(population, self.progress, self.config) {
            let text = serde_json::to_string_pretty(&champion).map_err(|e| Error::Serialize {
                what: "champion",
                reason: e.to_string(),
            })? + "\n";
            write_atomic(&self.dir.join(files::CHAMPION), text.as_bytes())?;
        }
        self.progress.done = generation;
        (self.on_generation)(&record);
        Ok(())
    }
}

impl<F: FnMut(&GenerationRecord)> Observer for Recorder<'_, F> {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        self.record(report).map_err(Into::into)
    }
}

impl<F> Checkpointer for Recorder<'_, F> {
    fn after_generation(&mut self, state: &CheckpointState<'_>) -> Result<(), HookError> {
        // A stopping run (finished or interrupted) always leaves a checkpoint.
        if state.stopping.is_some()
            || state
                .generations_done
                .is_multiple_of(self.config.run.checkpoint_interval)
        {
            write_checkpoint(self.dir, self.config, self.progress, state.strategy)?;
        }
        self.started = Instant::now();
        Ok(())
    }
}

impl Progress {
    fn start(start_generation: u32) -> Progress {
        Progress {
            done: 0,
            start_generation,
            generations_len: GENERATIONS_HEADER.len() as u64,
            population_len: POPULATION_HEADER.len() as u64,
            timing_len: TIMING_HEADER.len() as u64,
            figure_genomes: Vec::new(),
            scenario_fnv: None,
            maps_fnv: None,
        }
    }
}

fn thread_pool(threads: usize) -> Result<Arc<rayon::ThreadPool>> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map(Arc::new)
        .map_err(|e| Error::Threads(e.to_string()))
}

/// Appends `text` and returns the file's new length.
fn append(path: &Path, text: &str) -> Result<u64> {
    let mut f = fs::OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(Error::io("open", path))?;
    f.write_all(text.as_bytes())
        .map_err(Error::io("write", path))?;
    Ok(f.metadata().map_err(Error::io("read", path))?.len())
}

fn truncate(path: &Path, len: u64) -> Result<()> {
    let damaged = |reason: String| Error::Checkpoint {
        path: path.to_path_buf(),
        reason,
    };
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
fn checkpoint_names(entries: fs::ReadDir) -> Vec<String> {
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("gen-") && n.ends_with(".ckpt"))
        .collect();
    names.sort();
    names
}

fn prune_checkpoints(dir: &Path, keep: usize) -> Result<()> {
    let names = checkpoint_names(fs::read_dir(dir).map_err(Error::io("list", dir))?);
    let excess = names.len().saturating_sub(keep);
    for n in &names[..excess] {
        let path = dir.join(n);
        fs::remove_file(&path).map_err(Error::io("prune", path))?;
    }
    Ok(())
}

/// Reads `population.csv` back: per generation, the fitnesses best first.
pub fn read_population_csv(path: &Path) -> Result<Vec<Vec<f64>>> {
    let text = fs::read_to_string(path).map_err(Error::io("read", path))?;
    let malformed = |line: usize, what: &dyn std::fmt::Display| Error::RunFile {
        path: path.to_path_buf(),
        reason: format!("line {}: {what}", line + 1),
    };
    let mut out: Vec<Vec<f64>> = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let mut parts = line.split(',');
        let (Some(g), Some(_), Some(f)) = (parts.next(), parts.next(), parts.next()) else {
            return Err(malformed(i, &"expected generation,rank,fitness"));
        };
        let g: usize = g.parse().map_err(|e| malformed(i, &e))?;
        let f: f64 = f.parse().map_err(|e| malformed(i, &e))?;
        if g == 0 {
            return Err(malformed(i, &"generation 0"));
        }
        if out.len() < g {
            out.resize(g, Vec::new());
        }
        out[g - 1].push(f);
    }
    Ok(out)
}

/// Reads `generations.csv` back as (generation, best, mean) rows.
pub fn read_generations_csv(path: &Path) -> Result<Vec<(u32, f64, f64)>> {
    let text = fs::read_to_string(path).map_err(Error::io("read", path))?;
    text.lines()
        .enumerate()
        .skip(1)
        .map(|(i, line)| {
            let v: Vec<&str> = line.split(',').collect();
            let parse = || -> Option<(u32, f64, f64)> {
                Some((
                    v.first()?.parse().ok()?,
                    v.get(1)?.parse().ok()?,
                    v.get(2)?.parse().ok()?,
                ))
            };
            parse().ok_or_else(|| Error::RunFile {
                path: path.to_path_buf(),
                reason: format!("line {}: malformed row", i + 1),
            })
        })
        .collect()
}

/// Checks a decoded checkpoint against itself and the run's experiment: the
/// genomes fit the substrate (a wrong CPPN would fail in every later
/// generation) and the recorded file lengths are possible.
fn validate_progress(path: &Path, cp: &Checkpoint, experiment: &Experiment) -> Result<()> {
    let bad = |reason: String| Error::Checkpoint {
        path: path.to_path_buf(),
        reason,
    };
    let p = &cp.progress;
    if p.done > cp.config.experiment.generations {
        return Err(bad(format!(
            "{} generations done, more than the run's {}",
            p.done, cp.config.experiment.generations
        )));
    }
    for (name, len, header) in [
        (files::GENERATIONS, p.generations_len, GENERATIONS_HEADER),
        (files::POPULATION, p.population_len, POPULATION_HEADER),
        (files::TIMING, p.timing_len, TIMING_HEADER),
    ] {
        if len < header.len() as u64 {
            return Err(bad(format!(
                "{name} length {len} is shorter than its header"
            )));
        }
    }
    if cp.population.genomes().is_empty() {
        return Err(bad("the population has no genomes".into()));
    }
    let genomes = cp
        .population
        .genomes()
        .iter()
        .chain(p.figure_genomes.iter().map(|(_, _, g)| g));
    for g in genomes {
        experiment
            .controller(g)
            .map_err(|e| bad(format!("a genome does not fit the run: {e}")))?;
    }
    Ok(())
}

/// Removes temporary files a killed process left behind (`.NAME.tmp-PID`).
fn remove_stale_temporaries(dir: &Path) {
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
struct RunLock(#[allow(dead_code)] fs::File);

impl RunLock {
    /// Locks `dir`, or refuses (bad input) when another process holds it.
    fn acquire(dir: &Path) -> Result<RunLock> {
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
fn remove_abandoned_builds(parent: &Path, name: &str) {
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

/// Refuses an existing `dir` unless `force`; with `force`, locks it so that a
/// run still writing there is not deleted under its feet.
fn check_out_dir(dir: &Path, force: bool) -> Result<Option<RunLock>> {
    if !dir.exists() {
        return Ok(None);
    }
    if !force {
        return Err(bad_input(format!(
            "{}: already exists (choose another --out, or pass --force to overwrite)",
            dir.display()
        )));
    }
    if !dir.is_dir() {
        return Err(bad_input(format!(
            "{}: exists and is not a directory",
            dir.display()
        )));
    }
    RunLock::acquire(dir).map(Some)
}

/// Writes a new run's files and its first checkpoint into `dir`.
fn fill_new_run(
    dir: &Path,
    config: &mut Config,
    scenario_text: &str,
    population: &Population,
    progress: &Progress,
) -> Result<()> {
    let checkpoints = dir.join(files::CHECKPOINTS);
    fs::create_dir_all(&checkpoints).map_err(Error::io("create", checkpoints))?;
    write_atomic(&dir.join(files::SCENARIO), scenario_text.as_bytes())?;
    if !config.experiment.init_population.is_empty() {
        // Keep the starting population beside the config that names it.
        let init_cp = Checkpoint {
            config: config.clone(),
            progress: progress.clone(),
            population: population.clone(),
        };
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
    for (name, header) in [
        (files::GENERATIONS, GENERATIONS_HEADER),
        (files::POPULATION, POPULATION_HEADER),
        (files::TIMING, TIMING_HEADER),
        (files::BEST_GENOMES, ""),
    ] {
        write_atomic(&dir.join(name), header.as_bytes())?;
    }
    write_checkpoint(dir, config, progress, population)
}

/// Copies the training maps of a multi-map run into `dir/scenarios/` with
/// their manifest, and points `experiment.scenarios` at the copies.
fn copy_maps(dir: &Path, config: &mut Config, maps: &[crate::maps::TrainingMap]) -> Result<()> {
    if maps.is_empty() {
        return Ok(());
    }
    let folder = dir.join(crate::maps::MAPS_DIR);
    fs::create_dir_all(&folder).map_err(Error::io("create", &folder))?;
    let names = crate::maps::copy_names(maps);
    for (name, m) in names.iter().zip(maps) {
        write_atomic(&folder.join(name), m.loaded.text.as_bytes())?;
    }
    write_atomic(
        &folder.join(crate::maps::MANIFEST),
        crate::maps::manifest(&names, maps).as_bytes(),
    )?;
    config.experiment.scenarios = names
        .iter()
        .map(|n| format!("{}/{n}", crate::maps::MAPS_DIR))
        .collect();
    Ok(())
}

/// Checks that the CSV files, cut at the lengths the checkpoint records, end
/// exactly after its last generation: a checkpoint of another run, or one
/// with forged lengths, would otherwise cut a row in half.
fn check_csv_prefixes(dir: &Path, checkpoint: &Path, p: &Progress) -> Result<()> {
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
fn csv_prefix(path: &Path, len: u64, tail_only: bool) -> Result<Option<(Vec<u8>, bool)>> {
    use std::io::{Read, Seek, SeekFrom};
    let unreadable = |e: std::io::Error| Error::Checkpoint {
        path: path.to_path_buf(),
        reason: crate::io::io_reason(&e),
    };
    let mut f = fs::File::open(path).map_err(unreadable)?;
    let actual = f.metadata().map_err(unreadable)?.len();
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

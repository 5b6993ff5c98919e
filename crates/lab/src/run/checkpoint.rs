//! What a run keeps in its run directory that names its search and its
//! task: the checkpoints' contents, the config check on resume, the header
//! of `generations.csv` and a new run's first files. Their file format
//! (names, sealing, pruning) is [`crate::rundir`]'s.

use std::fs;
use std::path::Path;

use serde::{Deserialize, Serialize};
use vivae_neat::{Genome, Population};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::write_atomic;
use crate::rundir::{
    GENERATIONS_HEADER, POPULATION_HEADER, TIMING_HEADER, csv_prefix, files, seal_with, unseal,
    write_checkpoint_bytes,
};
use crate::search::Search;
use crate::tasks::maps::is_multi_map;
use crate::tasks::{StoredTarget, config_from_toml};

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
    /// The run's progress towards its task's target (tasks with a target
    /// only), stored under the task's name.
    #[serde(flatten)]
    pub(crate) target: StoredTarget,
    /// The genome that held the target on its task's check, which stopped
    /// the run and is its champion: (generation, training fitness, genome).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) solver: Option<(u32, f64, Genome)>,
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
    let expected = crate::tasks::config_text(recorded);
    if text == expected {
        return Ok(());
    }
    if let Ok(mut on_disk) = config_from_toml(&text) {
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
            "differs from the run's newest checkpoint {} (line {line}: `{differs}`); a run resumes with the config it started with: undo the edit (a resume to more generations extends the run), or start a new run from the edited config",
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
        let (population, search) = match search.downcast_ref::<Population>() {
            Some(p) => (Some(p.clone()), None),
            None => (None, Some(search.clone())),
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
            (Some(p), None) => Ok(Search::of(p.clone())),
            (None, Some(s)) if s.downcast_ref::<Population>().is_some() => {
                Err("a NEAT population stored as `search`")
            }
            (None, Some(s)) => Ok(s.clone()),
            (None, None) => Err("neither a population nor a search strategy"),
            (Some(_), Some(_)) => Err("both a population and a search strategy"),
        }
    }

    /// The NEAT population inside (of a strategy that breeds one), for `retrain`.
    fn into_population(self, path: &Path) -> Result<(Config, Population)> {
        let population = (self.search().ok()).and_then(|s| s.population().cloned());
        population
            .map(|p| (self.config, p))
            .ok_or_else(|| Error::Checkpoint {
                path: path.to_path_buf(),
                reason:
                    "holds no NEAT population (its strategy keeps an archive or a front instead)"
                        .into(),
            })
    }
}

/// The top-level files the registered search strategies write into a run
/// directory (their entries' `files`): a run replaced with `force` may hold them.
pub(crate) fn strategy_files() -> Vec<&'static str> {
    (crate::search::entries().iter())
        .flat_map(|e| e.files.iter().copied())
        .collect()
}

pub(crate) fn encode_checkpoint(cp: &Checkpoint) -> Result<Vec<u8>> {
    seal_with(|out| {
        serde_json::to_writer(out, cp).map_err(|e| Error::Serialize {
            what: "checkpoint",
            reason: e.to_string(),
        })
    })
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
    let body = unseal(text, path)?;
    let cp: Checkpoint = serde_json::from_str(body).map_err(|e| {
        // serde counts the body's lines: the file's are one more (the header).
        let text = e.to_string();
        let what = text
            .rsplit_once(" at line ")
            .map_or(text.as_str(), |(w, _)| w);
        let at = format!("line {} column {}", e.line() + 1, e.column());
        bad(&format!("unreadable checkpoint ({at}): {what}"))
    })?;
    // The population validated itself while being deserialised.
    crate::tasks::check(&cp.config).map_err(|e| bad(&format!("checkpoint config: {e}")))?;
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

pub(crate) fn write_checkpoint(
    dir: &Path,
    config: &Config,
    progress: &Progress,
    search: &Search,
) -> Result<()> {
    let cp = Checkpoint::new(config, progress, search);
    write_checkpoint_file(dir, config.run.checkpoint_keep, &cp)
}

/// Writes `cp` into the run directory `dir` (atomically) and prunes all but
/// the newest `keep` checkpoints.
pub(crate) fn write_checkpoint_file(dir: &Path, keep: usize, cp: &Checkpoint) -> Result<()> {
    write_checkpoint_bytes(dir, cp.progress.done, keep, &encode_checkpoint(cp)?)
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
            target: StoredTarget::default(),
            solver: None,
        }
    }
}

/// The header of `generations.csv` for a run of `config`: NEAT's columns,
/// then the strategy's own, then the task's.
pub(crate) fn generations_header(config: &Config) -> String {
    let base = GENERATIONS_HEADER.trim_end_matches('\n');
    let task =
        crate::tasks::entry(config.experiment.task.name()).map_or("", |t| t.generation_columns);
    format!(
        "{base}{}{task}\n",
        crate::search::entry_of(config).map_or("", |e| e.extra_columns)
    )
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

/// Writes a new run's files and its first checkpoint into `dir`.
pub(crate) fn fill_new_run(
    dir: &Path,
    config: &mut Config,
    scenario_text: Option<&str>,
    search: &Search,
    progress: &Progress,
) -> Result<()> {
    let checkpoints = dir.join(files::CHECKPOINTS);
    fs::create_dir_all(&checkpoints).map_err(Error::io("create", checkpoints))?;
    if let Some(text) = scenario_text {
        write_atomic(&dir.join(files::SCENARIO), text.as_bytes())?;
    }
    if !config.experiment.init_population.is_empty() {
        // Keep the starting population beside the config that names it.
        let init_cp = Checkpoint::new(config, progress, search);
        write_atomic(
            &dir.join(files::INIT_POPULATION),
            &encode_checkpoint(&init_cp)?,
        )?;
        config.experiment.init_population = files::INIT_POPULATION.into();
    }
    if scenario_text.is_some() && !is_multi_map(config) {
        config.experiment.scenario = files::SCENARIO.into();
    }
    write_atomic(
        &dir.join(files::CONFIG),
        crate::tasks::config_text(config).as_bytes(),
    )?;
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

#[cfg(test)]
pub(super) mod tests {
    use vivae_neat::{GenomeSpec, NeatParams};

    use super::*;
    use crate::io::fnv1a;
    use crate::rundir::seal_checkpoint;

    /// The checkpoint, after generation `done`, of a fresh population of a default config.
    pub(in crate::run) fn sample(done: u32) -> Checkpoint {
        let population =
            Population::new(NeatParams::default(), GenomeSpec::plain(3, 2), 7).unwrap();
        let mut progress = Progress::start(1);
        progress.done = done;
        Checkpoint::new(&Config::default(), &progress, &Search::of(population))
    }

    #[test]
    fn checkpoints_are_written_in_the_second_format_and_both_formats_resume() {
        let cp = sample(3);
        let text = String::from_utf8(encode_checkpoint(&cp).unwrap()).unwrap();
        let (header, body) = text.split_once('\n').unwrap();
        assert!(header.starts_with("vivae-checkpoint v2 "), "{header}");
        assert_eq!(text, seal_checkpoint(body));
        let path = Path::new("gen-000003.ckpt");
        assert_eq!(decode_checkpoint_text(&text, path).unwrap(), cp);
        // The first format: the same body behind an FNV-1a of its bytes.
        let v1 = format!(
            "vivae-checkpoint v1 {:016x}\n{body}",
            fnv1a(body.as_bytes())
        );
        assert_eq!(decode_checkpoint_text(&v1, path).unwrap(), cp);
        // Each format's checksum is its own: the other's is refused.
        let swapped = format!(
            "vivae-checkpoint v2 {:016x}\n{body}",
            fnv1a(body.as_bytes())
        );
        let e = decode_checkpoint_text(&swapped, path).unwrap_err();
        assert!(e.to_string().contains("checksum mismatch"), "{e}");
    }
}

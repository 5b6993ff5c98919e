//! Checkpoints: what they hold, their codec, the newest one, pruning.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::*;

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
    pub(crate) target: crate::tasks::StoredTarget,
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
    if let Ok(mut on_disk) = crate::tasks::config_from_toml(&text) {
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

/// The header of the first checkpoint format: its checksum is [`fnv1a`] of the body.
const CHECKPOINT_MAGIC_V1: &str = "vivae-checkpoint v1";

/// The header of checkpoints written now: its checksum is [`fnv1a_words`]
/// of the body (the body is the same JSON as in v1).
pub(crate) const CHECKPOINT_MAGIC: &str = "vivae-checkpoint v2";

/// FNV-1a over the body's 8-byte little-endian words (the last one padded
/// with zeros), then its length: the checksum of a v2 checkpoint.
///
/// A checkpoint after every generation hashed a megabyte each time, and
/// FNV-1a over bytes is one multiply per byte in a dependent chain (1.3 ms
/// a checkpoint of the default run); over words it is an eighth of that.
/// Each step is a bijection of the running hash, so a change of any one
/// word always changes the checksum, as with bytes.
pub fn fnv1a_words(bytes: &[u8]) -> u64 {
    const PRIME: u64 = 0x0100_0000_01b3;
    let mut chunks = bytes.chunks_exact(8);
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for c in &mut chunks {
        let w = u64::from_le_bytes(c.try_into().expect("8 bytes"));
        h = (h ^ w).wrapping_mul(PRIME);
    }
    let rest = chunks.remainder();
    if !rest.is_empty() {
        let mut last = [0u8; 8];
        last[..rest.len()].copy_from_slice(rest);
        h = (h ^ u64::from_le_bytes(last)).wrapping_mul(PRIME);
    }
    (h ^ bytes.len() as u64).wrapping_mul(PRIME)
}

/// `body` (a checkpoint's JSON) behind the header of the current format:
/// the bytes of a checkpoint file (for tests and tools that edit one).
pub fn seal_checkpoint(body: &str) -> String {
    header(fnv1a_words(body.as_bytes())) + body
}

/// The header line of a current-format checkpoint whose body hashes to
/// `checksum` (always the same length: the checksum has 16 digits).
fn header(checksum: u64) -> String {
    format!("{CHECKPOINT_MAGIC} {checksum:016x}\n")
}

pub(crate) fn encode_checkpoint(cp: &Checkpoint) -> Result<Vec<u8>> {
    // The header's checksum is filled in once the body is written after
    // it: the body is neither copied nor reallocated for the header.
    // The last checkpoint's size: the next one is about as large.
    static LAST_LEN: AtomicUsize = AtomicUsize::new(0);
    let placeholder = header(0);
    let mut out =
        Vec::with_capacity(LAST_LEN.load(Ordering::Relaxed).max(placeholder.len()) + 4096);
    out.extend_from_slice(placeholder.as_bytes());
    serde_json::to_writer(&mut out, cp).map_err(|e| Error::Serialize {
        what: "checkpoint",
        reason: e.to_string(),
    })?;
    let sealed = header(fnv1a_words(&out[placeholder.len()..]));
    out[..placeholder.len()].copy_from_slice(sealed.as_bytes());
    LAST_LEN.store(out.len(), Ordering::Relaxed);
    Ok(out)
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
    // Checkpoints of either format resume: only the checksum differs.
    let (checksum, hash): (&str, fn(&[u8]) -> u64) =
        if let Some(c) = header.strip_prefix(CHECKPOINT_MAGIC) {
            (c, fnv1a_words)
        } else if let Some(c) = header.strip_prefix(CHECKPOINT_MAGIC_V1) {
            (c, fnv1a)
        } else {
            return Err(bad("not a vivae checkpoint (bad header)"));
        };
    let expected = u64::from_str_radix(checksum.trim(), 16)
        .map_err(|_| bad("not a vivae checkpoint (bad checksum field)"))?;
    if hash(body.as_bytes()) != expected {
        return Err(bad("corrupt or truncated checkpoint (checksum mismatch)"));
    }
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
    write_checkpoint_file(dir, config.run.checkpoint_keep, &cp)
}

/// Writes `cp` into the run directory `dir` (atomically) and prunes all but
/// the newest `keep` checkpoints.
pub(crate) fn write_checkpoint_file(dir: &Path, keep: usize, cp: &Checkpoint) -> Result<()> {
    let dir = dir.join(files::CHECKPOINTS);
    let path = dir.join(format!("gen-{:06}.ckpt", cp.progress.done));
    write_atomic(&path, &encode_checkpoint(cp)?)?;
    prune_checkpoints(&dir, keep)
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
            target: crate::tasks::StoredTarget::default(),
        }
    }
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

#[cfg(test)]
pub(super) mod tests {
    use vivae_neat::{GenomeSpec, NeatParams};

    use super::*;

    /// The checkpoint, after generation `done`, of a fresh population of a default config.
    pub(in crate::rundir) fn sample(done: u32) -> Checkpoint {
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

    #[test]
    fn the_word_checksum_sees_every_byte_and_the_length() {
        let body = b"{\"config\":{\"seed\":1},\"rest\":[1,2,3]}".to_vec();
        let h = fnv1a_words(&body);
        for i in 0..body.len() {
            for bit in 0..8 {
                let mut b = body.clone();
                b[i] ^= 1 << bit;
                assert_ne!(fnv1a_words(&b), h, "byte {i} bit {bit}");
            }
        }
        // Dropping trailing zeros changes the length, and so the checksum.
        assert_ne!(fnv1a_words(&[1, 0, 0]), fnv1a_words(&[1]));
        assert_ne!(fnv1a_words(&[]), fnv1a_words(&[0]));
    }
}

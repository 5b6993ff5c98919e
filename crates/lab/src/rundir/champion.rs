//! The champion (`champion.json`) and each generation's best genome
//! (`best-genomes.jsonl`); reading a champion back, its recorded config
//! checked by its task, is [`crate::tasks`]'s (`read_champion`).

use super::*;

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
pub(super) fn read_run_file(path: &Path) -> std::io::Result<String> {
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
pub(super) fn parse_best_genomes(
    text: &str,
    path: &Path,
    budget: u64,
) -> Result<Vec<GenerationBest>> {
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
pub(super) fn genome_size(genome: &Genome) -> u64 {
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

//! The CSV files of a run (`generations.csv`, `population.csv`, `timing.csv`): their rows written, appended, truncated and read back.

use super::*;

pub(crate) const GENERATIONS_HEADER: &str = "generation,best,mean,median,worst,species,mean_cppn_nodes,mean_cppn_links,best_substrate_links,possible_substrate_links\n";

pub(crate) const POPULATION_HEADER: &str = "generation,rank,fitness\n";

pub(crate) const TIMING_HEADER: &str = "generation,seconds,robot_steps_per_second\n";

/// One generation's record: its row of `generations.csv`, and what the
/// terminal and `timing.csv` add to it.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationRecord {
    /// The generation's row of `generations.csv` (its generation, fitness
    /// statistics, species, CPPN sizes and substrate links).
    pub row: GenerationRow,
    /// Generations the run will have in all.
    pub total: u32,
    /// Wall time of the generation.
    pub seconds: f64,
    /// Simulated robot-steps per second of wall time.
    pub robot_steps_per_second: f64,
    /// Evaluations of the generation copied from an equal genome's instead of run.
    pub reused: usize,
    /// Best fitness of the run so far.
    pub best_ever: f64,
}

impl GenerationRecord {
    /// Generation, 1-based.
    pub fn generation(&self) -> u32 {
        self.row.generation
    }

    /// The record's row of `generations.csv`.
    pub fn generations_row(&self) -> String {
        self.row.to_csv()
    }

    /// The record's row of `timing.csv`.
    pub fn timing_row(&self) -> String {
        format!(
            "{},{:.6},{:.0}\n",
            self.row.generation, self.seconds, self.robot_steps_per_second
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

/// One row of `generations.csv`: as the run writes it, as it is read back,
/// and as the report and the viewer show it (their JSON names in `serde`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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
    #[serde(rename = "cppn_nodes")]
    pub mean_cppn_nodes: f64,
    /// Mean enabled CPPN links.
    #[serde(rename = "cppn_links")]
    pub mean_cppn_links: f64,
    /// Links the generation's best CPPN expresses in the substrate.
    #[serde(rename = "substrate_links")]
    pub best_substrate_links: usize,
    /// Links the substrate could have.
    #[serde(skip)]
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
pub(super) fn read_rows<T>(
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

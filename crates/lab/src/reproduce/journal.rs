//! A pack's journal: one line per finished run, so that a pack stopped by a
//! crash, a reboot or Ctrl-C continues where it was (`vivae reproduce` runs
//! again skip the runs already in it).
//!
//! A run is keyed by a checksum of its full config (the worker-thread count
//! aside, which does not change a result), so a journal never answers for a
//! run with other settings — another budget, another vivae default — and one
//! journal can hold several packs' or several methods' runs. The file is
//! rewritten atomically after each run: it is never half written.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{fnv1a, io_reason, read_regular_text, write_atomic};

/// First line of a journal file.
pub const HEADER: &str = "# vivae reproduce journal: config checksum, run, outcome";
/// Largest journal read (a million runs' lines).
const MAX_BYTES: u64 = 128 << 20;

/// A pack's finished runs, in memory and (with a path) on disk.
#[derive(Debug, Default)]
pub struct Journal {
    path: Option<PathBuf>,
    /// Checksum → (what the run was, its outcome).
    runs: BTreeMap<u64, (String, String)>,
}

impl Journal {
    /// The journal at `path` (empty when the file does not exist yet), or
    /// one kept in memory only.
    pub fn open(path: Option<&Path>) -> Result<Journal> {
        let Some(path) = path else {
            return Ok(Journal::default());
        };
        let mut journal = Journal {
            path: Some(path.to_path_buf()),
            runs: BTreeMap::new(),
        };
        let text = match read_regular_text(path, MAX_BYTES) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(journal),
            Err(e) => return Err(bad(path, &io_reason(&e))),
        };
        for (k, line) in text.lines().enumerate() {
            if line.starts_with('#') || line.trim().is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split('\t').collect();
            let parsed = match fields[..] {
                [sum, run, outcome] => u64::from_str_radix(sum, 16)
                    .ok()
                    .map(|s| (s, run.to_string(), outcome.to_string())),
                _ => None,
            };
            let Some((sum, run, outcome)) = parsed else {
                return Err(bad(
                    path,
                    &format!("line {} is not `checksum<TAB>run<TAB>outcome`", k + 1),
                ));
            };
            journal.runs.insert(sum, (run, outcome));
        }
        Ok(journal)
    }

    /// The outcome recorded for the run of `config`, if it finished before.
    pub fn get(&self, config: &Config) -> Option<&str> {
        (self.runs.get(&checksum(config))).map(|(_, outcome)| outcome.as_str())
    }

    /// Records that the run of `config`, described by `run`, gave `outcome`,
    /// and writes the journal (when it has a file).
    pub fn record(&mut self, config: &Config, run: &str, outcome: &str) -> Result<()> {
        let clean = |s: &str| s.replace(['\t', '\n', '\r'], " ");
        (self.runs).insert(checksum(config), (clean(run), clean(outcome)));
        let Some(path) = &self.path else {
            return Ok(());
        };
        let mut text = format!("{HEADER}\n");
        for (sum, (run, outcome)) in &self.runs {
            text += &format!("{sum:016x}\t{run}\t{outcome}\n");
        }
        write_atomic(path, text.as_bytes())
    }

    /// How many runs it holds.
    pub fn len(&self) -> usize {
        self.runs.len()
    }

    /// Whether it holds no run.
    pub fn is_empty(&self) -> bool {
        self.runs.is_empty()
    }
}

/// The checksum of a run's settings: its config as TOML, threads aside.
fn checksum(config: &Config) -> u64 {
    let mut c = config.clone();
    c.run.threads = 0;
    fnv1a(c.to_toml().as_bytes())
}

fn bad(path: &Path, why: &str) -> Error {
    Error::Invalid(format!("journal {}: {why}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_journal_answers_only_for_the_same_settings_and_survives_reopening() {
        let dir = std::env::temp_dir().join(format!("vivae-journal-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("runs.tsv");
        let mut a = Config::default();
        a.experiment.seed = 3;
        let mut j = Journal::open(Some(&path)).unwrap();
        assert!(j.is_empty() && j.get(&a).is_none());
        j.record(&a, "road seed 3", "solved 1250").unwrap();
        let mut threads = a.clone();
        threads.run.threads = 7;
        let mut other = a.clone();
        other.experiment.generations += 1;
        let j = Journal::open(Some(&path)).unwrap();
        assert_eq!((j.len(), j.get(&threads)), (1, Some("solved 1250")));
        assert_eq!(j.get(&other), None);
        std::fs::write(&path, "# x\nnot a line\n").unwrap();
        let e = Journal::open(Some(&path)).unwrap_err().to_string();
        assert!(e.contains("runs.tsv") && e.contains("line 2"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

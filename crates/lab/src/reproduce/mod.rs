//! Replication packs: a named published experiment run with the paper's
//! settings, its result one Markdown table of ours beside the paper's
//! numbers with their source (`vivae reproduce NAME`, Python's
//! `vivae.reproduce(name)`).
//!
//! A pack is a file here and a line in [`PACKS`]. Each run of a pack is the
//! very run `vivae evolve` makes with the same settings (it is prepared and
//! run by the same code, in a scratch run directory removed afterwards), so
//! a row of the table can be checked run by run from the command line.

mod boxes;
mod journal;
mod maze;
mod pole;
mod retina;
mod road;
mod xor;

use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use crate::config::Config;
use crate::error::Result;
use crate::io::bad_input;
use crate::run::prepare::prepare;

pub use journal::Journal;

/// How a pack is run.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Runs per method (the paper's count by default).
    pub runs: Option<usize>,
    /// The first run's seed; run `k` has seed `seed + k`.
    pub seed: u64,
    /// A few-minute version: fewer runs and a smaller budget.
    pub quick: bool,
    /// Evaluations per run at most (the paper's, or the quick budget, by default).
    pub evaluations: Option<u64>,
    /// Worker threads per run (0 = one per core); results do not depend on it.
    pub threads: usize,
    /// Only these methods (a pack's [`Pack::methods`]); empty = all of them.
    pub methods: Vec<String>,
    /// The journal of finished runs, which a run again skips (none = in memory).
    pub journal: Option<PathBuf>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            runs: None,
            seed: 1,
            quick: false,
            evaluations: None,
            threads: 0,
            methods: Vec::new(),
            journal: None,
        }
    }
}

/// A pack's result: one table, ours beside the paper's.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// What was run (the pack's title).
    pub title: String,
    /// Column headings.
    pub columns: Vec<String>,
    /// One row per method, as many cells as columns.
    pub rows: Vec<Vec<String>>,
    /// Lines under the table: settings, seeds, sources, differences.
    pub notes: Vec<String>,
}

impl Table {
    /// A table titled `title` with these columns, rows and notes.
    pub fn new(
        title: impl Into<String>,
        columns: &[&str],
        rows: Vec<Vec<String>>,
        notes: Vec<String>,
    ) -> Table {
        Table {
            title: title.into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows,
            notes,
        }
    }

    /// The table as Markdown: a heading, the table, the notes as a list.
    pub fn markdown(&self) -> String {
        let mut s = format!("### {}\n\n", self.title);
        let row = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        s += &row(&self.columns);
        s += &row(&vec!["---".to_string(); self.columns.len()]);
        for r in &self.rows {
            s += &row(r);
        }
        if !self.notes.is_empty() {
            s.push('\n');
        }
        for n in &self.notes {
            let _ = writeln!(s, "* {n}");
        }
        s
    }
}

/// How a pack runs: with its options, telling `progress` a line per finished run.
pub type RunPack = fn(&Options, &mut dyn FnMut(&str)) -> Result<Table>;

/// A replication pack.
#[derive(Debug, Clone, Copy)]
pub struct Pack {
    /// Its name (`vivae reproduce NAME`).
    pub name: &'static str,
    /// One line on what it reproduces.
    pub what: &'static str,
    /// The methods `--method` can pick (empty: the pack has no choice).
    pub methods: &'static [&'static str],
    /// Runs it; `progress` gets a line per finished run.
    pub run: RunPack,
}

/// Every pack.
pub const PACKS: [Pack; 8] = [
    maze::MEDIUM,
    maze::HARD,
    xor::XOR,
    pole::MARKOV,
    pole::NONMARKOV,
    boxes::BOXES,
    retina::RETINA,
    road::ROAD,
];

/// The pack called `name`; bad input naming the packs otherwise.
pub fn find(name: &str) -> Result<&'static Pack> {
    PACKS.iter().find(|p| p.name == name).ok_or_else(|| {
        let names: Vec<&str> = PACKS.iter().map(|p| p.name).collect();
        bad_input(format!(
            "reproduce: no pack {name:?}; the packs are {}",
            names.join(", ")
        ))
    })
}

/// Runs pack `name` with `options`; `progress` gets a line per finished run.
pub fn run(name: &str, options: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let pack = find(name)?;
    if options.runs == Some(0) || options.evaluations == Some(0) {
        return Err(bad_input(
            "reproduce: --runs and --evaluations must be at least 1",
        ));
    }
    if let Some(m) = (options.methods.iter()).find(|m| !pack.methods.contains(&m.as_str())) {
        return Err(bad_input(if pack.methods.is_empty() {
            format!("reproduce: pack {name} has no choice of method (asked for {m:?})")
        } else {
            format!(
                "reproduce: pack {name} has no method {m:?}; its methods are {}",
                pack.methods.join(", ")
            )
        }));
    }
    (pack.run)(options, progress)
}

/// What one run gave, from `journal` when it finished before, else run and
/// recorded there: the evaluations up to its first solver, if it solved; and
/// whether it came from the journal.
pub(crate) fn solved_at_journaled(
    config: Config,
    run: &str,
    journal: &mut Journal,
) -> Result<(Option<u64>, bool)> {
    let known = journal.get(&config).and_then(|o| match o {
        "unsolved" => Some(None),
        _ => (o.strip_prefix("solved ")?.parse().ok()).map(Some),
    });
    if let Some(at) = known {
        return Ok((at, true));
    }
    let at = solved_at(config.clone())?;
    let outcome = at.map_or("unsolved".to_string(), |n| format!("solved {n}"));
    journal.record(&config, run, &outcome)?;
    Ok((at, false))
}

/// What one run gave: the evaluations up to its first solver, if it solved.
fn solved_at(config: Config) -> Result<Option<u64>> {
    let dir = scratch_dir();
    let result = (|| {
        let mut run = prepare(config, true)?.create(&dir, true)?;
        run.run(&AtomicBool::new(false), |_| {})?;
        Ok(run.target_progress().and_then(|p| p.solved_at))
    })();
    // The scratch run directory is ours: written by `create` above.
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// A fresh scratch run directory for one run of a pack.
pub(crate) fn scratch_dir() -> PathBuf {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let k = NEXT.fetch_add(1, Ordering::SeqCst);
    std::env::temp_dir().join(format!("vivae-reproduce-{}-{k}", std::process::id()))
}

/// Mean, sample standard deviation and median of `xs` (none when empty).
pub(crate) fn stats(xs: &[u64]) -> Option<(f64, f64, f64)> {
    if xs.is_empty() {
        return None;
    }
    let n = xs.len() as f64;
    let mean = xs.iter().map(|&x| x as f64).sum::<f64>() / n;
    let var = xs.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    let mut sorted = xs.to_vec();
    sorted.sort_unstable();
    let mid = sorted.len() / 2;
    let median = if sorted.len().is_multiple_of(2) {
        (sorted[mid - 1] + sorted[mid]) as f64 / 2.0
    } else {
        sorted[mid] as f64
    };
    Some((mean, var.sqrt(), median))
}

/// `n` with thousands separators, rounded (`35,109`).
pub(crate) fn thousands(n: f64) -> String {
    let digits = format!("{:.0}", n.round());
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_and_numbers_read_as_the_paper_writes_them() {
        assert_eq!(stats(&[]), None);
        let (mean, sd, median) = stats(&[1, 2, 3, 10]).unwrap();
        assert_eq!((mean, median), (4.0, 2.5));
        assert!((sd - 4.0826).abs() < 1e-3, "{sd}");
        assert_eq!(thousands(35109.4), "35,109");
        assert_eq!(thousands(250000.0), "250,000");
        assert_eq!(thousands(999.0), "999");
    }

    #[test]
    fn an_unknown_pack_is_refused_naming_the_packs() {
        let e = run("nope", &Options::default(), &mut |_| {})
            .unwrap_err()
            .to_string();
        assert!(e.contains("\"nope\"") && e.contains("maze-hard"), "{e}");
    }

    #[test]
    fn the_table_is_markdown_with_its_notes() {
        let t = Table {
            title: "T".into(),
            columns: vec!["a".into(), "b".into()],
            rows: vec![vec!["1".into(), "2".into()]],
            notes: vec!["n".into()],
        };
        assert_eq!(
            t.markdown(),
            "### T\n\n| a | b |\n| --- | --- |\n| 1 | 2 |\n\n* n\n"
        );
    }
}

//! What a replication pack is: its options, its result table, its entry.

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::error::Result;

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

/// [`Pack::methods`] of a pack with no choice of method.
pub fn no_methods() -> Vec<&'static str> {
    Vec::new()
}

/// A replication pack.
#[derive(Debug, Clone, Copy)]
pub struct Pack {
    /// Its name (`vivae reproduce NAME`).
    pub name: &'static str,
    /// One line on what it reproduces.
    pub what: &'static str,
    /// The methods `--method` can pick (empty: the pack has no choice),
    /// listed when asked: a pack may run each of the registered tasks that
    /// fit it.
    pub methods: fn() -> Vec<&'static str>,
    /// Runs it; `progress` gets a line per finished run.
    pub run: RunPack,
}

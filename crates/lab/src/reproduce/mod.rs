//! Replication packs: a named published experiment run with the paper's
//! settings, its result one Markdown table of ours beside the paper's
//! numbers with their source (`vivae reproduce NAME`, Python's
//! `vivae.reproduce(name)`).
//!
//! A pack is a file here and a line in `PACKS` (the tasks sit below the
//! packs, which run them through `run`, so a task's packs live here too). Each run of
//! a pack is the very run `vivae evolve` makes with the same settings (it is
//! prepared and run by the same code, in a scratch run directory removed
//! afterwards), so a row of the table can be checked run by run from the
//! command line.

mod boxes;
mod gym;
mod journal;
mod maze;
mod pack;
mod pole;
mod retina;
mod road;
mod xor;

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use crate::config::Config;
use crate::error::{Error, Refusal, Result};
use crate::io::bad_input;
use crate::run::prepare::prepare;

pub use journal::{HEADER as JOURNAL_HEADER, Journal};
pub use pack::{Options, Pack, RunPack, Table};

/// Every pack, in the order `vivae reproduce` lists them: the maze's, then
/// the benchmarks of `vivae_neat::benchmarks`, the road and Gymnasium's
/// classic control.
const PACKS: [Pack; 9] = [
    maze::MEDIUM,
    maze::HARD,
    xor::XOR,
    pole::MARKOV,
    pole::NONMARKOV,
    boxes::BOXES,
    retina::RETINA,
    road::ROAD,
    gym::GYM_CLASSIC,
];

/// Every pack, the maze's first.
pub fn packs() -> impl Iterator<Item = &'static Pack> {
    PACKS.iter()
}

/// The pack called `name`; bad input naming the packs otherwise.
pub fn find(name: &str) -> Result<&'static Pack> {
    packs().find(|p| p.name == name).ok_or_else(|| {
        let names: Vec<&str> = packs().map(|p| p.name).collect();
        bad_input(format!(
            "reproduce: no pack {name:?}; the packs are {}",
            names.join(", ")
        ))
    })
}

/// Most runs a method of a pack runs (`--runs`).
pub const MAX_RUNS: usize = 10_000;

/// Largest first seed: run `k < MAX_RUNS` has seed `seed + k`, which never wraps.
pub const MAX_SEED: u64 = u64::MAX - MAX_RUNS as u64;

/// Runs pack `name` with `options`; `progress` gets a line per finished run.
pub fn run(name: &str, options: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let pack = find(name)?;
    if options.runs == Some(0) || options.evaluations == Some(0) {
        return Err(Error::Refused(
            Refusal::text("reproduce: ")
                .key("runs")
                .then(" and ")
                .key("evaluations")
                .then(" must be at least 1"),
        ));
    }
    if let Some(runs) = options.runs.filter(|&n| n > MAX_RUNS) {
        return Err(Error::Refused(
            Refusal::text("reproduce: ")
                .set("runs", runs)
                .then(format!(": at most {MAX_RUNS} runs a method")),
        ));
    }
    if options.seed > MAX_SEED {
        return Err(Error::Refused(
            Refusal::text("reproduce: ")
                .set("seed", options.seed)
                .then(format!(
                    ": at most {MAX_SEED} (run k has seed SEED + k, which may not pass 2^64 - 1)"
                )),
        ));
    }
    let methods = (pack.methods)();
    if let Some(m) = (options.methods.iter()).find(|m| !methods.contains(&m.as_str())) {
        return Err(bad_input(if methods.is_empty() {
            format!("reproduce: pack {name} has no choice of method (asked for {m:?})")
        } else {
            format!(
                "reproduce: pack {name} has no method {m:?}; its methods are {}",
                methods.join(", ")
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
    let dir = ScratchDir::new();
    let mut run = prepare(config, true)?.create(&dir.0, true)?;
    run.run(&AtomicBool::new(false), |_| {})?;
    Ok(run.target_progress().and_then(|p| p.solved_at))
}

/// A scratch run directory for one run of a pack, removed when dropped
/// (also on an error or a panic) or by [`remove_scratch_dirs`] (a signal).
pub(crate) struct ScratchDir(pub(crate) PathBuf);

/// The scratch directories of the runs under way.
static LIVE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

impl ScratchDir {
    /// A fresh name in the temporary folder (the run creates it).
    pub(crate) fn new() -> ScratchDir {
        use std::sync::atomic::{AtomicU64, Ordering};
        static NEXT: AtomicU64 = AtomicU64::new(0);
        let k = NEXT.fetch_add(1, Ordering::SeqCst);
        let dir = std::env::temp_dir().join(format!("vivae-reproduce-{}-{k}", std::process::id()));
        LIVE.lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(dir.clone());
        ScratchDir(dir)
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        remove_scratch(&self.0);
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        live.retain(|d| *d != self.0);
    }
}

/// Removes a scratch run directory and the folder it is built in before
/// its first checkpoint (`.NAME.tmp-PID`): both are ours, written by
/// [`crate::run::prepare::Prepared::create`].
fn remove_scratch(dir: &std::path::Path) {
    let _ = std::fs::remove_dir_all(dir);
    if let (Some(parent), Some(name)) = (dir.parent(), dir.file_name()) {
        let building = format!(".{}.tmp-{}", name.to_string_lossy(), std::process::id());
        let _ = std::fs::remove_dir_all(parent.join(building));
    }
}

/// Removes the scratch directories of the runs under way: what the program
/// does when Ctrl-C or SIGTERM stops `vivae reproduce` (the journal keeps
/// the finished runs; running the same command again continues).
pub fn remove_scratch_dirs() {
    let live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    for dir in live.iter() {
        remove_scratch(dir);
    }
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
        assert!(e.contains("\"nope\"") && e.contains("xor"), "{e}");
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

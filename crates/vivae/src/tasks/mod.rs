//! The program's side of the tasks: what it draws, serves and plays for a
//! task beyond what the task's [`TaskEntry`] in `vivae_lab` says. A task
//! with program-side parts (its report, figures, viewer page, MPI player) is
//! one folder here with one [`TaskTools`] registered in [`TOOLS`], found by
//! its entry's name (the run's `experiment.task`); a task without one (the
//! driving experiment, the maze) needs none. Nothing outside a task's folder
//! matches on which task it is.

pub mod predator_prey;

use std::path::{Path, PathBuf};

use vivae_lab::rundir::files;
use vivae_lab::tasks::{TaskEntry, read_config};

/// Every task with program-side parts. A new one is a folder here and one line in this list.
pub static TOOLS: [&TaskTools; 1] = [&predator_prey::TOOLS];

/// A tournament's table for a person and its CSV.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TournamentTables {
    /// The table, as `vivae tournament` prints it.
    pub table: String,
    /// The same rows as CSV (`--csv`).
    pub csv: String,
}

/// A task's tournament: how it plays one run's champions against another's,
/// and the CSV file it writes.
#[derive(Debug, Clone, Copy)]
pub struct Tournament {
    /// Plays run `a`'s champions against run `b`'s on this many threads.
    pub play: fn(&Path, &Path, usize) -> vivae_lab::Result<TournamentTables>,
    /// What `--csv` writes, to recognise an earlier one (`vivae_lab::output_path`).
    pub csv: vivae_lab::output_path::OutputKind,
}

/// A task's program-side parts, registered in [`TOOLS`].
pub struct TaskTools {
    /// The lab's entry of the task (its name finds these tools).
    pub entry: &'static TaskEntry,
    /// Writes the figures and `report.html` of the task's run in a directory
    /// (`vivae report`, and the end of a run); returns the page's path.
    pub report: fn(&Path) -> vivae_lab::Result<PathBuf>,
    /// What the end of a run says after the report's path (the figures beside it).
    pub report_note: &'static str,
    /// The record files of its runs, for a refusal by a command that reads
    /// one-population runs only (e.g. `a.csv and b.json`).
    pub records: &'static str,
    /// `vivae tournament` between two of its runs, for a task that has one.
    pub tournament: Option<Tournament>,
    /// `vivae view` of one of its runs: a page of its own.
    #[cfg(feature = "viewer")]
    pub view: Option<crate::view::OwnPage>,
    /// How an MPI job runs it, for a task on its own driver.
    #[cfg(feature = "mpi")]
    pub mpi: Option<crate::mpi::OwnDriverWork>,
}

impl std::fmt::Debug for TaskTools {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TaskTools")
            .field("task", &self.entry.name)
            .finish()
    }
}

/// The tools of the task called `name`, if it has any.
pub fn of_task(name: &str) -> Option<&'static TaskTools> {
    TOOLS.iter().copied().find(|t| t.entry.name == name)
}

/// The tools of the task of the run in `dir` (by its readable `config.toml`), if it has any.
pub fn of_run(dir: &Path) -> Option<&'static TaskTools> {
    let config = read_config(&dir.join(files::CONFIG)).ok()?;
    of_task(config.experiment.task.name())
}

/// The tournament of the task of the run `a`, or else the first task's
/// that has one (whose refusal then names what `a` lacks).
pub fn tournament_for(a: &Path) -> Option<Tournament> {
    of_run(a)
        .and_then(|t| t.tournament)
        .or_else(|| TOOLS.iter().find_map(|t| t.tournament))
}

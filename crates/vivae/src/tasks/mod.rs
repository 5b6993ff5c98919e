//! The program's side of the tasks: what it draws, serves and plays for a
//! task beyond what the task's [`TaskEntry`] in `vivae_lab` says. A task
//! with program-side parts (its report, figures, replay, viewer page, MPI
//! player) is one folder here with one [`TaskTools`] registered in
//! [`TOOLS`], found by its entry's name (the run's `experiment.task`); a
//! task without one (the maze, the classic-control tasks) needs none: the
//! commands give it its curves, its replay text and say what it lacks.
//! Nothing outside a task's folder matches on which task it is.

pub mod driving;
pub mod predator_prey;

use std::path::{Path, PathBuf};

use crate::report::RunSummary;
use vivae_lab::config::Config;
use vivae_lab::io::bad_input;
use vivae_lab::run::Run;
use vivae_lab::rundir::{Champion, files};
use vivae_lab::search::files::Member;
use vivae_lab::tasks::{TaskEntry, read_config};

/// Every task with program-side parts. A new one is a folder here and one line in this list.
pub static TOOLS: [&TaskTools; 2] = [&driving::TOOLS, &predator_prey::TOOLS];

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
    /// Draws the figures and `report.html` of a run on the program's driver
    /// at its end (`vivae evolve`, `vivae resume`, Python's `vivae.report`),
    /// for a task that draws figures of its own there (any other's end
    /// writes its curves alone); says what the end of the run prints.
    pub finish: Option<fn(&Run) -> vivae_lab::Result<RunSummary>>,
    /// What the end of a run says after the report's path (the figures beside it).
    pub report_note: &'static str,
    /// The record files of its runs, for a refusal by a command that reads
    /// one-population runs only (e.g. `a.csv and b.json`).
    pub records: &'static str,
    /// `vivae tournament` between two of its runs, for a task that has one.
    pub tournament: Option<Tournament>,
    /// `vivae replay` drawing the genome's episode, for a task that draws one
    /// (any other prints its replay text).
    pub replay: Option<fn(&ReplayRequest<'_>) -> anyhow::Result<()>>,
    /// `vivae view` of one of its runs: a page of its own.
    #[cfg(feature = "viewer")]
    pub view: Option<crate::view::OwnPage>,
    /// `vivae view` of its runs, genomes and scenarios: its robots' live
    /// world (a task with neither this nor a page of its own has nothing to show).
    #[cfg(feature = "viewer")]
    pub world: Option<crate::view::WorldPage>,
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

/// What `vivae replay` asks of a task that draws the replay: the genome,
/// the config it replays with (the command's flags applied) and the
/// command's options.
#[derive(Debug)]
pub struct ReplayRequest<'a> {
    /// The run directory or genome file replayed (for messages and names).
    pub source: &'a Path,
    /// The genome replayed, with what its file records.
    pub champion: &'a Champion,
    /// The config replayed with.
    pub config: &'a Config,
    /// Whether the command named a scenario (else the run's is replayed).
    pub scenario_given: bool,
    // The four options below are the driving task's alone. They stay here
    // rather than in its folder: clap's derive fixes `vivae replay`'s flags
    // in `cli::replay::ReplayArgs` when the program is built, so a task's
    // own flags there would mean that file naming the driving task's type
    // (what no file outside a task's folder does) or clap's arguments
    // registered at run time per task; a task that draws no replay refuses
    // `--placement-seed` by name.
    /// `--placement-seed`: the evaluation placement to replay.
    pub placement_seed: Option<u64>,
    /// `--blind-rays`: the distance rays read nothing.
    pub blind_rays: bool,
    /// `--swerve`: also draw the meeting blinding changes most.
    pub swerve: bool,
    /// `--meetings`: also write every robot's meetings with the placed blocks.
    pub meetings: bool,
    /// The archive or front member replayed (none: the champion).
    pub member: Option<Member>,
    /// The folder the figures go to.
    pub out: std::path::PathBuf,
}

/// Draws the figures and `report.html` of `run` at its end, as its task's
/// tools do ([`TaskTools::finish`]); refused for a task that draws none.
pub fn finish_run(run: &Run) -> vivae_lab::Result<RunSummary> {
    let task = &run.config().experiment.task;
    match finish_of(run) {
        Some(finish) => finish(run),
        None => Err(bad_input(format!(
            "{} run has no trajectory figures",
            vivae_lab::error::a(task.name())
        ))),
    }
}

/// How the task of `run` draws its figures at the end of a run, if it does.
pub fn finish_of(run: &Run) -> Option<fn(&Run) -> vivae_lab::Result<RunSummary>> {
    of_task(run.config().experiment.task.name()).and_then(|t| t.finish)
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

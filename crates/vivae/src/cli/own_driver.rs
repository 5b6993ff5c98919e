//! Running a task that has a driver of its own (the predator–prey task's two
//! populations): its lines for a person on stderr (unless quiet), its summary
//! line on stdout, then its report (the task's program-side tools). Under
//! MPI every rank prepares what the task's tools say (e.g. the run's arena)
//! and joins the job; rank 0 runs the driver, which has the job's ranks play
//! its batches (docs/distributed.md), and the workers play them.

use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use vivae_lab::config::Config;
use vivae_lab::tasks::{OwnDriver, Session, Stopped, entry_of_run};

use super::mpi_job::{OwnRun, join_mpi_own_driver, launched_by_mpi, own_driver_players};

/// Creates and runs a run of `config` in `dir` on `driver`.
pub fn evolve(
    driver: OwnDriver,
    dir: &Path,
    config: Config,
    force: bool,
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
) -> anyhow::Result<ExitCode> {
    let threads = config.run.threads;
    if launched_by_mpi() {
        // Every rank prepares the run; rank 0 writes to `dir` only after the handshake.
        if let (_, Some(code)) = join_mpi_own_driver(OwnRun::New(&config), quiet)? {
            return Ok(code);
        }
    }
    let task = config.experiment.task.name().to_string();
    let stopped = in_session(Some(&task), quiet, threads, interrupted, |session| {
        (driver.evolve)(dir, config, force, session)
    })?;
    conclude(dir, stopped, quiet)
}

/// Resumes the run in `dir` on `driver`.
pub fn resume(
    driver: OwnDriver,
    dir: &Path,
    generations: Option<u32>,
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
) -> anyhow::Result<ExitCode> {
    let mut threads = 0;
    if launched_by_mpi() {
        // Every rank reads the run (rank 0 writes to it only after the handshake).
        let (recorded, code) = join_mpi_own_driver(OwnRun::Existing(dir), quiet)?;
        threads = recorded;
        if let Some(code) = code {
            return Ok(code);
        }
    }
    let task = entry_of_run(dir).map(|e| e.name);
    let stopped = in_session(task, quiet, threads, interrupted, |session| {
        (driver.resume)(dir, generations, session)
    })?;
    conclude(dir, stopped, quiet)
}

/// The end of a run on its own driver, as [`super::drive`] ends one: a
/// finished run's report; an interrupted one's figures so far, the line
/// that says how to resume it and exit code 130; a finished run asked to
/// resume says so (its report drawn if missing).
fn conclude(dir: &Path, stopped: Stopped, quiet: bool) -> anyhow::Result<ExitCode> {
    match stopped {
        Stopped::Finished(_) => report(dir, quiet),
        Stopped::Interrupted(done) => {
            if done > 0 {
                report(dir, true)?;
            }
            eprintln!(
                "interrupted after generation {done}; checkpoint written. Resume with: vivae resume {}",
                dir.display()
            );
            Ok(ExitCode::from(130))
        }
        Stopped::AlreadyFinished { generations, .. } => {
            eprintln!("{}", finished_note(dir, generations));
            if !dir.join(vivae_lab::rundir::files::REPORT).is_file() {
                report(dir, quiet)?;
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Draws the figures and `report.html` of a run that has stopped, when its
/// task's program-side tools draw them (`vivae report` rebuilds them); says
/// where unless `quiet`.
fn report(dir: &Path, quiet: bool) -> anyhow::Result<ExitCode> {
    if let Some(tools) = crate::tasks::of_run(dir) {
        let path = (tools.report)(dir)?;
        if !quiet {
            eprintln!("report: {}{}", path.display(), tools.report_note);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs `work` in a session that says its progress on stderr unless
/// `quiet`, with Ctrl-C and SIGTERM asking it to stop after the generation;
/// prints a finished run's summary line. On rank 0 of an MPI job the
/// session's batches are played across the job's ranks by the players of
/// `task` (rank 0 on `threads` threads).
fn in_session(
    task: Option<&str>,
    quiet: bool,
    threads: usize,
    interrupted: &Arc<AtomicBool>,
    work: impl FnOnce(&Session<'_>) -> vivae_lab::Result<Stopped>,
) -> anyhow::Result<Stopped> {
    super::drive::install_ctrlc(interrupted);
    let say = move |line: &str| {
        if !quiet {
            eprintln!("{line}");
        }
    };
    let players = own_driver_players(task, threads)?;
    let session = Session {
        interrupted,
        say: &say,
        players: players.as_deref(),
    };
    let stopped = work(&session);
    // The job's traffic line (unless quiet) before the summary line.
    drop(players);
    let stopped = stopped?;
    if let Stopped::Finished(line) = &stopped {
        println!("{line}");
    }
    Ok(stopped)
}

/// What `vivae resume` says of a run whose `total` generations are all done:
/// that it is finished, and how to extend it.
pub fn finished_note(dir: &std::path::Path, total: u32) -> String {
    let dir = dir.display();
    format!(
        "{dir} is already finished ({total} of {total} generations); to extend it: vivae resume {dir} --generations N (N > {total})"
    )
}

//! Running a task that has a driver of its own (the predator–prey task's two
//! populations): its lines for a person on stderr (unless quiet), its summary
//! line on stdout. Under MPI every rank builds the run's arena and joins the
//! job; rank 0 runs the driver, which has the job's ranks play its meetings
//! (docs/distributed.md), and the workers play them.

use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use vivae_lab::config::Config;
use vivae_lab::tasks::predator_prey::run::{arena_for, arena_of_run};
use vivae_lab::tasks::{OwnDriver, Session};

use super::mpi_job::{join_mpi_meetings, launched_by_mpi, meetings_player};

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
        // Every rank builds the arena; rank 0 writes to `dir` only after the handshake.
        let prepared = arena_for(&config).map_err(anyhow::Error::from);
        let joining = (prepared.as_ref()).map(|(arena, text)| (&config, text.as_str(), arena));
        if let Some(code) = join_mpi_meetings(joining, threads, quiet)? {
            return Ok(code);
        }
    }
    in_session(quiet, threads, interrupted, |session| {
        (driver.evolve)(dir, config, force, session)
    })?;
    report(dir, quiet)
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
        let prepared = arena_of_run(dir).map_err(anyhow::Error::from);
        threads = prepared.as_ref().map_or(0, |(c, _, _)| c.run.threads);
        let joining = (prepared.as_ref()).map(|(c, arena, text)| (c, text.as_str(), arena));
        if let Some(code) = join_mpi_meetings(joining, threads, quiet)? {
            return Ok(code);
        }
    }
    in_session(quiet, threads, interrupted, |session| {
        (driver.resume)(dir, generations, session)
    })?;
    report(dir, quiet)
}

/// Draws the figures and `report.html` of a predator–prey run that has
/// stopped (`vivae report` rebuilds them); says where unless `quiet`.
fn report(dir: &Path, quiet: bool) -> anyhow::Result<ExitCode> {
    if vivae::report_coevo::is_predator_prey_run(dir) {
        let path = vivae::report_coevo::write(dir)?;
        if !quiet {
            eprintln!("report: {} (and ciao.png, coevolution.png)", path.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs `work` in a session that says its progress on stderr unless
/// `quiet`, then prints its summary line. On rank 0 of an MPI job the
/// session's meetings are played across the job's ranks (rank 0 on
/// `threads` threads).
fn in_session(
    quiet: bool,
    threads: usize,
    interrupted: &Arc<AtomicBool>,
    work: impl FnOnce(&Session<'_>) -> vivae_lab::Result<String>,
) -> anyhow::Result<ExitCode> {
    let say = move |line: &str| {
        if !quiet {
            eprintln!("{line}");
        }
    };
    let player = meetings_player(threads)?;
    let session = Session {
        interrupted,
        say: &say,
        meetings: player.as_deref(),
    };
    let line = work(&session);
    // The job's traffic line (unless quiet) before the summary line.
    drop(player);
    println!("{}", line?);
    Ok(ExitCode::SUCCESS)
}

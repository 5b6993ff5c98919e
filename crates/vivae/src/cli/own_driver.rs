//! Running a task that has a driver of its own (the predator–prey task's two
//! populations): its lines for a person on stderr (unless quiet), its summary
//! line on stdout. It runs on threads of this process, not under MPI.

use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use vivae_lab::config::Config;
use vivae_lab::tasks::{OwnDriver, Session};

use super::mpi_job::launched_by_mpi;

/// Creates and runs a run of `config` in `dir` on `driver`.
pub fn evolve(
    driver: OwnDriver,
    dir: &Path,
    config: Config,
    force: bool,
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
) -> anyhow::Result<ExitCode> {
    in_session(quiet, interrupted, |session| {
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
    in_session(quiet, interrupted, |session| {
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

/// Runs `work` in a session that says its progress on stderr unless `quiet`,
/// then prints its summary line (one process: MPI is refused).
fn in_session(
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
    work: impl FnOnce(&Session<'_>) -> vivae_lab::Result<String>,
) -> anyhow::Result<ExitCode> {
    refuse_mpi()?;
    let say = move |line: &str| {
        if !quiet {
            eprintln!("{line}");
        }
    };
    let session = Session {
        interrupted,
        say: &say,
    };
    println!("{}", work(&session)?);
    Ok(ExitCode::SUCCESS)
}

/// A task on its own driver does not run under MPI (every rank would run it).
fn refuse_mpi() -> anyhow::Result<()> {
    if launched_by_mpi() {
        return Err(vivae_lab::io::bad_input(
            "this task co-evolves two populations on its own driver, which does not run under MPI: run it without mpirun",
        )
        .into());
    }
    Ok(())
}

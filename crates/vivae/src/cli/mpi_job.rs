//! The evolving commands' side of an MPI job (the feature `mpi`; see
//! `crate::mpi` and docs/distributed.md): whether this process is one of its
//! ranks, the start-up handshake, and spreading generations (or the batches
//! of a run on its task's own driver) over the ranks.
//! Without the feature each is a no-op, so the commands call them always.

use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use vivae_lab::config::Config;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::GenerationRecord;
use vivae_lab::tasks::maps::TrainingMap;
use vivae_neat::driver::Task;

/// Rank 0's players of a task's batches, as its driver's session takes them.
pub type Players = Box<dyn std::any::Any + Sync>;

/// Whether an MPI launcher started this process (never without the `mpi` feature).
pub fn launched_by_mpi() -> bool {
    #[cfg(feature = "mpi")]
    return crate::mpi::launched_by_mpi();
    #[cfg(not(feature = "mpi"))]
    false
}

/// Under an MPI launcher, the start-up handshake of every rank (see
/// `crate::mpi`), for every command that evolves one population: each rank
/// brings the run it prepared (config, training maps, experiment) or why it
/// could not, and the evaluation threads it will use. `Some(code)` on a
/// worker rank whose work is done, `None` where the run goes on (always,
/// without MPI).
pub fn join_mpi_job(
    prepared: Result<(&Config, &[TrainingMap], &dyn Task), &anyhow::Error>,
    threads: usize,
    quiet: bool,
) -> anyhow::Result<Option<ExitCode>> {
    #[cfg(feature = "mpi")]
    {
        match prepared {
            Ok((config, maps, task)) => {
                let fingerprint = vivae_lab::tasks::maps::fingerprint_text(maps);
                let work = crate::mpi::Genomes(task);
                join(Ok((config, fingerprint.as_str(), &work)), threads, quiet)
            }
            Err(e) => join(Err(e), threads, quiet),
        }
    }
    #[cfg(not(feature = "mpi"))]
    {
        let _ = (prepared, threads, quiet);
        Ok(None)
    }
}

/// A run on its task's own driver, as every rank of an MPI job prepares it.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(not(feature = "mpi"), allow(dead_code))]
pub enum OwnRun<'a> {
    /// A new run of a config.
    New(&'a Config),
    /// The run in a directory, resumed.
    Existing(&'a Path),
}

/// [`join_mpi_job`] for a run on its task's own driver: each rank prepares
/// what the task's program-side tools say (config, scenario text, what a
/// worker does). The run's threads (an existing run's recorded ones, 0
/// when it cannot be read or without MPI) and `Some(code)` on a worker rank
/// whose work is done.
pub fn join_mpi_own_driver(
    run: OwnRun<'_>,
    quiet: bool,
) -> anyhow::Result<(usize, Option<ExitCode>)> {
    #[cfg(feature = "mpi")]
    {
        let entry = match run {
            OwnRun::New(config) => vivae_lab::tasks::entry_of(config).ok(),
            OwnRun::Existing(dir) => vivae_lab::tasks::entry_of_run(dir),
        };
        let Some(mpi) = entry.and_then(|e| crate::tasks::of_task(e.name)?.mpi) else {
            let why = "this run's task has no MPI work: run it without mpirun";
            return Err(vivae_lab::io::bad_input(why).into());
        };
        let prepared = match run {
            OwnRun::New(config) => (mpi.for_config)(config),
            OwnRun::Existing(dir) => (mpi.for_run)(dir),
        }
        .map_err(anyhow::Error::from);
        // A new run's threads are its config's; an existing run's, those it recorded.
        let threads = match (run, &prepared) {
            (OwnRun::New(config), _) => config.run.threads,
            (OwnRun::Existing(_), Ok(p)) => p.config.run.threads,
            (OwnRun::Existing(_), Err(_)) => 0,
        };
        let joining =
            (prepared.as_ref()).map(|p| (&p.config, p.scenario_text.as_str(), p.work.as_ref()));
        Ok((threads, join(joining, threads, quiet)?))
    }
    #[cfg(not(feature = "mpi"))]
    {
        let _ = (run, quiet);
        Ok((0, None))
    }
}

/// The handshake of this rank with `prepared` (config, scenario text, what
/// it does as a worker).
#[cfg(feature = "mpi")]
fn join(
    prepared: Result<(&Config, &str, &dyn crate::mpi::Work), &anyhow::Error>,
    threads: usize,
    quiet: bool,
) -> anyhow::Result<Option<ExitCode>> {
    use crate::mpi::{MpiError, Setup, Started, start};
    use vivae_lab::io::{bad_input, one_line};
    let setup = prepared
        .map(|(config, scenario_text, work)| Setup {
            config,
            scenario_text,
            work,
            threads,
        })
        .map_err(|e| one_line(&format!("{e:#}")));
    match start(setup, quiet) {
        Ok(Started::Lead) => Ok(None),
        Ok(Started::WorkerDone) => Ok(Some(ExitCode::SUCCESS)),
        Err(e @ MpiError::Refused(_)) => Err(bad_input(e.to_string()).into()),
        Err(e) => Err(e.into()),
    }
}

/// Who plays the batches of a run on the task `task`'s own driver, on rank
/// 0 of an MPI job whose workers joined (on `threads` threads of its own,
/// and the workers'): the task's players, as its session takes them;
/// `None` (this process's threads) otherwise.
pub fn own_driver_players(task: Option<&str>, threads: usize) -> anyhow::Result<Option<Players>> {
    #[cfg(feature = "mpi")]
    if let Some(mpi) = task.and_then(crate::tasks::of_task).and_then(|t| t.mpi) {
        return Ok((mpi.player)(threads)?);
    }
    let _ = (task, threads);
    Ok(None)
}

/// Runs the generations of `run`; rank 0 of an MPI job spreads each one over the job's ranks.
pub fn run_generations(
    run: &mut Run,
    interrupted: &AtomicBool,
    on_generation: impl FnMut(&GenerationRecord),
) -> vivae_lab::Result<Outcome> {
    #[cfg(feature = "mpi")]
    if let Some(evaluator) =
        crate::mpi::MpiEvaluator::for_leader(run.task().clone_box(), run.pool())
    {
        return run.run_on(evaluator, interrupted, on_generation);
    }
    run.run(interrupted, on_generation)
}

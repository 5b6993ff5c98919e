//! The evolving commands' side of an MPI job (the feature `mpi`; see
//! `vivae::mpi` and docs/distributed.md): whether this process is one of its
//! ranks, the start-up handshake, and spreading generations (or a
//! predator–prey run's meetings) over the ranks.
//! Without the feature each is a no-op, so the commands call them always.

use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use vivae_lab::config::Config;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::GenerationRecord;
use vivae_lab::tasks::maps::TrainingMap;
use vivae_lab::tasks::predator_prey::Arena;
use vivae_lab::tasks::predator_prey::meetings::Meetings;
use vivae_neat::driver::Task;

/// Whether an MPI launcher started this process (never without the `mpi` feature).
pub fn launched_by_mpi() -> bool {
    #[cfg(feature = "mpi")]
    return vivae::mpi::launched_by_mpi();
    #[cfg(not(feature = "mpi"))]
    false
}

/// Under an MPI launcher, the start-up handshake of every rank (see
/// `vivae::mpi`), for every command that evolves one population: each rank
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
                let work = vivae::mpi::Genomes(task);
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

/// [`join_mpi_job`] for a predator–prey run: each rank brings its config,
/// the arena's scenario text and the arena (a worker plays meetings in it).
pub fn join_mpi_meetings(
    prepared: Result<(&Config, &str, &Arena), &anyhow::Error>,
    threads: usize,
    quiet: bool,
) -> anyhow::Result<Option<ExitCode>> {
    #[cfg(feature = "mpi")]
    {
        match prepared {
            Ok((config, text, arena)) => join(
                Ok((config, text, &vivae::mpi::MeetingsOf(arena))),
                threads,
                quiet,
            ),
            Err(e) => join(Err(e), threads, quiet),
        }
    }
    #[cfg(not(feature = "mpi"))]
    {
        let _ = (prepared, threads, quiet);
        Ok(None)
    }
}

/// The handshake of this rank with `prepared` (config, scenario text, what
/// it does as a worker).
#[cfg(feature = "mpi")]
fn join(
    prepared: Result<(&Config, &str, &dyn vivae::mpi::Work), &anyhow::Error>,
    threads: usize,
    quiet: bool,
) -> anyhow::Result<Option<ExitCode>> {
    use vivae::mpi::{MpiError, Setup, Started, start};
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

/// Who plays a predator–prey run's meetings on rank 0 of an MPI job whose
/// workers joined (on `threads` threads of its own, and the workers');
/// `None` (this process's threads) otherwise.
pub fn meetings_player(threads: usize) -> anyhow::Result<Option<Box<dyn Meetings>>> {
    #[cfg(feature = "mpi")]
    if let Some(player) = vivae::mpi::MpiMeetings::for_leader(threads)? {
        return Ok(Some(Box::new(player)));
    }
    let _ = threads;
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
        vivae::mpi::MpiEvaluator::for_leader(run.task().clone_box(), run.pool())
    {
        return run.run_on(evaluator, interrupted, on_generation);
    }
    run.run(interrupted, on_generation)
}

//! `vivae resume`: continues an interrupted run, or extends a finished one.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use anyhow::Context as _;
use clap::Args;
use vivae_lab::run::Run;
use vivae_lab::rundir::{self, files};
use vivae_neat::driver::Task;

use super::args::{Generations, Quiet, Threads};
use super::drive::drive;
use super::mpi_job::{join_mpi_job, launched_by_mpi};

/// Options of `vivae resume`.
#[derive(Args, Debug)]
#[command(mut_arg("generations", |a| a.help("Total generations (extends a finished run)")))]
pub struct ResumeArgs {
    /// The run directory.
    pub run_dir: PathBuf,
    #[command(flatten)]
    pub generations: Generations,
    #[command(flatten)]
    pub threads: Threads,
    #[command(flatten)]
    pub quiet: Quiet,
    /// The precision the run computes in (exact|fast): refused unless it is
    /// the one the run started with (its checkpoint records it).
    #[arg(long, value_name = "exact|fast")]
    pub precision: Option<vivae_neat::Precision>,
}

/// Runs `vivae resume`.
pub fn run(args: ResumeArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let quiet = args.quiet.quiet;
    if let Some(driver) = vivae_lab::tasks::own_driver_of_run(&args.run_dir) {
        if let Some(p) = args.precision {
            let task = vivae_lab::tasks::entry_of_run(&args.run_dir).map_or("", |e| e.name);
            return Err(vivae_lab::io::bad_input(format!(
                "--precision {p}: {} run resumes as it was run (it has no choice of precision); leave --precision out",
                vivae_lab::error::a(task)
            ))
            .into());
        }
        let generations = args.generations.generations;
        return super::own_driver::resume(driver, &args.run_dir, generations, quiet, interrupted);
    }
    if launched_by_mpi() {
        // Every rank reads the run (rank 0 writes to it only after the handshake).
        let prepared = (|| -> anyhow::Result<_> {
            let checkpoint = rundir::latest_checkpoint(&args.run_dir)?;
            let (config, _) = vivae_lab::run::population_from_checkpoint(&checkpoint)?;
            let maps = vivae_lab::tasks::maps::load_run(&args.run_dir, &config, None)?;
            let experiment = vivae_lab::tasks::build(&config, &maps)?;
            Ok((config, maps, experiment))
        })();
        let recorded = prepared.as_ref().map_or(0, |(c, _, _)| c.run.threads);
        let joining = (prepared.as_ref()).map(|(c, m, e)| (c, m.as_slice(), e as &dyn Task));
        if let Some(code) = join_mpi_job(joining, args.threads.threads.unwrap_or(recorded), quiet)?
        {
            return Ok(code);
        }
    }
    let run = Run::resume_in(
        &args.run_dir,
        args.generations.generations,
        args.threads.threads,
        args.precision,
    )?;
    if already_finished(&run)? {
        return Ok(ExitCode::SUCCESS);
    }
    let source = if vivae_lab::tasks::maps::is_multi_map(run.config()) {
        let dir = run.dir();
        run.config()
            .experiment
            .scenarios
            .iter()
            .map(|s| dir.join(s).display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        run.dir().join(files::SCENARIO).display().to_string()
    };
    // The pool runs on the threads given now, if any, not the recorded ones.
    let threads = args.threads.threads.unwrap_or(run.config().run.threads);
    drive(run, "resume", &source, threads, quiet, interrupted)
}

/// Whether `run` has nothing left to do, said on the terminal (its task's target reached,
/// or every generation done; then any figures missing are drawn).
fn already_finished(run: &Run) -> anyhow::Result<bool> {
    let total = run.config().experiment.generations;
    if let Some(at) = run.target_progress().and_then(|m| m.solved_at) {
        let task = run.config().experiment.task.name();
        eprintln!(
            "{} is already finished: the {task} was solved after {at} evaluations ({} run stops when solved)",
            run.dir().display(),
            vivae_lab::error::a(task)
        );
        return Ok(true);
    }
    if run.done() < total {
        return Ok(false);
    }
    eprintln!("{}", super::own_driver::finished_note(run.dir(), total));
    // A run that stopped before its figures and report showed every
    // generation (killed while drawing them) gets them now.
    if let Some(finish) = crate::tasks::finish_of(run)
        && rundir::drawn_generations(run.dir()) != Some(run.done())
    {
        finish(run).context("writing figures")?;
        eprintln!("figures: {}", run.dir().join(files::FIGURES).display());
        eprintln!("report: {}", run.dir().join(files::REPORT).display());
    }
    Ok(true)
}

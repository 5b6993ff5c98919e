//! `vivae retrain`: a run's final population continues, as a new run, on a
//! re-sampled substrate.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use clap::Args;
use vivae_lab::config::Config;
use vivae_lab::io::bad_input;
use vivae_lab::run::Run;
use vivae_lab::rundir::{self, files};
use vivae_lab::tasks::maps::is_multi_map;
use vivae_neat::driver::Task;

use super::args::{Generations, NewRun, Quiet, Resolution, Threads};
use super::drive::drive;
use super::mpi_job::join_mpi_job;
use super::overrides::apply_overrides;
use super::terminal::warn_repeated_maps;
use vivae_lab::run::prepare::Overrides;

/// Options of `vivae retrain`.
#[derive(Args, Debug)]
#[command(mut_arg("sensors", |a| a.required_unless_present("neurons")))]
#[command(mut_arg("generations", |a| a.help("Generations to evolve on the new substrate").required(true)))]
pub struct RetrainArgs {
    /// The run whose final population continues.
    pub run_dir: PathBuf,
    #[command(flatten)]
    pub resolution: Resolution,
    #[command(flatten)]
    pub generations: Generations,
    #[command(flatten)]
    pub new_run: NewRun,
    #[command(flatten)]
    pub threads: Threads,
    #[command(flatten)]
    pub quiet: Quiet,
}

/// Runs `vivae retrain`.
pub fn run(args: RetrainArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let checkpoint = rundir::latest_checkpoint(&args.run_dir)?;
    let (mut config, population) = vivae_lab::run::population_from_checkpoint(&checkpoint)?;
    retrain_on_the_runs_maps(&mut config, &args.run_dir)?;
    config.experiment.init_population = checkpoint.to_string_lossy().into_owned();
    let overrides = Overrides {
        generations: args.generations.generations,
        sensors: args.resolution.sensors,
        neurons: args.resolution.neurons,
        threads: args.threads.threads,
        ..Overrides::default()
    };
    apply_overrides(&mut config, &overrides)?;
    let prepared = (|| -> anyhow::Result<_> {
        let maps = vivae_lab::tasks::maps::load(&config)?;
        let experiment = vivae_lab::tasks::build(&config, &maps)?;
        Ok((maps, experiment))
    })();
    let quiet = args.quiet.quiet;
    let joining = (prepared.as_ref()).map(|(m, e)| (&config, m.as_slice(), e as &dyn Task));
    if let Some(code) = join_mpi_job(joining, config.run.threads, quiet)? {
        return Ok(code);
    }
    let (maps, experiment) = prepared?;
    warn_repeated_maps(&maps);
    let dir = args.new_run.dir();
    let source = experiment.describe(&maps);
    let threads = config.run.threads;
    // A run on one map copies it as scenario.svg alone; on several, each one too.
    let copied = if is_multi_map(&config) {
        &maps[..]
    } else {
        &[]
    };
    let run = Run::create_task(
        &dir,
        config,
        experiment,
        Some(&maps[0].loaded.text),
        copied,
        Some(population),
        args.new_run.force,
    )?;
    drive(run, "retrain", &source, threads, quiet, interrupted)
}

/// Points the config of the run in `run_dir` at that run's copies of its
/// maps; refuses a run of another task, which has no substrate to re-sample.
fn retrain_on_the_runs_maps(config: &mut Config, run_dir: &std::path::Path) -> anyhow::Result<()> {
    if !vivae_lab::tasks::has_substrate(config) {
        return Err(bad_input(format!(
            "{}: {} run has no substrate network to re-sample: retrain works on runs of {}",
            run_dir.display(),
            vivae_lab::error::a(config.experiment.task.name()),
            vivae_lab::tasks::names_with(|t| t.substrate)
        ))
        .into());
    }
    if is_multi_map(config) {
        // A multi-map run retrains on the copies of its maps.
        for s in &mut config.experiment.scenarios {
            *s = run_dir.join(&*s).to_string_lossy().into_owned();
        }
    } else {
        config.experiment.scenario = run_dir.join(files::SCENARIO).to_string_lossy().into_owned();
    }
    Ok(())
}

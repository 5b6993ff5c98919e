//! `vivae evolve`: a new run from a config file (or the defaults) and the
//! options that override its keys.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use anyhow::Context as _;
use clap::Args;
use vivae_lab::run::prepare::resolve;
use vivae_neat::driver::Task;

use super::args::{NewRun, Quiet};
use super::drive::drive;
use super::mpi_job::join_mpi_job;
use super::overrides::{Overrides, SPELLING};
use super::terminal::warn_repeated_maps;

/// Options of `vivae evolve`.
#[derive(Args, Debug)]
pub struct EvolveArgs {
    /// Config file (TOML); flags override its keys.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    #[command(flatten)]
    pub overrides: Overrides,
    #[command(flatten)]
    pub new_run: NewRun,
    #[command(flatten)]
    pub quiet: Quiet,
}

/// Runs `vivae evolve`.
pub fn run(args: EvolveArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let resolved = resolve(args.config.as_deref(), &args.overrides.lab, &SPELLING)?;
    let config = resolved.config.clone();
    if let Some(driver) = vivae_lab::tasks::entry_of(&config)
        .ok()
        .and_then(|e| e.own_driver)
    {
        let (dir, force) = (args.new_run.dir(), args.new_run.force);
        let quiet = args.quiet.quiet;
        let run =
            || super::own_driver::evolve(driver, &dir, config.clone(), force, quiet, interrupted);
        return match &args.config {
            Some(path) => run().with_context(|| path.display().to_string()),
            None => run(),
        };
    }
    // Without a config file a task starts from its own defaults, which it
    // may fit to its scenario (e.g. a grid archive fitted to its arena).
    let setup = || resolved.clone().prepare();
    // Problems with what a config file names are reported against that file too.
    let prepared = match &args.config {
        Some(path) => setup().with_context(|| path.display().to_string()),
        None => setup().map_err(anyhow::Error::from),
    };
    let quiet = args.quiet.quiet;
    let joining = (prepared.as_ref()).map(|p| (&p.config, p.maps.as_slice(), &p.task as &dyn Task));
    if let Some(code) = join_mpi_job(joining, config.run.threads, quiet)? {
        return Ok(code);
    }
    let prepared = prepared?;
    if !quiet {
        for m in &prepared.maps {
            for w in &m.loaded.scenario.warnings {
                eprintln!("warning: {w}");
            }
        }
    }
    warn_repeated_maps(&prepared.maps);
    let source = prepared.task.describe(&prepared.maps);
    let threads = prepared.config.run.threads;
    let run = prepared.create(&args.new_run.dir(), args.new_run.force)?;
    drive(run, "evolve", &source, threads, quiet, interrupted)
}

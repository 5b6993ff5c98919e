//! `vivae evolve`: a new run from a config file (or the defaults) and the
//! options that override its keys.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use anyhow::Context as _;
use clap::Args;
use vivae_lab::config::{Config, TaskKind};
use vivae_lab::evolve::Run;
use vivae_lab::io::{bad_input, read_config};
use vivae_lab::run_task::RunTask;
use vivae_lab::rundir;
use vivae_neat::driver::Task;

use super::args::{NewRun, Quiet};
use super::drive::drive;
use super::mpi_job::join_mpi_job;
use super::overrides::{Overrides, apply_overrides};
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
    let task = args.overrides.task;
    let mut config = match &args.config {
        Some(p) => read_config(p)?,
        None => Config::for_task(task),
    };
    if let Some(why) = args
        .config
        .as_ref()
        .and_then(|_| config.task_mismatch(task))
    {
        let t = task.map_or("", TaskKind::name);
        return Err(bad_input(format!("--task {t}: {why}")).into());
    }
    apply_overrides(&mut config, &args.overrides)?;
    let maze_defaults = task == Some(TaskKind::Maze) && args.config.is_none();
    let setup = || -> vivae_lab::Result<_> {
        let maps = vivae_lab::maps::load(&config)?;
        let experiment = RunTask::new(&config, &maps)?;
        let init = if config.experiment.init_population.is_empty() {
            None
        } else {
            let path = Path::new(&config.experiment.init_population);
            Some(rundir::population_from_checkpoint(path)?.1)
        };
        Ok((maps, experiment, init))
    };
    // Problems with what a config file names are reported against that file too.
    let prepared = match &args.config {
        Some(path) => setup().with_context(|| path.display().to_string()),
        None => setup().map_err(anyhow::Error::from),
    };
    let quiet = args.quiet.quiet;
    let joining = (prepared.as_ref()).map(|(m, e, _)| (&config, m.as_slice(), e as &dyn Task));
    if let Some(code) = join_mpi_job(joining, config.run.threads, quiet)? {
        return Ok(code);
    }
    let (maps, experiment, init) = prepared?;
    if let (RunTask::Maze(maze), true) = (&experiment, maze_defaults) {
        // The example's MAP-Elites grid: 10 px cells over the maze.
        config.strategy.map_elites.bins = vivae_lab::maze_run::cell_bins(maze);
    }
    if !quiet {
        for m in &maps {
            for w in &m.loaded.scenario.warnings {
                eprintln!("warning: {w}");
            }
        }
    }
    warn_repeated_maps(&maps);
    let dir = args.new_run.dir();
    let source = match &experiment {
        RunTask::Driving(t) => t.describe(&maps),
        RunTask::Maze(_) => maps[0].loaded.scenario.source.clone(),
    };
    let first = &maps[0].loaded.text;
    let threads = config.run.threads;
    let force = args.new_run.force;
    let maps = if vivae_lab::maps::is_multi_map(&config) {
        &maps[..]
    } else {
        &[]
    };
    let run = Run::create_task(&dir, config, experiment, first, maps, init, force)?;
    drive(run, "evolve", &source, threads, quiet, interrupted)
}

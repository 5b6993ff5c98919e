//! The `vivae` command-line program: parses the command line and hands each
//! command to its file under `cli/`.
//!
//! Exit codes: 0 ok, 1 internal error, 2 bad input or usage, 130 interrupted.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use clap::{CommandFactory, Parser, Subcommand};
use vivae_lab::io::one_line;

mod cli;
mod portable_libm;

use cli::{
    compare, config, drive_image, evolve, export, help_reference, replay, report, reproduce,
    resume, retrain, scenario, tournament, view,
};

/// HyperNEAT-controlled robots that learn to drive on roads (ViVAE).
#[derive(Parser, Debug)]
#[command(
    name = "vivae",
    version,
    about,
    long_about = None,
    after_help = "Exit codes: 0 success, 1 internal error, 2 bad input or usage (one line on \
                  standard error naming the file or argument), 130 interrupted after a checkpoint."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Evolve a driving controller (with no options: the paper's experiment).
    Evolve(evolve::EvolveArgs),
    /// Continue an interrupted run, or extend a finished one.
    Resume(resume::ResumeArgs),
    /// Run a genome (a run's champion) and draw its trajectories.
    Replay(replay::ReplayArgs),
    /// Continue a run's final population on a re-sampled substrate.
    Retrain(retrain::RetrainArgs),
    /// Write a run's controller as ONNX, C or JSON, to run outside vivae.
    Export(export::ExportArgs),
    /// Drive a run's controller from images: camera frames, or a map and poses.
    DriveImage(drive_image::DriveImageArgs),
    /// Rebuild a run's self-contained report.html.
    Report {
        /// The run directory.
        run_dir: PathBuf,
    },
    /// Watch robots drive in the browser (a local web server).
    View(view::ViewArgs),
    /// Compare runs: fitness per generation and per wall-clock second, figure and table.
    Compare(compare::CompareArgs),
    /// Play one predator-prey run's champions against another's: catch rates and hunter fitness.
    Tournament(tournament::TournamentArgs),
    /// Run a published experiment with the paper's settings: ours beside the paper's numbers.
    Reproduce(reproduce::ReproduceArgs),
    /// Inspect and draw scenarios.
    #[command(subcommand)]
    Scenario(scenario::ScenarioCommand),
    /// Print configuration files and references.
    #[command(subcommand)]
    Config(config::ConfigCommand),
    /// Print the command-line reference (docs/reference/cli.md) as Markdown.
    #[command(hide = true)]
    HelpReference,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(err) = vivae_lab::simd::apply_env() {
        eprintln!("error: {err}");
        return ExitCode::from(2);
    }
    let interrupted = Arc::new(AtomicBool::new(false));
    // Under an MPI launcher the evolving commands join the job; MPI ends when `_mpi` drops.
    #[cfg(feature = "mpi")]
    let _mpi = matches!(
        cli.command,
        Command::Evolve(_) | Command::Resume(_) | Command::Retrain(_)
    )
    .then(vivae::mpi::Launch::init);
    match dispatch(cli, &interrupted) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", one_line(&format!("{err:#}")));
            let users_fault = err
                .chain()
                .filter_map(|c| c.downcast_ref::<vivae_lab::Error>())
                .any(vivae_lab::Error::is_bad_input);
            if users_fault {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

/// Runs the command the line names; `interrupted` is set by Ctrl-C.
fn dispatch(cli: Cli, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Evolve(args) => evolve::run(args, interrupted),
        Command::Resume(args) => resume::run(args, interrupted),
        Command::Replay(args) => replay::run(args),
        Command::Retrain(args) => retrain::run(args, interrupted),
        Command::Export(args) => export::run(args),
        Command::DriveImage(args) => drive_image::run(args),
        Command::Report { run_dir } => report::run(&run_dir),
        Command::View(args) => view::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Tournament(args) => tournament::run(args),
        Command::Reproduce(args) => reproduce::run(args),
        Command::Scenario(c) => scenario::run(c),
        Command::Config(c) => config::run(c),
        Command::HelpReference => {
            print!("{}", help_reference::markdown(Cli::command()));
            Ok(ExitCode::SUCCESS)
        }
    }
}

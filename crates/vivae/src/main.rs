//! The `vivae` command-line program: parses the command line ([`Cli`], in the
//! library's `cli` module) and hands each command to its file under `cli/`.
//!
//! Exit codes: 0 ok, 1 internal error, 2 bad input or usage, 130 interrupted.

use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use clap::{CommandFactory, Parser};
use vivae::cli::{
    Cli, Command, compare, config, drive_image, evolve, export, help_reference, replay, report,
    reproduce, resume, retrain, scenario, tournament, view,
};
use vivae_lab::io::one_line;

mod portable_libm;

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

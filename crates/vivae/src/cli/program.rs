//! The `vivae` program as a function: parse a command line, run its command,
//! give the exit code. The program's `main.rs` is a call of [`run_cli`]; a
//! crate of its own that [`register`](vivae_lab::tasks::register)s a task or
//! a [strategy](vivae_lab::search::register) first and then calls it is
//! `vivae` with those added (`--task`, `--strategy`, configs and run
//! directories name them as they name the built-in ones).
//!
//! Exit codes: 0 ok, 1 internal error, 2 bad input or usage, 130 interrupted.

use std::ffi::OsString;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use clap::{CommandFactory, Parser};
use vivae_lab::io::one_line;

use super::{
    Cli, Command, compare, config, drive_image, evolve, export, help_reference, replay, report,
    reproduce, resume, retrain, scenario, tournament, view,
};

/// Runs the `vivae` command line of this process's arguments with every
/// task and strategy registered so far.
pub fn run_cli() -> ExitCode {
    run_cli_from(std::env::args_os())
}

/// Runs the `vivae` command line `args` (the program's name first), as [`run_cli`].
pub fn run_cli_from<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    crate::portable_libm::link();
    // Parsed after the registrations: `--task` and `--strategy` list them.
    let cli = Cli::parse_from(args);
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
    .then(crate::mpi::Launch::init);
    match dispatch(cli, &interrupted) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", one_line(&spelled(&err)));
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

/// `err` as `{err:#}` prints it (each cause after a colon), the settings
/// the library's refusals name spelled as flags (`--out`, `--force`).
fn spelled(err: &anyhow::Error) -> String {
    let said: Vec<String> = (err.chain())
        .map(|c| match c.downcast_ref::<vivae_lab::Error>() {
            Some(e) => super::overrides::SPELLING.error(e),
            None => c.to_string(),
        })
        .collect();
    said.join(": ")
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

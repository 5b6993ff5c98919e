//! `vivae tournament`: one predator–prey run's champions against another's
//! (the tournament of RUN_A's task, from its program-side tools:
//! `crate::tasks`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use vivae_lab::output_path::Output;

use super::args::Threads;

/// Options of `vivae tournament`.
#[derive(Args, Debug)]
pub struct TournamentArgs {
    /// A finished predator-prey run directory.
    #[arg(value_name = "RUN_A")]
    pub a: PathBuf,
    /// Another (e.g. a held-out seed's, or a fixed-prey baseline; may be RUN_A itself).
    #[arg(value_name = "RUN_B")]
    pub b: PathBuf,
    /// Also write the table as CSV to this file (its folder must exist and
    /// not be a run directory).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Replace an existing --csv file that is not an earlier tournament CSV.
    #[arg(long)]
    pub force: bool,
    #[command(flatten)]
    pub threads: Threads,
}

/// Runs `vivae tournament`: the table on stdout (and the CSV written).
pub fn run(args: TournamentArgs) -> anyhow::Result<ExitCode> {
    let Some(tournament) = crate::tasks::tournament_for(&args.a) else {
        return Err(vivae_lab::io::bad_input("no task plays tournaments").into());
    };
    if let Some(path) = &args.csv {
        let csv = Output::new(path, "--csv", tournament.csv);
        vivae_lab::output_path::check_output(&csv, args.force)?;
    }
    let tables = (tournament.play)(&args.a, &args.b, args.threads.threads.unwrap_or(0))?;
    if let Some(path) = &args.csv {
        vivae_lab::io::write_atomic(path, tables.csv.as_bytes())?;
    }
    print!("{}", tables.table);
    Ok(ExitCode::SUCCESS)
}

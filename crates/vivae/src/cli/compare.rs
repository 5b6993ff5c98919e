//! `vivae compare`: several runs side by side, as a figure and a table (see
//! `crate::figures::compare`).

use std::path::PathBuf;
use std::process::ExitCode;

use crate::figures::compare::{CompareOptions, LabelRule};
use clap::Args;

/// Options of `vivae compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Run directories (several seeds per group; a run still evolving is read as far as it got).
    #[arg(required = true, value_name = "RUN_DIR")]
    pub runs: Vec<PathBuf>,
    /// Group the runs whose path or folder name matches GLOB (`*`, `?`) as NAME,
    /// e.g. --label 'camera=runs/cam16-s*'; repeatable, the first match wins.
    /// Other runs are grouped by their substrate (e.g. 3x5→3x3), or by task
    /// and strategy for a task without one (e.g. cartpole (neat)).
    #[arg(long, value_name = "NAME=GLOB")]
    pub label: Vec<LabelRule>,
    /// The figure: a .png or .svg file.
    #[arg(short, long, value_name = "OUT")]
    pub out: PathBuf,
    /// Also write the table as CSV to this file.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Figure title.
    #[arg(long, value_name = "TEXT", default_value_t = CompareOptions::default().title)]
    pub title: String,
}

/// Runs `vivae compare`: the figure (and CSV) written, the table on stdout.
pub fn run(args: CompareArgs) -> anyhow::Result<ExitCode> {
    let options = CompareOptions {
        title: args.title,
        ..CompareOptions::default()
    };
    let table = crate::figures::compare::run(
        &args.runs,
        &args.label,
        &args.out,
        args.csv.as_deref(),
        &options,
    )?;
    print!("{table}");
    eprintln!("figure: {}", args.out.display());
    Ok(ExitCode::SUCCESS)
}

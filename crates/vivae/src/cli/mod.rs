//! The command line: one file per command, each with its options (`…Args`)
//! and its `run`, which [`program`] calls.
//!
//! Options that several commands take are declared once, in [`args`], and
//! flattened into each command's options; [`overrides`] maps the options that
//! stand for config keys onto a config. The evolving commands (`evolve`,
//! `resume`, `retrain`) prepare a run, join an MPI job if launched under one
//! ([`mpi_job`]), and hand the run to [`drive`], which runs it and prints what
//! [`terminal`] words for a person at the terminal.

pub mod args;
pub mod compare;
pub mod config;
pub mod drive;
pub mod drive_image;
pub mod evolve;
pub mod export;
pub mod help_reference;
pub mod mpi_job;
pub mod overrides;
pub mod own_driver;
pub mod program;
pub mod replay;
pub mod report;
pub mod reproduce;
pub mod resume;
pub mod retrain;
pub mod scenario;
pub mod terminal;
pub mod tournament;
pub mod view;

use std::path::PathBuf;

use clap::{Parser, Subcommand};

// Public so that tests parse the commands of the docs with it (user_docs_are_current_and_linked).
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
pub struct Cli {
    // (no doc comment: clap would print it in the help)
    #[command(subcommand)]
    pub command: Command,
}

/// The commands of `vivae`, one file of this module each.
#[derive(Subcommand, Debug)]
pub enum Command {
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

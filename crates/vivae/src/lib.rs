//! The `vivae` program's own parts: figures, the run report, the live viewer
//! and distributed (MPI) evaluation, on top of the [`vivae_lab`] experiment
//! library. The command line is [`cli`] (one file per command), which the
//! program's `main.rs` runs with [`run_cli`]; a crate of one's own that
//! registers its own tasks or strategies first runs it the same way.
//!
//! Everything a researcher builds on (the experiment, configs, run
//! directories) is in `vivae_lab`, which has none of this crate's
//! dependencies (plotting, web server, command line, MPI). Drawing a run's
//! convergence figure from its numbers:
//!
//! ```
//! use vivae::figures::convergence::{ConvergenceOptions, render};
//!
//! // Every individual's fitness, per generation.
//! let generations = vec![vec![1.0, 0.5, 0.2], vec![2.0, 1.0, 0.4], vec![2.5, 1.5, 0.9]];
//! let figure = render(&generations, &ConvergenceOptions::default())?;
//! assert!(figure.svg.contains("<svg") && figure.png.starts_with(b"\x89PNG"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// The program needs the viewer (its `view` command); the Python module builds without it.
// The options' doc comments are the program's `--help` text, plain text rather than
// Markdown (`[physics]`, `runs/<timestamp>`), so rustdoc's Markdown lints do not apply.
#[cfg(feature = "viewer")]
#[allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]
pub mod cli;
pub mod figures;
#[cfg(feature = "mpi")]
pub mod mpi;
// With the program's command line: the Python module (no viewer) has its own copy.
#[cfg(feature = "viewer")]
pub mod portable_libm;
pub mod report;
pub mod report_html;
pub mod tasks;
#[cfg(feature = "viewer")]
pub mod view;

#[cfg(feature = "viewer")]
pub use cli::program::{run_cli, run_cli_from};

/// A figure that cannot be drawn is an output the program could not make.
impl From<figures::FigureError> for vivae_lab::Error {
    fn from(e: figures::FigureError) -> Self {
        vivae_lab::Error::Output(e.to_string())
    }
}

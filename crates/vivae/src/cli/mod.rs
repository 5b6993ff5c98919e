//! The command line: one file per command, each with its options (`…Args`)
//! and its `run`, which `main.rs` calls.
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
pub mod replay;
pub mod report;
pub mod reproduce;
pub mod resume;
pub mod retrain;
pub mod scenario;
pub mod terminal;
pub mod tournament;
pub mod view;

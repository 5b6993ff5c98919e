//! The vivae experiments: HyperNEAT-controlled robots learning to drive in ViVAE.
//!
//! `vivae-neat` evolves CPPNs and decodes substrates, `vivae-sim` simulates the
//! world; this crate joins them ([`experiment`]), drives evolution with
//! checkpoints ([`evolve`]), owns every file format and all I/O ([`config`],
//! [`io`]) and draws the paper's figures ([`figures`], [`report`]).

pub mod config;
pub mod evolve;
pub mod experiment;
pub mod figures;
pub mod io;
pub mod report;
pub mod sensors;
pub mod substrate;

/// The architecture page (docs/architecture.md): its examples are compiled and run as doctests.
#[doc = include_str!("../../../docs/architecture.md")]
pub mod architecture {}

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
pub mod report_html;
pub mod substrate;
pub mod view;

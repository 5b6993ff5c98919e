//! The vivae experiments: HyperNEAT-controlled robots learning to drive in ViVAE.
//!
//! `vivae-neat` evolves CPPNs and decodes substrates, `vivae-sim` simulates the
//! world; this crate joins them ([`experiment`]), drives evolution with
//! checkpoints ([`evolve`]), owns every file format and all I/O ([`config`],
//! [`io`]) and draws the paper's figures ([`figures`], [`report`]). Every
//! fallible function returns the typed [`Error`], which says whether the
//! user's input was at fault.
//!
//! The driving experiment as a library: evaluate a random CPPN on the
//! embedded road scenario (docs/architecture.md shows how to add a task,
//! a sensor or an observer).
//!
//! ```
//! use vivae::config::Config;
//! use vivae::experiment::Experiment;
//! use vivae_neat::Population;
//! use vivae_sim::{LoadOptions, Scenario};
//!
//! let config = Config::default(); // the paper's setup: 3×5 sensors, 3×3 neurons, 5 robots
//! let scenario = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default())?;
//! let experiment = Experiment::new(&config, &scenario)?;
//! let population = Population::new(config.neat.clone(), experiment.cppn_spec(), 1)?;
//! let controller = experiment.controller(&population.genomes()[0])?;
//! let episode = experiment.run(&controller, true);
//! println!("{:.3} px/step, {:.0}% on road", episode.fitness, 100.0 * episode.on_road.unwrap());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod behaviour;
pub mod config;
pub mod error;
pub mod evolve;
pub mod experiment;
pub mod figures;
pub mod io;
pub mod maps;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod normalize;
pub mod report;
pub mod report_html;
pub mod sensors;
pub mod shipped;
pub mod simd;
pub mod substrate;
pub mod training;
pub mod view;

pub use error::{Error, Result};

/// The architecture page (docs/architecture.md): its examples are compiled and run as doctests.
#[doc = include_str!("../../../docs/architecture.md")]
pub mod architecture {}

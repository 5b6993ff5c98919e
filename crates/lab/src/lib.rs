//! The vivae experiment library: HyperNEAT-controlled robots learning to drive in ViVAE.
//!
//! `vivae-neat` evolves CPPNs and decodes substrates, `vivae-sim` simulates the
//! world; this crate joins them in tasks ([`tasks`]: the driving experiment
//! and others, one folder each), decodes controllers ([`controller`]), drives evolution with a
//! search strategy ([`search`]) and checkpoints ([`run`]), and owns the config
//! and run-directory formats ([`config`], [`rundir`], [`io`]). It has no command line, plotting, web server or MPI
//! in its dependency tree, so that other programs (the `vivae` program, the
//! Python package) can bind it. Every fallible function returns the typed
//! [`Error`], which says whether the user's input was at fault.
//!
//! The driving experiment as a library: evaluate a random CPPN on the
//! embedded road scenario (docs/architecture.md shows how to add a task,
//! a sensor or an observer, and runs a task through [`run::prepare`]).
//!
//! ```
//! use vivae_lab::config::Config;
//! use vivae_lab::tasks::driving::episode::Episode;
//! use vivae_neat::Population;
//! use vivae_sim::{LoadOptions, Scenario};
//!
//! let config = Config::default(); // the paper's setup: 3×5 sensors, 3×3 neurons, 5 robots
//! let scenario = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default())?;
//! let experiment = Episode::new(&config, &scenario)?;
//! let population = Population::new(config.neat.clone(), experiment.cppn_spec(), 1)?;
//! let controller = experiment.controller(&population.genomes()[0])?;
//! let episode = experiment.run(&controller, true);
//! println!("{:.3} px/step, {:.0}% on road", episode.fitness, 100.0 * episode.on_road.unwrap());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod config;
pub mod controller;
pub mod error;
pub mod export;
pub mod io;
pub mod output_path;
pub mod polar;
pub mod reproduce;
pub mod run;
pub mod rundir;
pub mod search;
pub mod shipped;
pub mod simd;
pub mod tasks;

pub use error::{Error, Result};

/// The architecture page (docs/architecture.md): its examples are compiled and run as doctests.
#[doc = include_str!("../../../docs/architecture.md")]
pub mod architecture {}

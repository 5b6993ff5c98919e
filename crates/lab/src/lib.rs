//! The vivae experiment library: HyperNEAT-controlled robots learning to drive in ViVAE.
//!
//! `vivae-neat` evolves CPPNs and decodes substrates, `vivae-sim` simulates the
//! world; this crate joins them ([`experiment`]), drives evolution with
//! checkpoints ([`evolve`]) and owns the config and run-directory formats
//! ([`config`], [`io`]). It has no command line, plotting, web server or MPI
//! in its dependency tree, so that other programs (the `vivae` program, the
//! Python package) can bind it. Every fallible function returns the typed
//! [`Error`], which says whether the user's input was at fault.
//!
//! The driving experiment as a library: evaluate a random CPPN on the
//! embedded road scenario (docs/architecture.md shows how to add a task,
//! a sensor or an observer).
//!
//! ```
//! use vivae_lab::config::Config;
//! use vivae_lab::experiment::Experiment;
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

pub mod config;
pub mod controller;
pub mod error;
pub mod io;
pub mod run;
pub mod rundir;
pub mod search;
pub mod shipped;
pub mod simd;
pub mod tasks;

// The paths of the flat layout, kept while the program and the Python binding move over.
pub use config::{es as es_config, strategy as strategy_config};
pub use controller::{es as es_controller, normalize, polar, sensors, substrate};
pub use run as evolve;
pub use search::files as strategy_files;
pub use tasks as run_task;
pub use tasks::driving::{behaviour, descriptors, experiment, fitness, resolutions, rollout};
pub use tasks::driving::{combined as task, training};
pub use tasks::{maps, maze, maze::run as maze_run};

pub use error::{Error, Result};

/// The architecture page (docs/architecture.md): its examples are compiled and run as doctests.
#[doc = include_str!("../../../docs/architecture.md")]
pub mod architecture {}

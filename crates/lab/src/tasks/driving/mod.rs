//! The driving task: robots on roads, scored by average speed. An
//! [`episode::Episode`] is one episode setup (one map, one resolution,
//! one fitness); [`combined::Combined`] scores several as one;
//! [`training::Training`] is what a run evaluates on (maps × resolutions).

pub mod behaviour;
pub mod combined;
pub mod contacts;
pub mod descriptors;
pub mod episode;
pub mod fitness;
pub mod fitness_contacts;
pub mod fitness_progress;
pub mod meetings;
pub mod placement;
pub mod resolutions;
pub mod rollout;
pub mod run;
pub mod scenarios;
pub mod section;
pub mod substrate;
pub mod training;

pub use run::{TASK, training_of};

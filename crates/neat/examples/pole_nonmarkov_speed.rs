//! The library's double pole task without velocities at a fixed wall-clock
//! length: evaluations and network activations per second, for the side by
//! side with neat-python (`neat_python/efficacy.py pole_nonmarkov`).
//!
//! `cargo run --release -p vivae-neat --example pole_nonmarkov_speed -- --runs 2 --seconds 15 --set add_node_probability=0 --set add_link_probability=0`
//!
//! Physics, start state (the long pole at 4.5°) and Gruau's damping fitness
//! over at most 1,000 steps are `vivae_neat::benchmarks::pole`'s (see
//! `common/pole_task.rs`), parameters its `pole_params(false)` (population
//! 1,000), recurrent networks with 3 inputs and a bias. The library's
//! per-generation champion test (100,000 steps, then 625 generalisation
//! starts) decides when a run is solved, so it is left out: runs never stop.

// Only the command line, overrides and the recurrent helper of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/pole_task.rs"]
mod pole_task;

const TITLE: &str = "Double pole balancing without velocities (speed)";

fn main() {
    pole_task::speed_main("pole_nonmarkov_speed", TITLE, false);
}

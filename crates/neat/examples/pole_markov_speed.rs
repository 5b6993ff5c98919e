//! The library's double pole task with velocities at a fixed wall-clock
//! length: evaluations and network activations per second, for the side by
//! side with neat-python (`neat_python/efficacy.py pole_markov`).
//!
//! `cargo run --release -p vivae-neat --example pole_markov_speed -- --runs 2 --seconds 15 --set add_node_probability=0 --set add_link_probability=0`
//!
//! Physics, start state and fitness (steps balanced, at most 100,000) are
//! `vivae_neat::benchmarks::pole`'s (see `common/pole_task.rs`), parameters
//! its `pole_params(true)` (population 150), feed-forward networks with 6
//! inputs and a bias. Runs never stop at a solution.

// Only the command line, overrides and the recurrent helper of the shared runner are used here.
#[allow(dead_code)]
mod common;
#[path = "common/efficacy.rs"]
mod efficacy;
#[path = "common/pole_task.rs"]
mod pole_task;

const TITLE: &str = "Double pole balancing with velocities (speed)";

fn main() {
    pole_task::speed_main("pole_markov_speed", TITLE, true);
}

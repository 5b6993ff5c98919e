//! One hard-maze episode of 400 steps (the unit of the maze benchmark), to
//! compare with `gymnasium-hardmaze` stepping its hard maze
//! (crates/lab/examples/maze_gym.py): the rangefinders and radar read and
//! the world stepped every step, with a fixed policy (as the Python side)
//! and with a NEAT network deciding; and Lehman's robot, the task's default.

use divan::{Bencher, black_box};
use vivae_lab::tasks::maze::lehman::LehmanTask;
use vivae_lab::tasks::maze::{Maze, MazeModel, MazeTask};
use vivae_neat::{NeatParams, Population};

fn main() {
    divan::main();
}

/// Full speed ahead, no turn: the robot drives into the walls and slides on
/// for all 400 steps (it never reaches the goal, so no episode ends early).
#[divan::bench]
fn hard_maze_fixed_policy_400_steps(bencher: Bencher) {
    let task = MazeTask::shipped(Maze::Hard).unwrap();
    bencher.bench(|| black_box(task.run(|_, o| o.copy_from_slice(&[0.5, 1.0]))));
}

/// One evaluation as evolution runs it: a generation-0 genome's network
/// compiled, then 400 steps (or fewer if it reaches the goal).
#[divan::bench]
fn hard_maze_evaluation_minimal_genome(bencher: Bencher) {
    let task = MazeTask::shipped(Maze::Hard).unwrap();
    let pop = Population::new(NeatParams::plain_neat(), MazeTask::spec(), 1).unwrap();
    let genome = &pop.genomes()[0];
    bencher.bench(|| black_box(task.outcome(black_box(genome))));
}

/// Lehman's robot ([`LehmanTask`], the maze task's default) on his hard
/// maze, full speed ahead with a slight right turn, for all 400 steps.
#[divan::bench]
fn lehman_hard_maze_fixed_policy_400_steps(bencher: Bencher) {
    let task = LehmanTask::shipped(Maze::Hard);
    bencher.bench(|| black_box(task.run(|_, o| o.copy_from_slice(&[0.55, 1.0]))));
}

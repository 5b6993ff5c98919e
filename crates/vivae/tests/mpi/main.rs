//! The tests that launch `vivae` under Open MPI's `mpirun`, in one binary.
//! Cargo.toml declares it with `required-features = ["mpi"]`: a plain
//! `cargo test` does not build it; `.ci/run` runs
//! `cargo test --release -p vivae --features mpi --test mpi`.
//! Each module is one former test file, named for the behaviour it checks.

/// The helpers of the `it` binary (`tests/it/common`), shared.
#[path = "../it/common/mod.rs"]
mod common;
mod mpi_common;
mod mpi_killed_rank_then_resume_matches;
mod mpi_maze_run_equals_single_process_run;
mod mpi_mismatched_rank_is_refused;
mod mpi_multi_map_run_equals_single_process_run;
mod mpi_predator_prey_run_equals_single_process_run;
mod mpi_resume_with_other_rank_count_matches;
mod mpi_runs_equal_single_process_run;
mod mpi_strategy_runs_equal_single_process_run;

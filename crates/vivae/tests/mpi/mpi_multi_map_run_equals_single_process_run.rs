//! A multi-map run (`--scenario A --scenario B`) under `mpirun` writes the
//! files of the single-process run, and resumes under MPI identically.
use crate::common::*;
use crate::mpi_common::*;

const MAPS: [&str; 4] = ["--scenario", "roads", "--scenario", "oval"];

#[test]
fn multi_map_runs_under_mpi_match_the_single_process_run() {
    let dir = scratch("mpi-multi-map");
    let config = write_small_config(&dir, 3);
    let reference = dir.join("reference");
    evolve(&config, &reference, &MAPS);
    let two = dir.join("two");
    mpi_evolve(2, &config, &two, &MAPS);
    assert_same_results(&reference, &two);
    // Stopped after 1 generation, resumed by 2 ranks from the run's copies.
    let resumed = dir.join("resumed");
    mpi_evolve(
        2,
        &config,
        &resumed,
        &[&MAPS[..], &["--generations", "1"]].concat(),
    );
    ok(mpirun(2)
        .args(["resume", "-q", "--threads", "1", "--generations", "3"])
        .arg(&resumed));
    assert_same_results(&reference, &resumed);
    std::fs::remove_dir_all(&dir).unwrap();
}

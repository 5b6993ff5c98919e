//! A run stopped after k generations and resumed (or extended) ends with exactly
//! the files of a run that went straight through.

use crate::common::*;

#[test]
fn extended_run_matches_uninterrupted_run() {
    let dir = scratch("resume-extend");
    let config = write_small_config(&dir, 6);
    let full = dir.join("full");
    evolve(&config, &full, &[]);

    let short = dir.join("short");
    evolve(&config, &short, &["--generations", "3"]);
    ok(vivae()
        .args(["resume", "-q", "--generations", "6"])
        .arg(&short));
    assert_same_results(&full, &short);
    // The resolved config of the extended run equals the uninterrupted run's.
    assert_eq!(read(&full, "config.toml"), read(&short, "config.toml"));

    // And the resolved config reproduces the run bit for bit.
    let again = dir.join("again");
    ok(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(full.join("config.toml"))
        .arg("--out")
        .arg(&again));
    assert_same_results(&full, &again);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn resume_refuses_to_shrink_a_run() {
    let dir = scratch("resume-shrink");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "1"])
        .arg(&run_dir));
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Step counts that validate as numbers but could never finish (or would
//! fill memory with trajectories) are refused with exit 2 and one line,
//! before any output is written, in `evolve` and in `replay`.

use crate::common::*;

#[test]
fn absurd_step_counts_are_refused_before_any_output() {
    let dir = scratch("too-big");
    let out_dir = dir.join("out");
    let out = run(vivae()
        .args(["evolve", "-q", "--steps", "4294967295", "--out"])
        .arg(&out_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("steps"), "{stderr}");
    assert!(!out_dir.exists(), "evolve left a run directory");

    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let replay_dir = dir.join("replay");
    let out = run(vivae()
        .arg("replay")
        .arg(run_dir.join("champion.json"))
        .args(["--steps", "4294967295", "-o"])
        .arg(&replay_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("steps"), "{stderr}");
    assert!(!replay_dir.exists(), "replay wrote output");
    std::fs::remove_dir_all(&dir).unwrap();
}

//! SIGTERM (what `kill` and service managers send) behaves like Ctrl-C: the
//! current generation finishes, a checkpoint is written, exit code 130, and
//! the run resumes.

use crate::common::*;

#[test]
fn sigterm_checkpoints_then_resumes() {
    let dir = scratch("sigterm");
    let config = write_small_config(&dir, 100_000);
    let run_dir = dir.join("run");
    let out = evolve_until_signalled(&config, &run_dir, 1, "-TERM");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "stderr: {stderr}");
    assert!(stderr.contains("vivae resume"), "stderr: {stderr}");
    let rows = String::from_utf8(read(&run_dir, "generations.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    // The interrupted generation was finished and checkpointed.
    let ckpt = run_dir.join(format!("checkpoints/gen-{rows:06}.ckpt"));
    assert!(ckpt.exists(), "no checkpoint for generation {rows}");
    ok(vivae()
        .args(["resume", "-q", "--generations", &(rows + 1).to_string()])
        .arg(&run_dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

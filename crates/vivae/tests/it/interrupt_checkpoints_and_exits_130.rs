//! Ctrl-C (SIGINT) finishes the current generation, writes a checkpoint, says
//! how to resume, draws the figures so far and exits 130; resuming then
//! matches an uninterrupted run.

use crate::common::*;

const GENERATIONS: u32 = 150;

#[test]
fn sigint_then_resume_matches() {
    let dir = scratch("sigint");
    let config = dir.join("c.toml");
    // Long enough (about a second) that the interrupt lands well before the end.
    std::fs::write(&config, small_config(GENERATIONS)).unwrap();
    let reference = dir.join("reference");
    evolve(&config, &reference, &[]);

    let run_dir = dir.join("interrupted");
    let out = evolve_until_signalled(&config, &run_dir, 2, "-INT");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "stderr: {stderr}");
    assert!(stderr.contains("vivae resume"), "stderr: {stderr}");
    let csv = String::from_utf8(read(&run_dir, "generations.csv")).unwrap();
    assert!(
        csv.lines().count() < 1 + GENERATIONS as usize,
        "the run stopped early"
    );
    // The figures show the run up to its last generation.
    for f in [
        "trajectories-champion.png",
        "convergence.png",
        "network.png",
    ] {
        assert!(run_dir.join("figures").join(f).exists(), "missing {f}");
    }
    ok(vivae().args(["resume", "-q"]).arg(&run_dir));
    assert_same_results(&reference, &run_dir);
    std::fs::remove_dir_all(&dir).unwrap();
}

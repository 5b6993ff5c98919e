//! Ctrl-C (SIGINT) finishes the current generation, writes a checkpoint, says
//! how to resume, draws the figures so far and exits 130; resuming then
//! matches an uninterrupted run.

mod common;
use common::*;
use std::time::{Duration, Instant};

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
    let child = vivae()
        .args(["evolve", "-q", "--threads", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&run_dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(120);
    while !run_dir.join("checkpoints/gen-000002.ckpt").exists() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(2));
    }
    let status = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
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

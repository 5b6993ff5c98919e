//! A corrupt, truncated or foreign checkpoint stops `resume` with exit 2 and a
//! one-line message naming it, and the run directory is left untouched.

use crate::common::*;
use std::path::Path;

fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = [
        "generations.csv",
        "population.csv",
        "champion.json",
        "config.toml",
    ]
    .iter()
    .map(|n| (n.to_string(), read(dir, n)))
    .collect();
    files.sort();
    files
}

#[test]
fn damaged_checkpoints_are_refused_without_touching_the_run() {
    let dir = scratch("corrupt-ckpt");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let ckpt = run_dir.join("checkpoints/gen-000002.ckpt");
    let good = std::fs::read(&ckpt).unwrap();
    let before = snapshot(&run_dir);

    let truncated = good[..good.len() / 2].to_vec();
    let mut flipped = good.clone();
    let at = flipped.len() - 50;
    flipped[at] ^= 0x01;
    let foreign = b"{\"generation\": 3, \"population\": []}".to_vec();
    for (what, bytes) in [
        ("truncated", truncated),
        ("bit flip", flipped),
        ("foreign", foreign),
        ("empty", Vec::new()),
    ] {
        std::fs::write(&ckpt, &bytes).unwrap();
        let out = run(vivae()
            .args(["resume", "-q", "--generations", "3"])
            .arg(&run_dir));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{what}: {stderr}");
        assert!(stderr.contains("gen-000002.ckpt"), "{what}: {stderr}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert_eq!(snapshot(&run_dir), before, "{what}: run directory changed");
        assert_eq!(
            std::fs::read(&ckpt).unwrap(),
            bytes,
            "{what}: checkpoint overwritten"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn existing_output_directory_needs_force() {
    let dir = scratch("force");
    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let before = read(&run_dir, "generations.csv");
    let out = run(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&run_dir));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
    assert_eq!(read(&run_dir, "generations.csv"), before);
    evolve(&config, &run_dir, &["--force"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

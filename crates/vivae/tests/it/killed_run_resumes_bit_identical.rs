//! A run killed with SIGKILL at any moment resumes, losing at most the current
//! generation, and still ends with the files of an uninterrupted run.

use crate::common::*;
use std::path::Path;
use std::time::{Duration, Instant};

const GENERATIONS: u32 = 8;

fn checkpoints(run_dir: &Path) -> usize {
    std::fs::read_dir(run_dir.join("checkpoints"))
        .map(|d| {
            d.filter_map(|e| e.ok())
                .filter(|e| e.file_name().to_string_lossy().ends_with(".ckpt"))
                .count()
        })
        .unwrap_or(0)
}

fn newest_generation(run_dir: &Path) -> Option<u32> {
    let mut names: Vec<String> = std::fs::read_dir(run_dir.join("checkpoints"))
        .ok()?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("gen-") && n.ends_with(".ckpt"))
        .collect();
    names.sort();
    names
        .pop()?
        .trim_start_matches("gen-")
        .trim_end_matches(".ckpt")
        .parse()
        .ok()
}

#[test]
fn sigkill_at_several_points_then_resume_matches() {
    let dir = scratch("sigkill");
    let config = write_small_config(&dir, GENERATIONS);
    let reference = dir.join("reference");
    evolve(&config, &reference, &[]);

    // Kill once a given generation's checkpoint exists, and once after a bare delay
    // (anywhere: even while a file is being written).
    let kill_points: [(Option<u32>, u64); 4] =
        [(Some(1), 0), (Some(4), 3), (None, 150), (Some(6), 1)];
    for (i, (after_generation, extra_ms)) in kill_points.into_iter().enumerate() {
        let run_dir = dir.join(format!("killed-{i}"));
        let mut child = vivae()
            .args(["evolve", "-q", "--threads", "1", "--config"])
            .arg(&config)
            .arg("--out")
            .arg(&run_dir)
            .spawn()
            .unwrap();
        let deadline = Instant::now() + Duration::from_secs(120);
        if let Some(g) = after_generation {
            while newest_generation(&run_dir).is_none_or(|n| n < g) && Instant::now() < deadline {
                if child.try_wait().unwrap().is_some() {
                    break;
                }
                std::thread::sleep(Duration::from_millis(2));
            }
        } else {
            // Wait until the run directory has its first checkpoint, then a while longer.
            while checkpoints(&run_dir) == 0 && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(2));
            }
        }
        std::thread::sleep(Duration::from_millis(extra_ms));
        child.kill().unwrap(); // SIGKILL on Unix
        child.wait().unwrap();
        ok(vivae().args(["resume", "-q"]).arg(&run_dir));
        assert_same_results(&reference, &run_dir);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

//! A worker rank killed mid-run ends the job with a message naming the rank;
//! the last checkpoint is intact and `vivae resume` (with or without MPI)
//! ends with the files of an uninterrupted run.
use crate::common::*;
use crate::mpi_common::*;
use std::path::Path;
use std::time::{Duration, Instant};

const GENERATIONS: u32 = 60;

/// The newest checkpoint's generation, if any.
fn newest_generation(run_dir: &Path) -> Option<u32> {
    std::fs::read_dir(run_dir.join("checkpoints"))
        .ok()?
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.strip_prefix("gen-")?
                .strip_suffix(".ckpt")?
                .parse()
                .ok()
        })
        .max()
}

/// Process ids of the processes that descend from `ancestor` and run as MPI rank `rank`.
fn pids_of_rank(ancestor: u32, rank: u32) -> Vec<u32> {
    let parent = |pid: u32| -> Option<u32> {
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
        // The field after the parenthesised command name.
        stat.rsplit_once(')')?
            .1
            .split_whitespace()
            .nth(1)?
            .parse()
            .ok()
    };
    let wanted = format!("OMPI_COMM_WORLD_RANK={rank}");
    std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|&pid| {
            let mut p = pid;
            for _ in 0..4 {
                match parent(p) {
                    Some(q) if q == ancestor => return true,
                    Some(q) if q > 1 => p = q,
                    _ => return false,
                }
            }
            false
        })
        .filter(|pid| {
            std::fs::read(format!("/proc/{pid}/environ"))
                .map(|env| env.split(|&b| b == 0).any(|v| v == wanted.as_bytes()))
                .unwrap_or(false)
        })
        .collect()
}

/// Starts a 3-rank run, kills rank `victim` once generation 2 is checkpointed;
/// returns mpirun's stderr.
fn run_and_kill_rank(config: &Path, run_dir: &Path, victim: u32) -> String {
    let child = mpirun(3)
        .args(["evolve", "-q", "--threads", "1", "--config"])
        .arg(config)
        .arg("--out")
        .arg(run_dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // A generous bound so a broken build fails instead of hanging.
    let deadline = Instant::now() + Duration::from_secs(300);
    while newest_generation(run_dir).is_none_or(|g| g < 2) && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(2));
    }
    let pids = pids_of_rank(child.id(), victim);
    assert_eq!(pids.len(), 1, "rank {victim}: {pids:?}");
    let status = std::process::Command::new("kill")
        .args(["-KILL", &pids[0].to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !out.status.success(),
        "the job went on without rank {victim}"
    );
    stderr
}

#[test]
fn killed_worker_rank_then_resume_matches() {
    let dir = scratch("mpi-killed");
    // Longer episodes than the other tests': generations must outlast finding and killing a rank.
    let config = dir.join("c.toml");
    std::fs::write(
        &config,
        small_config(GENERATIONS).replace("steps = 150", "steps = 400"),
    )
    .unwrap();
    let reference = dir.join("reference");
    evolve(&config, &reference, &[]);

    for (victim, resume_ranks) in [(1, None), (2, Some(2))] {
        let run_dir = dir.join(format!("killed-rank-{victim}"));
        let stderr = run_and_kill_rank(&config, &run_dir, victim);
        assert!(
            stderr.contains(&format!("rank {victim}")),
            "the message does not name rank {victim}: {stderr}"
        );
        assert!(
            newest_generation(&run_dir).is_some_and(|g| g < GENERATIONS),
            "the run finished before rank {victim} was killed"
        );
        let mut resume = match resume_ranks {
            Some(n) => mpirun(n),
            None => vivae(),
        };
        ok(resume
            .args(["resume", "-q", "--threads", "1"])
            .arg(&run_dir));
        assert_same_results(&reference, &run_dir);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

//! A run directory is locked by the process writing it: a `resume` while the
//! run is still going is refused with exit 2 and one line, and writes nothing;
//! once the writer is gone (killed, so the lock is released by the OS) the
//! run resumes.

use crate::common::*;

#[test]
fn resume_while_the_run_is_going_is_refused() {
    let dir = scratch("lock");
    // Far more generations than the test waits for: the first writer is killed.
    let config = write_small_config(&dir, 100_000);
    let run_dir = dir.join("run");
    let mut first = vivae()
        .args(["evolve", "-q", "--threads", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&run_dir)
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    wait_for_file(&run_dir.join("checkpoints/gen-000001.ckpt"), 300);
    let out = run(vivae()
        .args(["resume", "-q", "--threads", "1"])
        .arg(&run_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("another vivae process"), "{stderr}");
    assert!(stderr.contains("run"), "{stderr}");

    first.kill().unwrap();
    first.wait().unwrap();
    // The lock died with its process: the newest checkpoint resumes (to itself).
    let newest = std::fs::read_dir(run_dir.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("gen-") && n.ends_with(".ckpt"))
        .max()
        .unwrap();
    let done: u32 = newest["gen-".len()..newest.len() - ".ckpt".len()]
        .parse()
        .unwrap();
    ok(vivae()
        .args(["resume", "-q", "--generations", &done.max(1).to_string()])
        .arg(&run_dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Temporary files a killed process left behind (`.NAME.tmp-PID`, written
//! before an atomic rename) are removed by `resume`, and nothing else is.

mod common;
use common::*;

#[test]
fn resume_removes_temporary_files_of_a_killed_process() {
    let dir = scratch("stale-tmp");
    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let stale = [
        run_dir.join(".champion.json.tmp-999999"),
        run_dir.join("checkpoints/.gen-000002.ckpt.tmp-999999"),
        run_dir.join("figures/.network.png.tmp-999999"),
    ];
    for p in &stale {
        std::fs::write(p, b"half written").unwrap();
    }
    let keep = run_dir.join("notes.txt");
    std::fs::write(&keep, b"mine").unwrap();
    ok(vivae()
        .args(["resume", "-q", "--generations", "2"])
        .arg(&run_dir));
    for p in &stale {
        assert!(!p.exists(), "{} left behind", p.display());
    }
    assert!(keep.exists(), "a file of the user's was removed");
    std::fs::remove_dir_all(&dir).unwrap();
}

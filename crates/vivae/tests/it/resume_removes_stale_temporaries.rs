//! Temporary files a killed process left behind (`.NAME.tmp-PID`, written
//! before an atomic rename) are removed by `resume`, and nothing else is.

use crate::common::*;

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

/// A run killed before its first checkpoint leaves its hidden build folder
/// (`.DIR.tmp-PID`); the next run of that directory removes it, but never the
/// folder of a process that is still alive.
#[test]
fn a_new_run_removes_build_folders_of_killed_runs() {
    let dir = scratch("stale-build");
    let config = write_small_config(&dir, 1);
    let dead = dir.join(".run.tmp-999999");
    let alive = dir.join(format!(".run.tmp-{}", std::process::id()));
    for d in [&dead, &alive] {
        std::fs::create_dir_all(d.join("checkpoints")).unwrap();
        std::fs::write(d.join("config.toml"), b"half").unwrap();
    }
    let other = dir.join(".other.tmp-999999");
    std::fs::create_dir(&other).unwrap();
    evolve(&config, &dir.join("run"), &[]);
    assert!(!dead.exists(), "the killed run's build folder is left");
    assert!(alive.exists(), "a live process's build folder was removed");
    assert!(other.exists(), "another run's folder was touched");
    std::fs::remove_dir_all(&dir).unwrap();
}

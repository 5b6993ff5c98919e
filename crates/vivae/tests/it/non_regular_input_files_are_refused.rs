//! Inputs that are not regular files — a FIFO, `/dev/zero` or `/dev/urandom`
//! directly or through a symlink, a directory — are refused at once with exit
//! code 2 and one line naming the file, instead of blocking forever or being
//! read until memory runs out; so is a file over the size limit.

use crate::common::*;
use std::process::Command;

fn assert_refused(cmd: &mut Command, name: &str, what: &str) {
    let out = run(cmd);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{what}: {stderr}");
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{what}: {stderr}");
    assert!(stderr.contains(name), "{what}: {stderr}");
}

#[test]
fn fifos_devices_and_huge_files_are_refused() {
    let dir = scratch("non-regular");
    let fifo = dir.join("pipe.svg");
    mkfifo(&fifo);
    let zero = dir.join("zero.svg");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let urandom = dir.join("random.json");
    std::os::unix::fs::symlink("/dev/urandom", &urandom).unwrap();
    let fifo_toml = dir.join("pipe.toml");
    mkfifo(&fifo_toml);
    let fifo_json = dir.join("pipe.json");
    mkfifo(&fifo_json);
    // Sparse: 100 MiB on disk costs nothing.
    let huge = dir.join("huge.svg");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(100 << 20)
        .unwrap();
    let out = dir.join("out");

    for (path, what) in [
        (&fifo, "FIFO scenario"),
        (&zero, "symlink to /dev/zero as scenario"),
        (&huge, "100 MiB scenario"),
    ] {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert_refused(
            vivae()
                .args(["evolve", "-q", "--scenario"])
                .arg(path)
                .arg("--out")
                .arg(&out),
            &name,
            what,
        );
        assert!(!out.exists(), "{what}: output written");
    }
    assert_refused(
        vivae()
            .args(["evolve", "-q", "--config"])
            .arg(&fifo_toml)
            .arg("--out")
            .arg(&out),
        "pipe.toml",
        "FIFO config",
    );
    assert_refused(
        vivae()
            .args(["evolve", "-q", "--scenario", "/dev/urandom", "--out"])
            .arg(&out),
        "/dev/urandom",
        "/dev/urandom as scenario",
    );
    for (path, what) in [(&fifo_json, "FIFO genome"), (&urandom, "urandom genome")] {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert_refused(
            vivae().arg("replay").arg(path).arg("-o").arg(&out),
            &name,
            what,
        );
    }
    assert!(!out.exists(), "output written");

    // A FIFO in place of the newest checkpoint.
    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let ckpt = run_dir.join("checkpoints/gen-000001.ckpt");
    std::fs::remove_file(&ckpt).unwrap();
    mkfifo(&ckpt);
    assert_refused(
        vivae()
            .args(["resume", "-q", "--generations", "2"])
            .arg(&run_dir),
        "gen-000001.ckpt",
        "FIFO checkpoint",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `vivae resume` on a finished run says it is finished and changes nothing;
//! `vivae retrain --neurons` alone keeps the run's sensors.

use crate::common::*;

#[test]
fn resume_of_finished_run_says_so() {
    let dir = scratch("resume-finished");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let before = read(&run_dir, "generations.csv");
    let out = run(vivae().arg("resume").arg(&run_dir));
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("already finished"), "{err}");
    assert!(err.contains("--generations"), "{err}");
    assert_eq!(before, read(&run_dir, "generations.csv"));

    let retrained = dir.join("retrained");
    ok(vivae()
        .arg("retrain")
        .arg(&run_dir)
        .args(["--neurons", "2x4", "--generations", "1", "-q", "--out"])
        .arg(&retrained));
    let resolved = String::from_utf8(read(&retrained, "config.toml")).unwrap();
    assert!(resolved.contains("neurons = \"2x4\""), "{resolved}");
    assert!(resolved.contains("angles = 5"), "{resolved}");
    // Neither flag is refused with a message naming both.
    let out = run(vivae()
        .arg("retrain")
        .arg(&run_dir)
        .args(["--generations", "1"]));
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

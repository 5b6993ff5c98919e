//! A run killed after its last generation was written but before its figures
//! and `report.html` were redrawn (issue 24) is not "already finished" with
//! an old report: `vivae resume` redraws them, and only then.

use std::path::Path;

use crate::common::*;

/// Copies the files of `from` (one level deep) into `to`, replacing `to`.
fn copy_dir(from: &Path, to: &Path) {
    let _ = std::fs::remove_dir_all(to);
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn resume_redraws_figures_and_report_older_than_the_results() {
    let dir = scratch("stale-report");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    // The figures and report of 2 generations, as a crash would leave them.
    let old_figures = dir.join("old-figures");
    copy_dir(&run_dir.join("figures"), &old_figures);
    let old_report = read(&run_dir, "report.html");
    ok(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&run_dir));
    let new_report = read(&run_dir, "report.html");
    let new_convergence = read(&run_dir, "figures/convergence.svg");
    assert_ne!(old_report, new_report);
    // kill -9 between the last generation and the drawing: results of 3
    // generations, figures and report of 2.
    copy_dir(&old_figures, &run_dir.join("figures"));
    std::fs::write(run_dir.join("report.html"), &old_report).unwrap();
    let champion = read(&run_dir, "champion.json");
    let out = run(vivae().arg("resume").arg(&run_dir));
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("already finished (3 of 3"), "{err}");
    assert!(err.contains("report: "), "{err}");
    assert!(
        read(&run_dir, "report.html") == new_report,
        "report.html not redrawn"
    );
    assert!(read(&run_dir, "figures/convergence.svg") == new_convergence);
    assert_eq!(champion, read(&run_dir, "champion.json"));
    // Killed while drawing (the record of what is drawn already gone): redrawn too.
    std::fs::remove_file(run_dir.join("figures/drawn-generations.txt")).unwrap();
    std::fs::remove_file(run_dir.join("report.html")).unwrap();
    let out = run(vivae().arg("resume").arg(&run_dir));
    assert_eq!(out.status.code(), Some(0));
    assert!(read(&run_dir, "report.html") == new_report);
    // Once drawn, a finished run is left as it is.
    let out = run(vivae().arg("resume").arg(&run_dir));
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("report: "), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

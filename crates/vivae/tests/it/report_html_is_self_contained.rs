//! Every run writes `report.html`; `vivae report` rebuilds the same file; it
//! asks no other host for anything; bad run directories are exit 2.

use crate::common;

use crate::common::{evolve, read, scratch, vivae, write_small_config};

#[test]
fn a_run_writes_report_html_and_vivae_report_rebuilds_it() {
    let dir = scratch("report-html");
    let config = write_small_config(&dir, 10);
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    let first = read(&run, "report.html");
    let html = String::from_utf8(first.clone()).unwrap();
    assert!(html.len() < 5 << 20);
    for part in [
        "Champion (generation",
        "Best of generation 1",
        "Best of generation 10",
        "\"generations\":[{\"generation\":1",
        "\"species\":[[[",
        "<svg",
    ] {
        assert!(html.contains(part), "report.html lacks {part}");
    }
    // Nothing is loaded from elsewhere: no src/href/url() to any host.
    let lower = html.to_ascii_lowercase();
    for needle in [
        "src=\"http",
        "href=\"http",
        "url(http",
        "src='http",
        "@import",
    ] {
        assert!(!lower.contains(needle), "report.html has {needle}");
    }
    std::fs::remove_file(run.join("report.html")).unwrap();
    let out = common::run(vivae().arg("report").arg(&run));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        read(&run, "report.html") == first,
        "vivae report wrote a different report.html"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn report_of_a_non_run_is_one_line_and_exit_2() {
    let dir = scratch("report-bad");
    let out = common::run(vivae().arg("report").arg(dir.join("nothing")));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(!dir.join("nothing").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

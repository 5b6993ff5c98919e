//! `vivae view` serves a run file only if it is a regular file inside the run
//! directory: a symlink out of it (`population.csv → /etc/passwd`), a link to
//! `/dev/zero` or a FIFO in a listed name is refused (403 or 404), promptly,
//! while the run's ordinary files are still served.

use crate::common;
use crate::common::browser::{Viewer, http};
use crate::common::{scratch, write_small_config};

#[test]
fn links_out_of_the_run_and_special_files_are_refused() {
    let dir = scratch("view-links");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    common::evolve(&config, &run, &[]);
    let population = run.join("population.csv");
    std::fs::remove_file(&population).unwrap();
    std::os::unix::fs::symlink("/etc/passwd", &population).unwrap();
    let report = run.join("report.html");
    let _ = std::fs::remove_file(&report);
    std::os::unix::fs::symlink("/dev/zero", &report).unwrap();
    let best = run.join("best-genomes.jsonl");
    std::fs::remove_file(&best).unwrap();
    common::mkfifo(&best);
    // A link that stays inside the run directory is fine.
    let champion = run.join("champion.json");
    std::fs::rename(&champion, run.join("champion-copy.json")).unwrap();
    std::os::unix::fs::symlink("champion-copy.json", &champion).unwrap();

    let v = Viewer::start(&[run.as_os_str()]);
    for refused in [
        "/run/population.csv",
        "/run/report.html",
        "/run/best-genomes.jsonl",
    ] {
        let r = http(v.port, "GET", refused, None);
        assert!(
            r.status == 403 || r.status == 404,
            "{refused} gave {}",
            r.status
        );
        assert!(!String::from_utf8_lossy(&r.body).contains("root:"));
    }
    for ok in [
        "/run/config.toml",
        "/run/champion.json",
        "/run/generations.csv",
    ] {
        let r = http(v.port, "GET", ok, None);
        assert_eq!(r.status, 200, "{ok}");
        assert!(!r.body.is_empty(), "{ok}");
    }
    let served = http(v.port, "GET", "/run/config.toml", None).body;
    assert_eq!(served, std::fs::read(run.join("config.toml")).unwrap());
    drop(v);
    let _ = std::fs::remove_dir_all(&dir);
}

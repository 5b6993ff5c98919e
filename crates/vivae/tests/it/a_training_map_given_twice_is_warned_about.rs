//! A training map given twice (by name or as two files with the same text)
//! is trained on twice and counts double in the mean fitness: `evolve` says
//! so in one warning line per extra copy, and still runs, as asked.

use crate::common::*;

#[test]
fn the_same_map_twice_gets_one_warning_line() {
    let dir = scratch("map-twice");
    let config = write_small_config(&dir, 1);
    let copy = dir.join("my-oval.svg");
    std::fs::write(
        &copy,
        vivae_lab::tasks::scenarios::find("oval").unwrap().svg,
    )
    .unwrap();
    let out = run(vivae()
        .args(["evolve", "-q", "--steps", "20"])
        .args(["--scenario", "oval", "--scenario", "roads", "--scenario"])
        .arg(&copy)
        .arg("--config")
        .arg(&config)
        .arg("--out")
        .arg(dir.join("run")));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].contains("training maps 1 (oval.svg (shipped)) and 3 (")
            && warnings[0].contains("my-oval.svg) are the same map"),
        "{stderr}"
    );

    // Different maps: no warning.
    let out = run(vivae()
        .args(["evolve", "-q", "--steps", "20"])
        .args(["--scenario", "oval", "--scenario", "roads"])
        .arg("--config")
        .arg(&config)
        .arg("--out")
        .arg(dir.join("run2")));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("warning:"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

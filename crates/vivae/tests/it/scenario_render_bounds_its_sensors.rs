//! `vivae scenario render --sensors` is held to the sensor limit of an
//! evolving run (`config::MAX_SENSORS`, 65 536): 1000x1000 used to run for
//! tens of seconds and gigabytes (issue 24); now it is refused at once with
//! exit 2, one line, and nothing written.

use crate::common::*;

#[test]
fn too_many_sensors_are_refused_with_one_line() {
    let dir = scratch("render-sensors");
    for (grid, ext) in [("1000x1000", "png"), ("257x256", "svg")] {
        let out = dir.join(format!("s.{ext}"));
        let result = run(vivae()
            .args(["scenario", "render", "--sensors", grid, "-o"])
            .arg(&out));
        let err = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{grid}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("--sensors") && err.contains("65536"), "{err}");
        assert!(!out.exists());
    }
    let out = dir.join("ok.png");
    ok(vivae()
        .args(["scenario", "render", "--sensors", "3x5", "-o"])
        .arg(&out));
    assert!(out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Step counts that validate as numbers but could never finish (or would
//! fill memory with trajectories) are refused with exit 2 and one line,
//! before any output is written, in `evolve` and in `replay`.

use crate::common::*;

#[test]
fn absurd_step_counts_are_refused_before_any_output() {
    let dir = scratch("too-big");
    let out_dir = dir.join("out");
    let out = run(vivae()
        .args(["evolve", "-q", "--steps", "4294967295", "--out"])
        .arg(&out_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("steps"), "{stderr}");
    assert!(!out_dir.exists(), "evolve left a run directory");

    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let replay_dir = dir.join("replay");
    let out = run(vivae()
        .arg("replay")
        .arg(run_dir.join("champion.json"))
        .args(["--steps", "4294967295", "-o"])
        .arg(&replay_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("steps"), "{stderr}");
    assert!(!replay_dir.exists(), "replay wrote output");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn many_big_training_maps_are_refused_with_their_total_before_any_output() {
    let dir = scratch("too-big-maps");
    // Just under the per-map limit (10⁸ px²), so each map alone is accepted.
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="10001" height="9990"><rect id="road1" x="0" y="80" width="400" height="40" inkscape:label="Road"/><rect id="r1" x="100" y="100" width="12" height="12" inkscape:label="Robot"/></svg>"#;
    let mut cmd = vivae();
    cmd.args(["evolve", "-q", "--generations", "1", "--steps", "10"]);
    for k in 0..24 {
        let map = dir.join(format!("arena-{k}.svg"));
        std::fs::write(&map, svg).unwrap();
        cmd.arg("--scenario").arg(&map);
    }
    let out_dir = dir.join("out");
    let out = run(cmd.arg("--out").arg(&out_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    // The estimate: 24 × 10001 × 9990 bytes of surface raster.
    assert!(
        stderr.contains("24 training maps") && stderr.contains("about 2398 MB"),
        "{stderr}"
    );
    assert!(!out_dir.exists(), "evolve left a run directory");
    std::fs::remove_dir_all(&dir).unwrap();
}

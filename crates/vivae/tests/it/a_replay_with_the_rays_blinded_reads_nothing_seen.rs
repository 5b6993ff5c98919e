//! `vivae replay --blind-rays`: a distance-sheet champion replayed with
//! every ray reading "nothing in range" drives otherwise than seeing, on
//! the same placement; `--swerve` draws the meeting blinding changes most;
//! a champion without rays has none to blind, refused by name.

use crate::common::*;

/// `vivae replay RUN --placement-seed 3 --out OUT [extra…]`'s printed lines.
fn replay(run: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> String {
    ok(vivae()
        .arg("replay")
        .arg(run)
        .args(["--placement-seed", "3", "--out"])
        .arg(out)
        .args(extra))
}

#[test]
fn blinded_rays_change_a_rays_champion_and_the_swerve_is_drawn() {
    let dir = scratch("blind-rays");
    let run = rays_corridor_run(&dir);
    let out = dir.join("r");
    let seeing = replay(&run, &out, &[]);
    let blind = replay(&run, &out, &["--blind-rays"]);
    assert_eq!(
        blind,
        replay(&run, &out, &["--blind-rays"]),
        "deterministic"
    );
    assert_ne!(seeing, blind, "the rays changed nothing");
    // The blinded figure is drawn beside the seeing one, and says so.
    let svgs: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
        .collect();
    let blinded = svgs
        .iter()
        .find(|p| p.to_string_lossy().contains("-blind-rays"))
        .expect("a blinded figure");
    assert!(
        std::fs::read_to_string(blinded)
            .unwrap()
            .contains("rays blinded")
    );
    assert_eq!(svgs.len(), 2, "{svgs:?}");
    let swerve = replay(&run, &out, &["--swerve"]);
    let line = swerve.lines().find(|l| l.starts_with("swerve ")).unwrap();
    assert!(line.contains("blinded_clearance="), "{line}");
    number(line, "clearance");
    let png = std::fs::read(out.join("swerve-p3.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG"));
    let svg = std::fs::read_to_string(out.join("swerve-p3.svg")).unwrap();
    assert!(
        svg.contains("rays blinded") && svg.contains("block"),
        "{svg:.400}"
    );
    // Without rays there is nothing to blind.
    let plain = dir.join("surface");
    evolve(
        &write_small_config(&dir, 1),
        &plain,
        &["--scenario", "corridor"],
    );
    let refused = vivae()
        .arg("replay")
        .arg(&plain)
        .arg("--out")
        .arg(&out)
        .arg("--blind-rays")
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("--blind-rays")
            && err.contains("no distance rays")
            && err.lines().count() == 1,
        "{err}"
    );
}

//! A scenario whose obstacles and traffic are placed per evaluation: runs
//! stay independent of the thread count, and `replay --placement-seed N`
//! replays a champion on placement N (the same N, the same episode); a
//! scenario that places nothing refuses the seed.

use crate::common::*;

/// The replay's printed measures and its figure (SVG) on `placement` (none: the default).
pub(crate) fn replay(
    run: &std::path::Path,
    placement: Option<&str>,
    out: &std::path::Path,
) -> String {
    let mut cmd = vivae();
    cmd.arg("replay").arg(run).arg("--out").arg(out);
    if let Some(p) = placement {
        cmd.args(["--placement-seed", p]);
    }
    let printed = ok(&mut cmd);
    let svg = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
        .unwrap();
    printed + &std::fs::read_to_string(svg).unwrap()
}

#[test]
fn random_obstacles_and_traffic_are_seeded_and_replayable() {
    let dir = scratch("placements");
    let config = write_small_config(&dir, 3);
    for scenario in ["obstacles-random", "oncoming"] {
        let (one, two) = (
            dir.join(format!("{scenario}-1")),
            dir.join(format!("{scenario}-2")),
        );
        evolve(&config, &one, &["--scenario", scenario, "--threads", "1"]);
        evolve(&config, &two, &["--scenario", scenario, "--threads", "2"]);
        assert_same_results(&one, &two);
        let r = dir.join("r");
        let default = replay(&one, None, &r);
        assert_eq!(
            default,
            replay(&one, Some("0"), &r),
            "the default is placement 0"
        );
        let seven = replay(&one, Some("7"), &r);
        assert_eq!(seven, replay(&one, Some("7"), &r));
        assert_ne!(
            default, seven,
            "{scenario}: placements 0 and 7 give one episode"
        );
        assert!(
            seven.contains("contacts_traffic=") && seven.contains("contacts_wall="),
            "{seven}"
        );
    }
    // A scenario that places nothing refuses a seed by name: none would change the replay.
    let plain = dir.join("roads");
    evolve(&config, &plain, &[]);
    let r = dir.join("r");
    let refused = vivae()
        .arg("replay")
        .arg(&plain)
        .arg("--out")
        .arg(&r)
        .args(["--placement-seed", "7"])
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("--placement-seed 7") && err.contains("places no obstacles"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

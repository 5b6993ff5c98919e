//! The courses where no line is safe (`corridor`, `kerbed-loop`,
//! `oncoming-edges`: blocks in rows across the road) load, render and
//! evolve by name, and a champion replays on held-out placements: the same
//! placement the same episode, another placement another.

use crate::common::*;

/// The replay's printed measures and its figure (SVG) on `placement`.
fn replay(run: &std::path::Path, placement: &str, out: &std::path::Path) -> String {
    crate::random_placements_are_seeded_and_replayable::replay(run, Some(placement), out)
}

#[test]
fn the_courses_load_render_evolve_and_replay_on_placements_by_name() {
    let dir = scratch("courses");
    let config = write_small_config(&dir, 1);
    let list = ok(vivae().args(["scenario", "list"]));
    for name in ["corridor", "kerbed-loop", "oncoming-edges"] {
        assert!(list.lines().any(|l| l.starts_with(name)), "{list}");
        let info = ok(vivae().args(["scenario", "info", name]));
        assert!(info.contains("robots: 5"), "{name}: {info}");
        let png = dir.join(format!("{name}.png"));
        ok(vivae()
            .args(["scenario", "render", name, "--out"])
            .arg(&png));
        assert!(
            std::fs::read(&png).unwrap().starts_with(b"\x89PNG"),
            "{name}"
        );
        let run = dir.join(name);
        evolve(&config, &run, &["--scenario", name]);
        let r = dir.join(format!("{name}-replay"));
        let seven = replay(&run, "7", &r);
        assert_eq!(seven, replay(&run, "7", &r), "{name}");
        assert_ne!(
            seven,
            replay(&run, "8", &r),
            "{name}: placements 7 and 8 alike"
        );
        assert!(seven.contains("contacts_obstacle="), "{seven}");
    }
}

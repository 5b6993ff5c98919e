//! `vivae replay --meetings`: every robot's meetings with the blocks placed
//! for the episode, one CSV line each beside the trajectories, their counts
//! on stdout; every contact with a placed block is in one; blinded, the CSV
//! is named so; a course without a route is refused by name.

use crate::common::*;

#[test]
fn meetings_hold_the_replays_block_contacts_and_say_what_the_rays_showed() {
    let dir = scratch("meetings");
    let run = rays_corridor_run(&dir);
    let out = dir.join("r");
    for blind in [false, true] {
        let mut args = vec!["--placement-seed", "3", "--meetings", "--out"];
        let out_s = out.to_str().unwrap();
        args.push(out_s);
        if blind {
            args.push("--blind-rays");
        }
        let printed = ok(vivae().arg("replay").arg(&run).args(&args));
        let (replay, counts) = (
            printed.lines().next().unwrap(),
            printed.lines().last().unwrap(),
        );
        let name = if blind {
            "meetings-p3-blind-rays.csv"
        } else {
            "meetings-p3.csv"
        };
        let csv = std::fs::read_to_string(out.join(name)).unwrap();
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert!(rows.iter().all(|r| r.len() == header.len()), "{csv}");
        assert_eq!(number(counts, "meetings") as usize, rows.len(), "{counts}");
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        // Every contact with a placed block (5 robots, 150 steps) is in a meeting.
        let touches: f64 = rows
            .iter()
            .map(|r| r[col("touches")].parse::<f64>().unwrap())
            .sum();
        let placed = number(replay, "contacts_placed") * 5.0 * 150.0 / 1000.0;
        // (the rate is printed to 3 decimals: 0.0005 per 1,000 robot-steps)
        assert!(
            (touches - placed).abs() < 0.01,
            "{touches} vs {placed}: {replay}"
        );
        let on_line = rows.iter().filter(|r| r[col("on_line")] == "true").count();
        assert_eq!(number(counts, "on_line") as usize, on_line);
        assert!(number(counts, "on_line_seen") <= on_line as f64);
        for r in &rows {
            let peak: f64 = r[col("peak")].parse().unwrap();
            assert!((0.0..=1.0).contains(&peak), "{r:?}");
            assert_eq!(r[col("seen_at")].is_empty(), peak == 0.0, "{r:?}");
        }
    }
    // A course without a route has no along-route meetings.
    let plain = dir.join("roads");
    evolve(&write_small_config(&dir, 1), &plain, &[]);
    let refused = vivae()
        .arg("replay")
        .arg(&plain)
        .arg("--out")
        .arg(&out)
        .arg("--meetings")
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("--meetings") && err.contains("route") && err.lines().count() == 1,
        "{err}"
    );
}

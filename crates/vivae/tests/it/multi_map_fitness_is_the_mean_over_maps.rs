//! A multi-map run's fitness is the map-weighted mean of the champion's
//! fitness on each map with that map's own robots, exactly as `replay
//! --scenario` measures it; `replay RUN` alone replays on the first map.

use crate::common::*;

/// The `fitness=` of a replay's output line.
fn replay_fitness(stdout: &str) -> f64 {
    number(stdout, "fitness")
}

#[test]
fn champion_fitness_is_the_mean_of_its_replays_on_each_map() {
    let dir = scratch("multi-map-mean");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    // traffic has 6 robots, the others 5: --robots 0 drives all of each map's.
    let maps = ["roads", "oval", "traffic"];
    let mut flags = vec!["--robots", "0"];
    for m in &maps {
        flags.extend(["--scenario", m]);
    }
    evolve(&config, &run_dir, &flags);
    let champion: serde_json::Value =
        serde_json::from_slice(&read(&run_dir, "champion.json")).unwrap();
    let recorded = champion["fitness"].as_f64().unwrap();

    let per_map: Vec<f64> = maps
        .iter()
        .map(|m| {
            replay_fitness(&ok(vivae()
                .arg("replay")
                .arg(&run_dir)
                .args(["--scenario", m, "--robots", "0"])
                .arg("--out")
                .arg(dir.join("replay"))))
        })
        .collect();
    let mean = per_map.iter().sum::<f64>() / 3.0;
    assert_eq!(
        recorded.to_bits(),
        mean.to_bits(),
        "{recorded} vs {per_map:?}"
    );
    assert!(
        per_map[0] != per_map[1],
        "maps gave the same fitness: {per_map:?}"
    );

    // Without --scenario: the first training map, said on stderr.
    let out = run(vivae()
        .arg("replay")
        .arg(&run_dir)
        .arg("--out")
        .arg(dir.join("replay")));
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("first training map") && stderr.contains("roads.svg"),
        "{stderr}"
    );
    let first = replay_fitness(&String::from_utf8_lossy(&out.stdout));
    assert_eq!(first.to_bits(), per_map[0].to_bits());
    // The champion file alone finds the copies beside it.
    let alone = ok(vivae()
        .arg("replay")
        .arg(run_dir.join("champion.json"))
        .arg("--out")
        .arg(dir.join("replay")));
    assert_eq!(replay_fitness(&alone).to_bits(), per_map[0].to_bits());
    // The report still builds.
    ok(vivae().arg("report").arg(&run_dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

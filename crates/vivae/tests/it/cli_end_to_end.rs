//! The command-line workflow a user follows: inspect the scenario, evolve,
//! replay at other resolutions, retrain, print the config.

use crate::common::*;

#[test]
fn scenario_info_json_describes_the_default_scenario() {
    let out = ok(vivae().args(["scenario", "info", "--json"]));
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON object");
    assert!(v["arena"]["width"].as_f64().unwrap() > 0.0);
    assert_eq!(v["robots"].as_array().unwrap().len(), 5);
    assert!(v["surfaces"]["road"].as_u64().unwrap() >= 1);
    for key in [
        "fixed_obstacles",
        "movable_obstacles",
        "pucks",
        "marks",
        "warnings",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    let text = ok(vivae().args(["scenario", "info"]));
    assert!(text.contains("robots: 5"), "{text}");
}

#[test]
fn scenario_info_json_lists_routes_obstacle_regions_and_scripted_robots() {
    let info = |name: &str| {
        let out = ok(vivae().args(["scenario", "info", "--json", name]));
        serde_json::from_str::<serde_json::Value>(out.trim()).expect("one JSON object")
    };
    let v = info("oncoming");
    let routes: Vec<&str> = (v["routes"].as_array().unwrap().iter())
        .map(|r| r["id"].as_str().unwrap())
        .collect();
    assert_eq!(routes, ["lane-cw", "lane-acw"]);
    assert!(v["routes"][0]["length"].as_f64().unwrap() > 1000.0, "{v}");
    assert_eq!(v["routes"][0]["closed"], true);
    assert_eq!(v["robots"][0]["route"], "lane-cw");
    let traffic = v["traffic"].as_array().unwrap();
    assert_eq!(traffic.len(), 4);
    assert_eq!(traffic[0]["id"], "car1");
    assert_eq!(traffic[0]["route"], "lane-acw");
    assert_eq!(traffic[0]["throttle"], serde_json::json!([0.5, 0.7]));
    assert_eq!(traffic[0]["spread"], 150.0);
    let v = info("obstacles-random");
    assert_eq!(
        v["obstacle_regions"],
        serde_json::json!([{"id": "blocks", "count": 8, "size": [16.0, 16.0], "clearance": 40.0}])
    );
    assert_eq!(v["traffic"], serde_json::json!([]));
    let text = ok(vivae().args(["scenario", "info", "oncoming"]));
    assert!(
        text.contains("scripted robot car1: follows lane-acw"),
        "{text}"
    );
    assert!(text.contains("route lane-acw: "), "{text}");
}

#[test]
fn scenario_render_writes_png_and_svg() {
    let dir = scratch("render");
    let png = dir.join("s.png");
    let svg = dir.join("s.svg");
    ok(vivae()
        .args(["scenario", "render", "--sensors", "3x5", "-o"])
        .arg(&png));
    ok(vivae().args(["scenario", "render", "-o"]).arg(&svg));
    assert_eq!(&std::fs::read(&png).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    assert!(
        String::from_utf8(std::fs::read(&svg).unwrap())
            .unwrap()
            .contains("<svg")
    );
    let bad = run(vivae()
        .args(["scenario", "render", "-o"])
        .arg(dir.join("s.jpg")));
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn evolve_replay_retrain_workflow() {
    let dir = scratch("workflow");
    let config = write_small_config(&dir, 3);
    let run_dir = dir.join("run");
    let summary = evolve(&config, &run_dir, &[]);
    assert!(summary.starts_with("evolve: generations=3 "), "{summary}");
    for f in [
        "config.toml",
        "scenario.svg",
        "generations.csv",
        "population.csv",
        "timing.csv",
        "champion.json",
        "figures/trajectories-gen001.png",
        "figures/trajectories-gen001.svg",
        "figures/trajectories-champion.png",
        "figures/convergence.png",
        "figures/convergence.svg",
        "figures/network.png",
        "figures/network.svg",
    ] {
        assert!(run_dir.join(f).exists(), "missing {f}");
    }
    let generations = String::from_utf8(read(&run_dir, "generations.csv")).unwrap();
    assert_eq!(generations.lines().count(), 4);
    let population = String::from_utf8(read(&run_dir, "population.csv")).unwrap();
    assert_eq!(population.lines().count(), 1 + 3 * 24);

    // Replaying the champion on the training substrate gives its recorded fitness.
    let champion: serde_json::Value =
        serde_json::from_slice(&read(&run_dir, "champion.json")).unwrap();
    let line = ok(vivae().arg("replay").arg(&run_dir));
    let fitness: f64 = line
        .split_whitespace()
        .next()
        .unwrap()
        .trim_start_matches("fitness=")
        .parse()
        .unwrap();
    assert_eq!(fitness, champion["fitness"].as_f64().unwrap(), "{line}");
    assert!(line.contains("on_road="));
    // The behaviour measures, each a number (side may be `none`).
    for key in ["collisions", "left_turns", "right_turns", "loops", "side"] {
        let value = line
            .split_whitespace()
            .find_map(|f| f.strip_prefix(&format!("{key}=")))
            .unwrap_or_else(|| panic!("no {key}= in {line}"));
        assert!(
            value == "none" || value.parse::<f64>().is_ok(),
            "{key}={value}"
        );
    }
    assert!(run_dir.join("replay/replay-roads-s3x5-n3x3.png").exists());

    // Re-sampled substrates run without re-training.
    let line =
        ok(vivae()
            .arg("replay")
            .arg(&run_dir)
            .args(["--neurons", "9x9", "--sensors", "3x6"]));
    assert!(line.starts_with("fitness="), "{line}");
    assert!(run_dir.join("replay/replay-roads-s3x6-n9x9.png").exists());

    // Retrain continues the final population on the new substrate.
    let retrained = dir.join("retrained");
    ok(vivae()
        .arg("retrain")
        .arg(&run_dir)
        .args(["--sensors", "3x6", "--generations", "2", "-q", "--out"])
        .arg(&retrained));
    let config: String = String::from_utf8(read(&retrained, "config.toml")).unwrap();
    assert!(config.contains("angles = 6"), "{config}");
    assert_eq!(
        String::from_utf8(read(&retrained, "generations.csv"))
            .unwrap()
            .lines()
            .count(),
        3
    );
    // Its resolved config reproduces it.
    let again = dir.join("again");
    ok(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(retrained.join("config.toml"))
        .arg("--out")
        .arg(&again));
    assert_same_results(&retrained, &again);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn config_default_is_complete_and_parses() {
    let text = ok(vivae().args(["config", "default"]));
    assert!(text.contains("population_size = 100"));
    assert!(
        text.contains("# genomes per generation; default: 100; paper: 100\n"),
        "{text}"
    );
    let dir = scratch("config-default");
    let path = dir.join("default.toml");
    std::fs::write(&path, &text).unwrap();
    let resolved = ok(vivae().args(["config", "check"]).arg(&path));
    assert!(resolved.contains("[neat]"));
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `champion.json` alone rebuilds its controller: replaying the file gives
//! what replaying its run directory gives, on a non-default substrate too.

use crate::common::*;

fn fitness_of(line: &str) -> f64 {
    line.split_whitespace()
        .next()
        .and_then(|f| f.strip_prefix("fitness="))
        .and_then(|f| f.parse().ok())
        .unwrap_or_else(|| panic!("no fitness in {line:?}"))
}

#[test]
fn replay_of_champion_file_equals_replay_of_run_dir() {
    let dir = scratch("replay-champion-file");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    // Not the defaults: a champion read with the default config would not fit
    // (distance sensors need another CPPN output) or would differ.
    evolve(
        &config,
        &run_dir,
        &["--sensors", "3x6", "--neurons", "2x4", "--robots", "3"],
    );
    let recorded: serde_json::Value =
        serde_json::from_slice(&read(&run_dir, "champion.json")).unwrap();

    let from_dir = ok(vivae().arg("replay").arg(&run_dir));
    // A copy of champion.json away from its run still replays the same (the
    // scenario it names is given, being the one file outside the champion).
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::copy(run_dir.join("champion.json"), elsewhere.join("c.json")).unwrap();
    let from_file = ok(vivae()
        .arg("replay")
        .arg(run_dir.join("champion.json"))
        .arg("--out")
        .arg(&elsewhere));
    assert_eq!(from_dir, from_file);
    assert_eq!(
        fitness_of(&from_file),
        recorded["fitness"].as_f64().unwrap()
    );
    let copied = ok(vivae()
        .arg("replay")
        .arg(elsewhere.join("c.json"))
        .arg("--scenario")
        .arg(run_dir.join("scenario.svg"))
        .args(["--robots", "3"]));
    assert_eq!(from_dir, copied);
    // Without the scenario the copy says what is missing.
    let out = run(vivae().arg("replay").arg(elsewhere.join("c.json")));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--scenario"));

    // A champion file of an older vivae (no config) replays with the defaults, saying so.
    let mut old: serde_json::Value = recorded.clone();
    old.as_object_mut().unwrap().remove("config");
    let old_file = elsewhere.join("old.json");
    std::fs::write(&old_file, serde_json::to_string_pretty(&old).unwrap()).unwrap();
    let out =
        run(vivae()
            .arg("replay")
            .arg(&old_file)
            .args(["--sensors", "3x6", "--neurons", "2x4"]));
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("records no config"));

    // Flags override what the file records.
    let resampled = ok(vivae()
        .arg("replay")
        .arg(run_dir.join("champion.json"))
        .args(["--neurons", "3x3"]));
    assert_ne!(from_file, resampled);
    assert!(run_dir.join("replay/replay-roads-s3x6-n2x4.png").exists());
    assert!(run_dir.join("replay/replay-roads-s3x6-n3x3.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Training on several maps (`--scenario A --scenario B`, `experiment.scenarios`):
//! the run does not depend on the thread count, the config key and the flag
//! give the same run, a resumed run matches an uninterrupted one, the run
//! directory keeps a copy of every map, and an edited copy is refused.

use crate::common::*;

const MAPS: [&str; 4] = ["--scenario", "roads", "--scenario", "oval"];

#[test]
fn multi_map_runs_are_reproducible_and_resume_identically() {
    let dir = scratch("multi-map");
    let config = write_small_config(&dir, 3);
    let one = dir.join("one");
    let two = dir.join("two");
    evolve(&config, &one, &[&["--threads", "1"][..], &MAPS].concat());
    evolve(&config, &two, &[&["--threads", "2"][..], &MAPS].concat());
    assert_same_results(&one, &two);

    // Every map is copied, with its hash; scenario.svg is the first map.
    let recorded = std::fs::read_to_string(one.join("config.toml")).unwrap();
    assert!(
        recorded.contains(r#"scenarios = ["scenarios/roads.svg", "scenarios/oval.svg"]"#),
        "{recorded}"
    );
    assert_eq!(
        read(&one, "scenarios/roads.svg"),
        vivae_sim::ROADS_SVG.as_bytes()
    );
    assert_eq!(read(&one, "scenario.svg"), vivae_sim::ROADS_SVG.as_bytes());
    let oval = vivae_lab::tasks::scenarios::find("oval").unwrap().svg;
    assert_eq!(read(&one, "scenarios/oval.svg"), oval.as_bytes());
    let manifest = String::from_utf8(read(&one, "scenarios/manifest.txt")).unwrap();
    let hash = format!("{:016x}", vivae_lab::io::fnv1a(oval.as_bytes()));
    assert!(
        manifest.contains(&format!("oval.svg {hash} ")),
        "{manifest}"
    );

    // The config key gives the same run as the flags.
    let keyed = dir.join("keyed.toml");
    std::fs::write(
        &keyed,
        small_config(3).replace(
            "[experiment]\n",
            "[experiment]\nscenarios = [\"roads\", \"oval\"]\n",
        ),
    )
    .unwrap();
    let by_key = dir.join("by-key");
    evolve(&keyed, &by_key, &[]);
    assert_same_results(&one, &by_key);
    // So does the run's own config.toml, which names the copies.
    let again = dir.join("again");
    evolve(&one.join("config.toml"), &again, &[]);
    assert_same_results(&one, &again);

    // Stopped after 2 generations, then resumed to 3.
    let resumed = dir.join("resumed");
    evolve(
        &config,
        &resumed,
        &[&["--generations", "2"][..], &MAPS].concat(),
    );
    ok(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&resumed));
    assert_same_results(&one, &resumed);

    // The maps matter: the same seed on roads alone evolves differently.
    let single = dir.join("single");
    evolve(&config, &single, &[]);
    assert_ne!(
        read(&one, "generations.csv"),
        read(&single, "generations.csv"),
        "the second map had no effect"
    );
    assert!(!single.join("scenarios").exists());

    // An edited copy of a training map is refused, and nothing changes.
    let copy = one.join("scenarios/oval.svg");
    std::fs::write(&copy, format!("{oval}<!-- edited -->\n")).unwrap();
    let before = read(&one, "generations.csv");
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "4"])
        .arg(&one));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("oval.svg") && stderr.contains("edited"),
        "{stderr}"
    );
    assert_eq!(read(&one, "generations.csv"), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn setting_both_scenario_keys_is_refused() {
    let dir = scratch("multi-map-both");
    let config = dir.join("both.toml");
    std::fs::write(
        &config,
        "[experiment]\nscenario = \"roads\"\nscenarios = [\"roads\", \"oval\"]\n",
    )
    .unwrap();
    let out = run(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("run")));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("both.toml") && stderr.contains("both set"),
        "{stderr}"
    );
    assert!(!dir.join("run").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_training_map_is_refused_before_anything_is_written() {
    let dir = scratch("multi-map-missing");
    let out = run(vivae()
        .args([
            "evolve",
            "-q",
            "--scenario",
            "roads",
            "--scenario",
            "nowhere",
        ])
        .arg("--out")
        .arg(dir.join("run")));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("nowhere"), "{stderr}");
    assert!(!dir.join("run").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_run_named_by_a_relative_path_writes_its_report_and_resumes() {
    // The config's map names resolve against the run folder; with a relative
    // `--out` they once resolved twice (`run/run/scenarios/...`), so evolve,
    // report and resume all failed at the figures.
    let dir = scratch("multi-map-relative");
    write_small_config(&dir, 1);
    let in_dir = |args: &[&str]| ok(vivae().current_dir(&dir).args(args));
    let out = in_dir(
        &[
            &["evolve", "-q", "--config", "c.toml", "--out", "run"][..],
            &MAPS,
        ]
        .concat(),
    );
    assert!(out.contains("per_map="), "{out}");
    assert!(dir.join("run/report.html").is_file());
    std::fs::remove_file(dir.join("run/report.html")).unwrap();
    in_dir(&["report", "run"]);
    assert!(dir.join("run/report.html").is_file());
    in_dir(&["resume", "-q", "run", "--generations", "2"]);
    let rows = std::fs::read_to_string(dir.join("run/generations.csv")).unwrap();
    assert_eq!(rows.lines().count(), 3, "{rows}");
    let _ = std::fs::remove_dir_all(&dir);
}

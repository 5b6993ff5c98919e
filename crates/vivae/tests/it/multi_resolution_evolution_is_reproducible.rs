//! Multi-resolution evolution (`--train-neurons`, `--train-sensors`): the
//! resolutions are recorded in the run's config, the run does not depend on
//! the thread count, a resumed run matches an uninterrupted one, and training
//! at several resolutions changes the fitnesses (it is not ignored).

use crate::common::*;

const TRAIN: [&str; 4] = ["--train-neurons", "3x3,5x5", "--train-sensors", "3x5,3x6"];

#[test]
fn multi_resolution_runs_are_recorded_and_reproducible() {
    let dir = scratch("multi-res");
    let config = write_small_config(&dir, 3);
    let one = dir.join("one");
    let two = dir.join("two");
    evolve(&config, &one, &[&["--threads", "1"][..], &TRAIN].concat());
    evolve(&config, &two, &[&["--threads", "2"][..], &TRAIN].concat());
    assert_same_results(&one, &two);
    let recorded = std::fs::read_to_string(one.join("config.toml")).unwrap();
    assert!(
        recorded.contains(r#"train_neurons = ["3x3", "5x5"]"#),
        "{recorded}"
    );
    assert!(
        recorded.contains(r#"train_sensors = ["3x5", "3x6"]"#),
        "{recorded}"
    );

    // Interrupted after 2 generations, then resumed to 3.
    let resumed = dir.join("resumed");
    evolve(
        &config,
        &resumed,
        &[&["--generations", "2"][..], &TRAIN].concat(),
    );
    ok(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&resumed));
    assert_same_results(&one, &resumed);

    // The same seed at the reported resolution only evolves differently.
    let single = dir.join("single");
    evolve(&config, &single, &[]);
    assert_ne!(
        read(&one, "generations.csv"),
        read(&single, "generations.csv"),
        "training resolutions had no effect"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn too_many_training_resolutions_are_refused() {
    let out = run(vivae().args([
        "evolve",
        "-q",
        "--train-neurons",
        "1x1,1x2,1x3,1x4,1x5",
        "--train-sensors",
        "1x1,1x2,1x3,1x4",
    ]));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("train_neurons x train_sensors = 20"),
        "{stderr}"
    );
}

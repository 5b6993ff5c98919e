//! `--placements N` (`experiment.placements`): every genome is evaluated on N
//! placements of a scenario that places obstacles or traffic per evaluation.
//! Such a run differs from a one-placement run, does not depend on the
//! thread count, resumes bit-identically, and gives the same run from the
//! config key; N > 1 on a scenario that places nothing is refused in one line.

use crate::common::*;

#[test]
fn several_placements_per_genome_are_seeded_and_resume_identically() {
    let dir = scratch("several-placements");
    let config = write_small_config(&dir, 3);
    let flags = ["--scenario", "obstacles-random", "--placements", "3"];
    let (one, two) = (dir.join("one"), dir.join("two"));
    evolve(&config, &one, &[&["--threads", "1"][..], &flags].concat());
    evolve(&config, &two, &[&["--threads", "2"][..], &flags].concat());
    assert_same_results(&one, &two);
    let recorded = String::from_utf8(read(&one, "config.toml")).unwrap();
    assert!(recorded.contains("placements = 3"), "{recorded}");

    // One placement per genome (the default) is another run.
    let single = dir.join("single");
    evolve(&config, &single, &["--scenario", "obstacles-random"]);
    assert_ne!(
        read(&one, "generations.csv"),
        read(&single, "generations.csv"),
        "three placements evolved as one"
    );
    // So is the worst of the three placements instead of their mean.
    let worst = dir.join("worst");
    evolve(
        &config,
        &worst,
        &[&flags[..], &["--placements-aggregate", "min"]].concat(),
    );
    assert_ne!(
        read(&one, "generations.csv"),
        read(&worst, "generations.csv"),
        "min over placements evolved as their mean"
    );

    // The config key gives the same run as the flag.
    let keyed = dir.join("keyed.toml");
    std::fs::write(
        &keyed,
        small_config(3).replace("[experiment]\n", "[experiment]\nplacements = 3\n"),
    )
    .unwrap();
    let by_key = dir.join("by-key");
    evolve(&keyed, &by_key, &["--scenario", "obstacles-random"]);
    assert_same_results(&one, &by_key);

    // Stopped after 2 generations, then resumed to 3.
    let resumed = dir.join("resumed");
    evolve(
        &config,
        &resumed,
        &[&["--generations", "2"][..], &flags].concat(),
    );
    ok(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&resumed));
    assert_same_results(&one, &resumed);

    // A scenario that places nothing per evaluation would repeat one episode.
    let refused = run(vivae()
        .args(["evolve", "-q", "--placements", "3", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("roads")));
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8(refused.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("experiment.placements = 3") && err.contains("obstacles-random"),
        "{err}"
    );
    assert!(!dir.join("roads").join("champion.json").exists());
    // So would a task that places nothing, and 0 placements is no evaluation.
    for (extra, says) in [
        (
            &["--placements", "2", "--task", "maze"][..],
            "only a driving run",
        ),
        (&["--placements", "0"][..], "must be from 1 to"),
    ] {
        let out = run(vivae()
            .args(["evolve", "-q"])
            .args(extra)
            .arg("--out")
            .arg(dir.join("refused")));
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(err.contains(says), "{err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `--robots` on evolve and replay; a replay on a scenario with fewer robot
//! starts uses that scenario's robots; too few robots says how to fix it.

use crate::common::*;

#[test]
fn one_robot_vivae_scenario_evolves_and_replays() {
    let Some(corpus) = shared_scenarios() else {
        return;
    };
    let ushape = corpus.join("ushape.svg");
    let dir = scratch("robots-flag");
    let config = write_small_config(&dir, 2);

    // The default experiment asks for 5 robots: the error names the fix.
    let out = run(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(&config)
        .arg("--scenario")
        .arg(&ushape)
        .arg("--out")
        .arg(dir.join("refused")));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("has 1 robot") && err.contains("--robots 1"),
        "{err}"
    );

    let one = dir.join("one");
    evolve(
        &config,
        &one,
        &["--robots", "1", "--scenario", ushape.to_str().unwrap()],
    );
    assert!(
        String::from_utf8(read(&one, "config.toml"))
            .unwrap()
            .contains("robots = 1")
    );

    // A 5-robot champion replays on the 1-robot scenario with its one robot…
    let five = dir.join("five");
    evolve(&config, &five, &[]);
    let line = ok(vivae()
        .arg("replay")
        .arg(five.join("champion.json"))
        .arg("--scenario")
        .arg(&ushape));
    assert!(line.starts_with("fitness="), "{line}");
    assert!(five.join("replay/replay-ushape-s3x5-n3x3.png").exists());
    // …and --robots still decides when given.
    let out = run(vivae()
        .arg("replay")
        .arg(&five)
        .arg("--scenario")
        .arg(&ushape)
        .args(["--robots", "2"]));
    assert_eq!(out.status.code(), Some(2));
    let line = ok(vivae().arg("replay").arg(&five).args(["--robots", "2"]));
    assert!(line.starts_with("fitness="), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

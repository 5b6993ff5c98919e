//! A crate of its own (`examples/extend-vivae`) registers a task and a
//! strategy and runs the `vivae` command line with them (`vivae::run_cli`),
//! without a line of vivae edited: its runs evolve, resume, replay and export as a
//! built-in task's do, and vivae's own program refuses the task by name.

use std::path::Path;
use std::process::Command;

use crate::common::*;

/// `cargo run -p extend-vivae -- ARGS` in the profile these tests were built
/// in (the program is built the first time; its stdout).
fn extended(args: &[&str]) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut cmd = Command::new(option_env!("CARGO").unwrap_or("cargo"));
    cmd.args(["run", "-q", "-p", "extend-vivae", "--manifest-path"])
        .arg(root.join("Cargo.toml"));
    if !cfg!(debug_assertions) {
        cmd.arg("--release");
    }
    ok(cmd.arg("--").args(args))
}

#[test]
fn a_task_and_a_strategy_of_its_own_run_through_the_program() {
    let dir = scratch("extend-vivae");
    let run_dir = dir.join("run");
    let out = run_dir.to_str().unwrap();
    let evolve = [
        "evolve",
        "--task",
        "seek",
        "--strategy",
        "random-search",
        "-q",
    ];
    let line = extended(&[&evolve[..], &["--generations", "3", "--out", out]].concat());
    assert!(line.starts_with("evolve: generations=3 "), "{line}");
    assert!(line.contains(" strategy=random-search "), "{line}");
    let config = String::from_utf8(read(&run_dir, "config.toml")).unwrap();
    assert!(config.contains("task = \"seek\""), "{config}");
    assert!(config.contains("kind = \"random-search\""), "{config}");
    for name in [
        "champion.json",
        "population.csv",
        "checkpoints",
        "report.html",
    ] {
        assert!(run_dir.join(name).exists(), "{name}");
    }
    assert!(
        !run_dir.join("scenario.svg").exists(),
        "a plain task loads no map"
    );
    // The first generation: the strategy's batch of the config's
    // population, each scored by the task: 1 - a mean distance, where the point
    // (moving at most 0.1 a step for 30 steps) is at most 4 from its target.
    let csv = String::from_utf8(read(&run_dir, "generations.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");
    let first: Vec<f64> = (csv.lines().nth(1).unwrap().split(','))
        .map(|v| v.parse().unwrap())
        .collect();
    let [generation, best, mean, _, worst] = first[..5] else {
        panic!("{csv}")
    };
    assert_eq!(generation, 1.0, "{csv}");
    assert!(
        best <= 1.0 && best > mean && mean > worst && worst >= -3.0,
        "{csv}"
    );
    let population = String::from_utf8(read(&run_dir, "population.csv")).unwrap();
    let size = vivae_neat::NeatParams::plain_neat().population_size;
    let firsts = population.lines().filter(|l| l.starts_with("1,")).count();
    assert_eq!(firsts, size, "{population}");
    // The replay is the task's evaluation, step by step: its fitness is
    // 1 + the mean reward (−distance) of its episodes' steps.
    let replay = extended(&["replay", out]);
    let fitness: f64 = field(&replay, "fitness").parse().unwrap();
    let episode = String::from_utf8(read(&run_dir, "replay/episode.csv")).unwrap();
    let rewards: Vec<f64> = (episode.lines().skip(1))
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(rewards.len(), 4 * 30, "{episode}");
    let mean_reward = rewards.iter().sum::<f64>() / rewards.len() as f64;
    assert!((fitness - (1.0 + mean_reward)).abs() < 1e-12, "{replay}");
    // Its checkpoints resume: two generations and one more are three at once.
    let part = dir.join("part");
    let part_out = part.to_str().unwrap();
    extended(&[&evolve[..], &["--generations", "2", "--out", part_out]].concat());
    extended(&["resume", "-q", "--generations", "3", part_out]);
    assert_same_results(&run_dir, &part);
    extended(&[
        "export",
        out,
        "--format",
        "json",
        "--out",
        &format!("{}/net.json", dir.display()),
    ]);
    assert!(dir.join("net.json").is_file());
    // vivae's own program has neither, and says which tasks it has.
    let own = run(vivae()
        .args(["evolve", "--task", "seek", "-q", "--out"])
        .arg(dir.join("own")));
    let err = String::from_utf8_lossy(&own.stderr);
    assert_eq!(own.status.code(), Some(2), "{err}");
    assert!(err.contains("'seek'") && err.contains("cartpole"), "{err}");
    assert!(!dir.join("own").exists());
}

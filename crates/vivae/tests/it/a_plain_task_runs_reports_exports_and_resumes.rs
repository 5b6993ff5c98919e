//! A plain task (CartPole-v1, `crates/lab/src/tasks/cartpole.rs`: a genome
//! shape and a scoring function on the adapter of `tasks/plain.rs`) runs
//! from the CLI with every strategy, resumes bit-identically, reaches
//! Gymnasium's threshold, writes the run directory every task writes (no
//! map), and gets report.html, a replay and its network exported; settings
//! it does not read are refused by name.

use std::path::Path;

use crate::common::*;
use vivae_lab::tasks::cartpole::CartPole;
use vivae_lab::tasks::plain::Plain;

/// `vivae evolve -q --task TASK ARGS --out OUT`, which must succeed; returns stdout.
pub fn plain(task: &str, out: &Path, args: &[&str]) -> String {
    ok(vivae()
        .args(["evolve", "-q", "--task", task])
        .args(args)
        .arg("--out")
        .arg(out))
}

/// `vivae evolve -q --task cartpole ARGS --out OUT`, which must succeed; returns stdout.
fn cartpole(out: &Path, args: &[&str]) -> String {
    plain("cartpole", out, args)
}

/// Asserts a command fails with exit 2 and one line of stderr containing every one of `needles`.
fn refused(cmd: &mut std::process::Command, needles: &[&str]) {
    let out = run(cmd);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n}: {err}");
    }
}

#[test]
fn every_strategy_runs_cartpole_and_resumes_bit_identical() {
    every_strategy_runs_and_resumes_bit_identical("cartpole", "30", "2");
}

/// Plain task `task` runs with every strategy, resumes bit-identically and
/// writes the run directory every task writes (no map), with its target's
/// columns; `population` and `seed` must leave 4 generations unsolved (a
/// solved run stops, and there would be nothing to resume).
pub fn every_strategy_runs_and_resumes_bit_identical(task: &str, population: &str, seed: &str) {
    let dir = scratch(&format!("{task}-resume"));
    for strategy in ["neat", "novelty", "map-elites", "nsga2"] {
        let common = [
            "--strategy",
            strategy,
            "--population",
            population,
            "--seed",
            seed,
        ];
        let whole = dir.join(format!("{strategy}-whole"));
        let line = plain(
            task,
            &whole,
            &[&common[..], &["--generations", "4"]].concat(),
        );
        let part = dir.join(format!("{strategy}-part"));
        plain(
            task,
            &part,
            &[&common[..], &["--generations", "2"]].concat(),
        );
        ok(vivae()
            .args(["resume", "-q", "--generations", "4"])
            .arg(&part));
        assert_same_results(&whole, &part);
        for name in ["best-genomes.jsonl", "config.toml"] {
            assert!(
                read(&whole, name) == read(&part, name),
                "{task} {strategy}: {name}"
            );
        }
        assert_eq!(field(&line, "solved"), "no", "{task} {strategy}: {line}");
        // The layout every task writes, without a map.
        for name in ["config.toml", "timing.csv", "checkpoints", "report.html"] {
            assert!(whole.join(name).exists(), "{task} {strategy}: {name}");
        }
        assert!(!whole.join("scenario.svg").exists(), "{task} {strategy}");
        let csv = String::from_utf8(read(&whole, "generations.csv")).unwrap();
        let header = csv.lines().next().unwrap();
        assert!(header.starts_with("generation,best,mean,"), "{header}");
        assert!(header.contains(",solvers,evaluations"), "{header}");
    }
}

#[test]
fn cartpole_reaches_gymnasiums_threshold_and_reports_replays_and_exports() {
    let dir = scratch("cartpole-solved");
    let out = dir.join("run");
    let line = cartpole(&out, &["--seed", "1", "--generations", "30"]);
    let target = CartPole::TARGET.unwrap();
    assert_eq!(field(&line, "solved"), "yes", "{line}");
    assert!(number(&line, "best") >= target, "{line}");
    assert!(
        number(&line, "generations") < 30.0,
        "a solved run stops: {line}"
    );
    let html = String::from_utf8(read(&out, "report.html")).unwrap();
    assert!(
        html.contains("\"task\":\"cartpole\""),
        "the report of a plain task"
    );
    std::fs::remove_file(out.join("report.html")).unwrap();
    ok(vivae().arg("report").arg(&out));
    assert!(read(&out, "report.html") == html.as_bytes());
    let replayed = ok(vivae().arg("replay").arg(&out));
    assert!(number(&replayed, "fitness") > 0.0, "{replayed}");
    let episode = String::from_utf8(read(&out, "replay/episode.csv")).unwrap();
    assert!(episode.starts_with("episode,step,in0,"), "{episode}");
    // A replay flag that only a task drawing its own replay reads is refused, not ignored.
    for flag in ["--blind-rays", "--swerve", "--meetings"] {
        refused(
            vivae().args(["replay", flag]).arg(&out),
            &[flag, "a cartpole run draws no replay"],
        );
    }
    refused(
        vivae().args(["replay", "--placement-seed", "3"]).arg(&out),
        &["--placement-seed 3", "a cartpole run places nothing"],
    );
    for format in ["json", "c", "onnx"] {
        let file = dir.join(format!("cartpole.{format}"));
        let said = ok(vivae()
            .args(["export", "--format", format, "--out"])
            .arg(&file)
            .arg(&out));
        assert!(
            said.contains("5 inputs") && said.contains("feed-forward"),
            "{said}"
        );
        assert!(file.exists());
    }
    refused(
        vivae()
            .args(["export", "--format", "json", "--sensors", "3x3", "--out"])
            .arg(dir.join("x.json"))
            .arg(&out),
        &["cartpole", "no substrate"],
    );
    // The commands that need a substrate network say which tasks have one.
    refused(
        vivae().arg("view").arg(&out),
        &["a cartpole run", "runs of driving", "vivae report"],
    );
    refused(
        (vivae().args([
            "retrain",
            "-q",
            "--neurons",
            "5x5",
            "--generations",
            "1",
            "--out",
        ]))
        .arg(dir.join("retrained"))
        .arg(&out),
        &["a cartpole run", "retrain works on runs of driving"],
    );
    refused(
        (vivae().args(["drive-image", "--draw-map"]))
            .arg(dir.join("map.png"))
            .arg(&out),
        &["a cartpole run", "runs of driving have one"],
    );
    // Compared, it is grouped by task and strategy (it has no substrate).
    let table = ok(vivae()
        .args(["compare", "--out"])
        .arg(dir.join("compare.svg"))
        .arg(&out));
    assert!(table.contains("cartpole (neat)"), "{table}");
}

#[test]
fn settings_a_plain_task_does_not_read_are_refused_by_name() {
    let dir = scratch("cartpole-refused");
    let out = dir.join("run");
    let evolve = |args: &[&str]| {
        let mut c = vivae();
        c.args(["evolve", "-q", "--task", "cartpole"])
            .args(args)
            .arg("--out")
            .arg(&out);
        c
    };
    refused(
        &mut evolve(&["--sensors", "5x7"]),
        &["surface_sensors", "cartpole"],
    );
    refused(
        &mut evolve(&["--robots", "2"]),
        &["experiment.robots", "cartpole"],
    );
    refused(
        &mut evolve(&["--scenario", "oval"]),
        &["experiment.scenario", "cartpole"],
    );
    refused(
        &mut evolve(&["--neurons", "5x5"]),
        &["substrate.neurons", "cartpole"],
    );
    refused(&mut evolve(&["--precision", "fast"]), &["precision"]);
    assert!(!out.exists(), "nothing is written for a refused run");
}

#[test]
fn a_plain_run_writes_only_the_sections_it_reads_and_resumes_the_whole_form() {
    let dir = scratch("cartpole-sections");
    let (whole, part) = (dir.join("whole"), dir.join("part"));
    cartpole(
        &whole,
        &["--population", "30", "--seed", "2", "--generations", "3"],
    );
    cartpole(
        &part,
        &["--population", "30", "--seed", "2", "--generations", "2"],
    );
    let text = String::from_utf8(read(&whole, "config.toml")).unwrap();
    let tables: Vec<&str> = text.lines().filter(|l| l.starts_with('[')).collect();
    assert_eq!(
        tables,
        [
            "[experiment]",
            "[neat]",
            "[run]",
            "[strategy]",
            "[strategy.novelty]",
            "[strategy.map_elites]",
            "[strategy.nsga2]"
        ],
        "{text}"
    );
    // `config default --task` holds the same sections, and checks.
    let default = ok(vivae().args(["config", "default", "--task", "cartpole"]));
    let headers = |t: &str| -> Vec<String> {
        (t.lines().filter(|l| l.starts_with('[')))
            .map(String::from)
            .collect()
    };
    assert_eq!(headers(&default), tables, "{default}");
    std::fs::write(dir.join("default.toml"), &default).unwrap();
    let checked = ok(vivae()
        .args(["config", "check"])
        .arg(dir.join("default.toml")));
    assert_eq!(headers(&checked), tables, "{checked}");
    // A run written before (every shared section, at its defaults) resumes
    // as if it had not been, its config.toml rewritten in the new form.
    let config = vivae_lab::tasks::read_config(&part.join("config.toml")).unwrap();
    let old = config.to_toml();
    assert!(
        old.contains("\n[physics]\n") && old.contains("\n[substrate]\n"),
        "{old}"
    );
    std::fs::write(part.join("config.toml"), old).unwrap();
    ok(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&part));
    assert_same_results(&whole, &part);
    assert!(read(&whole, "config.toml") == read(&part, "config.toml"));
}

/// Gymnasium 1.4.0's CartPole-v1 from state (0.01, −0.02, 0.03, 0.04) under
/// these actions, to the bit (`env.unwrapped.state = …; env.step(a)`, the
/// state printed with `float.hex`).
const GYMNASIUM: [(bool, [f64; 4]); 4] = [
    (
        true,
        [
            0.009600000000000001,
            0.17467919574755525,
            0.030799999999999998,
            -0.2430687179600081,
        ],
    ),
    (
        false,
        [
            0.013093583914951107,
            -0.020868848948191993,
            0.025938625640799837,
            0.0591679999394166,
        ],
    ),
    (
        false,
        [
            0.012676206935987267,
            -0.21635292104612766,
            0.02712198563958817,
            0.3599205713784138,
        ],
    ),
    (
        true,
        [
            0.008349148515064714,
            -0.021626799199488206,
            0.03432039706715644,
            0.0759116989474441,
        ],
    ),
];

#[test]
fn cartpole_steps_as_gymnasium_does() {
    let mut s = [0.01, -0.02, 0.03, 0.04];
    for (push_right, want) in GYMNASIUM {
        s = vivae_lab::tasks::cartpole::step(s, push_right);
        assert_eq!(s, want);
        assert!(!vivae_lab::tasks::cartpole::terminated(s));
    }
    assert!(vivae_lab::tasks::cartpole::terminated([
        2.41, 0.0, 0.0, 0.0
    ]));
    assert!(vivae_lab::tasks::cartpole::terminated([
        0.0, 0.0, -0.21, 0.0
    ]));
}

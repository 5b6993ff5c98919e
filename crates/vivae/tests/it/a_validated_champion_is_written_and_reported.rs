//! A classic-control run (a task whose entry declares a reward threshold)
//! ends with its champion validated on 100 fresh episodes: `validation.json`
//! in the run directory (the shape `vivae.gym.validate` writes), the same
//! numbers as the summary line's `validated_mean=` and `validated=`, shown
//! in report.html; the header says a stop needs the check too. A task
//! without validation writes no such file.

use crate::a_plain_task_runs_reports_exports_and_resumes::plain;
use crate::common::*;

#[test]
fn a_classic_control_run_writes_its_validation_and_reports_it() {
    let dir = scratch("validation-json");
    let out = dir.join("run");
    let line = plain(
        "cartpole",
        &out,
        &["--seed", "3", "--generations", "3", "--population", "20"],
    );
    let v: serde_json::Value =
        serde_json::from_slice(&read(&out, "validation.json")).expect("validation.json is JSON");
    assert_eq!(v["env"], "cartpole", "{v}");
    assert_eq!(v["episodes"], 100, "{v}");
    assert_eq!(v["seeds"], serde_json::json!([0, 99]), "{v}");
    assert!(v["validation_seed"].is_u64(), "{v}");
    assert_eq!(v["reward_threshold"], 475.0, "{v}");
    let mean = v["mean"].as_f64().unwrap();
    let (min, max) = (v["min"].as_f64().unwrap(), v["max"].as_f64().unwrap());
    assert!(
        min <= mean && mean <= max && v["std"].as_f64().unwrap() >= 0.0,
        "{v}"
    );
    // The summary line's validation, to the digit Rust prints.
    assert_eq!(number(&line, "validated_mean"), mean, "{line}");
    assert_eq!(number(&line, "validated_worst"), min, "{line}");
    let solved = field(&line, "validated") == "yes";
    assert_eq!(v["solved"], solved, "{v} {line}");
    assert_eq!(solved, mean >= 475.0);
    assert_eq!(
        v["fitness"].as_f64().unwrap(),
        number(&line, "best"),
        "{line}"
    );
    assert_eq!(
        v["generation"].as_f64().unwrap(),
        number(&line, "champion_generation"),
        "{line}"
    );
    // report.html says it, with the verdict.
    let html = String::from_utf8(read(&out, "report.html")).unwrap();
    let verdict = if solved { ": solved" } else { ": not solved" };
    assert!(
        html.contains("validated on 100 fresh episodes of cartpole"),
        "no validation in report.html"
    );
    assert!(
        html.contains(&format!("threshold 475{verdict}")),
        "no verdict in report.html"
    );
    // `vivae report` rebuilds it from the file.
    std::fs::remove_file(out.join("report.html")).unwrap();
    ok(vivae().arg("report").arg(&out));
    let again = String::from_utf8(read(&out, "report.html")).unwrap();
    assert!(
        again.contains(&format!("mean return {mean:.2}")),
        "rebuilt report"
    );
    // The header names the check a stop needs.
    let header = run(vivae()
        .args([
            "evolve",
            "--task",
            "cartpole",
            "--generations",
            "1",
            "--population",
            "10",
        ])
        .arg("--out")
        .arg(dir.join("header")));
    let err = String::from_utf8_lossy(&header.stderr);
    assert!(
        err.contains("the run stops when an evaluation reaches 475 and its genome's mean over 100 check episodes"),
        "{err}"
    );
    // A run whose task has no validation writes none.
    let maze = dir.join("maze");
    plain("maze", &maze, &["--generations", "1", "--population", "10"]);
    assert!(!maze.join("validation.json").exists());
}

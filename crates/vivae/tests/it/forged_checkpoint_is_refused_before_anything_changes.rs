//! A checkpoint that passes its checksum but cannot be resumed (forged or
//! from a different substrate) stops `resume` with exit 2 and one line, before
//! anything in the run directory changes: no panic, no rewritten
//! `config.toml`, no truncated CSV file.

use crate::common::*;
use serde_json::Value;
use std::path::Path;

/// Every file of the run directory that resume could change, with its bytes.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    [
        "generations.csv",
        "population.csv",
        "timing.csv",
        "champion.json",
        "config.toml",
    ]
    .iter()
    .map(|n| (n.to_string(), read(dir, n)))
    .collect()
}

/// A checkpoint with a valid checksum over `body`, in the format the program writes.
fn encode(body: &Value) -> Vec<u8> {
    vivae_lab::rundir::seal_checkpoint(&serde_json::to_string(body).unwrap()).into_bytes()
}

/// Drops input node 4 (and its links) from a CPPN genome: 4 inputs instead of 5.
fn drop_input(genome: &mut Value) {
    genome["nodes"]
        .as_array_mut()
        .unwrap()
        .retain(|n| n["id"] != 4);
    genome["links"]
        .as_array_mut()
        .unwrap()
        .retain(|l| l["from"] != 4);
}

#[test]
fn forged_checkpoints_are_refused_without_touching_the_run() {
    let dir = scratch("forged-ckpt");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let ckpt = run_dir.join("checkpoints/gen-000002.ckpt");
    let good = std::fs::read_to_string(&ckpt).unwrap();
    let body: Value = serde_json::from_str(good.split_once('\n').unwrap().1).unwrap();
    let before = snapshot(&run_dir);

    type Forge = fn(&mut Value);
    let forgeries: [(&str, Forge); 8] = [
        ("figure genome with 4 CPPN inputs", |b| {
            drop_input(&mut b["progress"]["figure_genomes"][0][2])
        }),
        ("population genome with 4 CPPN inputs", |b| {
            drop_input(&mut b["population"]["genomes"][0])
        }),
        ("generations_len 0", |b| {
            b["progress"]["generations_len"] = 0.into()
        }),
        ("population_len 0", |b| {
            b["progress"]["population_len"] = 0.into()
        }),
        ("more generations done than the run has", |b| {
            b["progress"]["done"] = 9.into()
        }),
        ("no genomes", |b| {
            b["population"]["genomes"] = Value::Array(Vec::new())
        }),
        ("no species", |b| {
            b["population"]["species"] = Value::Array(Vec::new())
        }),
        ("a species without members", |b| {
            b["population"]["species"][0]["members"] = Value::Array(Vec::new())
        }),
    ];
    for (what, forge) in forgeries {
        let mut forged = body.clone();
        forge(&mut forged);
        std::fs::write(&ckpt, encode(&forged)).unwrap();
        let out = run(vivae()
            .args(["resume", "-q", "--generations", "3"])
            .arg(&run_dir));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {stderr}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{what}: {stderr}");
        assert!(stderr.contains("gen-000002.ckpt"), "{what}: {stderr}");
        assert_eq!(snapshot(&run_dir), before, "{what}: run directory changed");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn another_runs_checkpoint_or_a_replaced_scenario_is_refused() {
    let dir = scratch("foreign-ckpt");
    let config = write_small_config(&dir, 3);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let other = dir.join("other");
    evolve(&config, &other, &["--generations", "1", "--seed", "99"]);
    let before = snapshot(&run_dir);

    // Another run's checkpoint placed as the newest.
    let foreign = run_dir.join("checkpoints/gen-000004.ckpt");
    std::fs::copy(other.join("checkpoints/gen-000001.ckpt"), &foreign).unwrap();
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "5"])
        .arg(&run_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("gen-000004.ckpt"), "{stderr}");
    assert_eq!(snapshot(&run_dir), before, "foreign: run directory changed");
    std::fs::remove_file(&foreign).unwrap();

    // config.toml edited after the run started (a resume would silently undo it).
    let config_toml = run_dir.join("config.toml");
    let original = std::fs::read_to_string(&config_toml).unwrap();
    let edited = original.replacen("steps = 150", "steps = 151", 1);
    assert_ne!(edited, original, "the test edits the steps");
    std::fs::write(&config_toml, &edited).unwrap();
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "4"])
        .arg(&run_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("config.toml") && stderr.contains("steps = 151"),
        "{stderr}"
    );
    std::fs::write(&config_toml, &original).unwrap();
    assert_eq!(snapshot(&run_dir), before, "config: run directory changed");

    // The scenario replaced after the run started.
    let scenario = run_dir.join("scenario.svg");
    let mut text = std::fs::read_to_string(&scenario).unwrap();
    text.push_str("<!-- edited -->\n");
    std::fs::write(&scenario, text).unwrap();
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "4"])
        .arg(&run_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("scenario.svg"), "{stderr}");
    assert_eq!(
        snapshot(&run_dir),
        before,
        "scenario: run directory changed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

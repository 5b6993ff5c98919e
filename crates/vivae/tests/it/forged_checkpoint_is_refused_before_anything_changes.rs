//! A checkpoint that passes its checksum but cannot be resumed (forged or
//! from a different substrate) stops `resume` with exit 2 and one line, before
//! anything in the run directory changes: no panic, no rewritten
//! `config.toml`, no truncated CSV file.

use crate::common::*;
use crate::every_task_keeps_the_interrupt_promise::snapshot;
use serde_json::Value;

/// The byte range of the value of the one `"rng":` key in `text`.
fn rng_range(text: &str) -> std::ops::Range<usize> {
    let key = "\"rng\":";
    assert_eq!(text.matches(key).count(), 1, "one rng");
    let start = text.find(key).unwrap() + key.len();
    let mut values = serde_json::Deserializer::from_str(&text[start..]).into_iter::<Value>();
    values.next().unwrap().unwrap();
    start..start + values.byte_offset()
}

/// A checkpoint with a valid checksum over `body`, in the format the
/// program writes, its generator state spliced in from `good` (the body it
/// was read from): its 128-bit numbers do not survive a `Value`, and a
/// forgery must be refused for what it forged, not for a mangled state.
fn encode(body: &Value, good: &str) -> Vec<u8> {
    let mut text = serde_json::to_string(body).unwrap();
    text.replace_range(rng_range(&text), &good[rng_range(good)]);
    vivae_lab::rundir::seal_checkpoint(&text).into_bytes()
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
    let good_body = good.split_once('\n').unwrap().1;
    let body: Value = serde_json::from_str(good_body).unwrap();

    type Forge = fn(&mut Value);
    let forgeries: [(&str, Forge); 8] = [
        ("figure genome with 4 CPPN inputs", |b| {
            drop_input(&mut b["progress"]["figure_genomes"][0][2])
        }),
        ("population genome with 4 CPPN inputs", |b| {
            drop_input(&mut b["population"]["genomes"][1])
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
    // Where a genome of the wrong shape is, said: which one, or the line.
    let figure = format!(
        "the best genome of generation {} does not fit the run: CPPN has 4 inputs",
        body["progress"]["figure_genomes"][0][0]
    );
    let named: [&[&str]; 2] = [
        &[&figure],
        &["(line 2 column", "genome 1 has 4 inputs and 3 outputs"],
    ];
    for (k, (what, forge)) in forgeries.into_iter().enumerate() {
        let mut forged = body.clone();
        forge(&mut forged);
        std::fs::write(&ckpt, encode(&forged, good_body)).unwrap();
        // Every file, the forged checkpoint among them, byte for byte.
        let before = snapshot(&run_dir);
        let out = run(vivae()
            .args(["resume", "-q", "--generations", "3"])
            .arg(&run_dir));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {stderr}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{what}: {stderr}");
        assert!(stderr.contains("gen-000002.ckpt"), "{what}: {stderr}");
        for needle in named.get(k).copied().unwrap_or_default() {
            assert!(stderr.contains(needle), "{what}: {needle}: {stderr}");
        }
        assert!(
            snapshot(&run_dir) == before,
            "{what}: run directory changed"
        );
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
    let with_foreign = snapshot(&run_dir);
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "5"])
        .arg(&run_dir));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("gen-000004.ckpt"), "{stderr}");
    assert!(
        snapshot(&run_dir) == with_foreign,
        "foreign: run directory changed"
    );
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
    assert!(
        snapshot(&run_dir) == before,
        "config: run directory changed"
    );

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
    // All but the edited scenario as before.
    let after = snapshot(&run_dir);
    let others = |s: &[(String, Vec<u8>)]| -> Vec<(String, Vec<u8>)> {
        s.iter()
            .filter(|(n, _)| n != "scenario.svg")
            .cloned()
            .collect()
    };
    assert!(
        others(&after) == others(&before),
        "scenario: run directory changed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

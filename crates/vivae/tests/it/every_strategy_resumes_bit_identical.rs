//! A run of every registered search strategy but NEAT (whose runs the
//! pinned-hash tests cover), stopped after some generations and resumed,
//! ends with a run directory byte-identical to an uninterrupted run's,
//! including the files the strategy's entry says it writes (archive, front,
//! parent) and its checkpoints; only wall-clock traces may differ:
//! `timing.csv`, its length as checkpoints record it, and `report.html`
//! (which shows the timing and the directory's name). `--force` replaces
//! each strategy's run folder.

use std::collections::BTreeMap;
use std::path::Path;

use crate::common::*;

/// A checkpoint without its checksum line and with `timing_len` blanked.
fn without_timing(checkpoint: &[u8]) -> Vec<u8> {
    let text = String::from_utf8(checkpoint.to_vec()).unwrap();
    let body = text.split_once('\n').unwrap().1;
    let (before, after) = body.split_once("\"timing_len\":").unwrap();
    let rest = after.trim_start_matches(|c: char| c.is_ascii_digit());
    format!("{before}\"timing_len\":_{rest}").into_bytes()
}

/// Every file under `dir` (relative path → bytes; checkpoints
/// [`without_timing`]), but `timing.csv` and `report.html`.
fn files_of(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.strip_prefix(root).unwrap().display().to_string();
            if path.is_dir() {
                walk(root, &path, out);
            } else if name.ends_with(".ckpt") {
                out.insert(name, without_timing(&std::fs::read(&path).unwrap()));
            } else if name != "timing.csv" && name != "report.html" {
                out.insert(name, std::fs::read(&path).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

#[test]
fn interrupted_and_resumed_runs_of_every_strategy_match_uninterrupted_ones() {
    let dir = scratch("strategies-resume");
    let config = write_small_config(&dir, 5);
    let entries = vivae_lab::search::entries();
    let mut cases: Vec<_> = (entries.iter().filter(|e| e.kind != "neat"))
        .map(|e| (e.kind, "end-position", e.files))
        .collect();
    // A sampled path: 10 coordinates, through the k-d tree.
    cases.push(("novelty", "trajectory", &[]));
    assert!(cases.len() >= 5, "{cases:?}");
    for (strategy, behaviour, own) in cases {
        let name = format!("{strategy}-{behaviour}");
        let flags = ["--strategy", strategy, "--behaviour", behaviour];
        let full = dir.join(format!("{name}-full"));
        let summary = evolve(&config, &full, &flags);
        assert!(
            summary.contains(&format!(" strategy={strategy}")),
            "{summary}"
        );
        let short = dir.join(format!("{name}-short"));
        evolve(
            &config,
            &short,
            &[&flags[..], &["--generations", "2"]].concat(),
        );
        ok(vivae()
            .args(["resume", "-q", "--generations", "5"])
            .arg(&short));
        let (a, b) = (files_of(&full), files_of(&short));
        assert_eq!(
            a.keys().collect::<Vec<_>>(),
            b.keys().collect::<Vec<_>>(),
            "{strategy}: other files"
        );
        for (name, bytes) in &a {
            assert!(*bytes == b[name], "{strategy}: {name} differs after resume");
        }
        for own in own {
            assert!(a.contains_key(*own), "{strategy}: no {own}");
        }
        let header = String::from_utf8(read(&full, "generations.csv")).unwrap();
        assert!(header.lines().count() == 6, "{strategy}: {header}");
        // The run folder holds only files vivae writes: --force replaces it.
        evolve(&config, &full, &[&flags[..], &["--force"]].concat());
        assert!(files_of(&full) == a, "{strategy}: --force");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

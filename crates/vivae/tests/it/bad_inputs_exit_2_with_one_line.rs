//! Every file of the bad-input corpus (`tests/bad-inputs/` at the repository
//! root) is refused with exit code 2 and a one-line message naming the file,
//! never a panic, and nothing is written.

use crate::common::*;
use std::path::{Path, PathBuf};

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/bad-inputs");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("svg" | "toml" | "json")
            )
        })
        .collect();
    files.sort();
    files
}

#[test]
fn every_bad_input_is_refused_cleanly() {
    let files = corpus();
    assert!(
        files.len() >= 30,
        "the corpus has only {} files",
        files.len()
    );
    let scratch_dir = scratch("bad-inputs");
    let mut failures = Vec::new();
    for (i, file) in files.iter().enumerate() {
        let out_dir = scratch_dir.join(format!("out-{i}"));
        let mut cmd = vivae();
        match file.extension().and_then(|e| e.to_str()) {
            Some("svg") => cmd
                .args(["evolve", "-q", "--generations", "1", "--scenario"])
                .arg(file)
                .arg("--out")
                .arg(&out_dir),
            Some("toml") => cmd
                .args(["evolve", "-q", "--config"])
                .arg(file)
                .arg("--out")
                .arg(&out_dir),
            _ => cmd.arg("replay").arg(file).arg("-o").arg(&out_dir),
        };
        let out = run(&mut cmd);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let name = file.file_name().unwrap().to_string_lossy();
        let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
        let problem = if out.status.code() != Some(2) {
            Some(format!("exit {:?}", out.status.code()))
        } else if stderr.contains("panicked") {
            Some("panicked".into())
        } else if lines.len() != 1 {
            Some(format!("{} lines on stderr", lines.len()))
        } else if !lines[0].contains(name.as_ref()) {
            Some("message does not name the file".into())
        } else if out_dir.exists() {
            Some("output written".into())
        } else {
            None
        };
        if let Some(p) = problem {
            failures.push(format!("{name}: {p}: {stderr}"));
        }
    }
    std::fs::remove_dir_all(&scratch_dir).unwrap();
    assert!(
        failures.is_empty(),
        "{} bad inputs not refused cleanly:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

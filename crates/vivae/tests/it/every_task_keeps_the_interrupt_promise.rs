//! Every registered task keeps the interrupt promise of docs/guide.md: on
//! SIGTERM (as on Ctrl-C) its run finishes the generation, writes its
//! checkpoint, says how to resume and exits 130; the run then resumes, and
//! `vivae resume` of a finished run says it is finished and changes nothing.
//! A new task in `vivae_lab::tasks::TASKS` is covered without a new test.

use std::io::{BufRead as _, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

use crate::common::*;

/// Every file under `dir` with its bytes, by path, in order.
pub fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).unwrap().display().to_string();
                out.push((rel, std::fs::read(&path).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// `vivae evolve --task NAME` of a long, small run, sent SIGTERM once its
/// first generation is reported: returns its exit code and stderr.
fn evolve_then_terminate(task: &str, run_dir: &Path) -> (Option<i32>, String) {
    let mut child = vivae()
        .args(["evolve", "--task", task, "--threads", "1", "--seed", "3"])
        .args(["--population", "12", "--generations", "100000"])
        .arg("--out")
        .arg(run_dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = String::new();
    let mut signalled = false;
    for line in BufReader::new(child.stderr.take().unwrap()).lines() {
        let line = line.unwrap();
        if !signalled && line.trim_start().starts_with("gen ") {
            let status = Command::new("kill")
                .args(["-TERM", &child.id().to_string()])
                .status()
                .unwrap();
            assert!(status.success());
            signalled = true;
        }
        stderr.push_str(&line);
        stderr.push('\n');
    }
    let status = child.wait().unwrap();
    assert!(signalled, "{task}: no generation reported: {stderr}");
    (status.code(), stderr)
}

#[test]
fn every_task_stops_cleanly_on_sigterm_resumes_and_says_when_it_is_finished() {
    // A task whose episodes a host plays (its entry's `host`: Gymnasium's,
    // from Python) the program refuses to evolve (python/tests/test_gym.py runs it).
    let tasks = vivae_lab::tasks::TASKS.iter().filter(|t| t.host.is_none());
    for task in tasks.map(|t| t.name) {
        let dir = scratch(&format!("interrupt-{task}"));
        let run_dir = dir.join("run");
        let (code, stderr) = evolve_then_terminate(task, &run_dir);
        assert_eq!(code, Some(130), "{task}: {stderr}");
        let hint = format!("vivae resume {}", run_dir.display());
        assert!(stderr.contains(&hint), "{task}: {stderr}");
        let done: u32 = stderr
            .split("interrupted after generation ")
            .nth(1)
            .and_then(|rest| rest.split(';').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{task}: no interrupted line: {stderr}"));
        assert!(done >= 1, "{task}: {stderr}");
        // The run resumes from its checkpoint, to one generation more.
        let line = ok(vivae()
            .args(["resume", "-q", "--generations", &(done + 1).to_string()])
            .arg(&run_dir));
        assert!(
            line.contains(&format!("generations={}", done + 1)),
            "{task}: {line}"
        );
        // A finished run: said so, with how to extend it, and nothing changes.
        let before = snapshot(&run_dir);
        let out = run(vivae().arg("resume").arg(&run_dir));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{task}: {err}");
        assert!(err.contains("is already finished"), "{task}: {err}");
        assert!(err.contains("--generations N"), "{task}: {err}");
        assert!(!err.contains("resuming after"), "{task}: {err}");
        assert!(
            snapshot(&run_dir) == before,
            "{task}: the finished run changed"
        );
    }
}

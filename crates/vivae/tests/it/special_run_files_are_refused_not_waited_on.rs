//! A FIFO in a run directory (as `best-genomes.jsonl`) is refused with a
//! one-line message naming it and exit code 2, instead of blocking `vivae
//! report` forever waiting for a writer.

use crate::common;
use crate::common::{scratch, vivae, write_small_config};
use std::time::{Duration, Instant};

#[test]
fn a_fifo_as_best_genomes_makes_report_exit_2_naming_it() {
    let dir = scratch("report-fifo");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    common::evolve(&config, &run, &[]);
    let best = run.join("best-genomes.jsonl");
    std::fs::remove_file(&best).unwrap();
    common::mkfifo(&best);
    let mut child = vivae()
        .arg("report")
        .arg(&run)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Bounded wait, so a blocked report fails the test instead of hanging it.
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("vivae report blocked on the FIFO");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut err = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err).unwrap();
    assert_eq!(status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("best-genomes.jsonl"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

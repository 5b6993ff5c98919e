//! A predator–prey run (`--task predator-prey`, two populations on its own
//! driver) spread over MPI ranks writes exactly the files of the
//! single-process run, for each kind of opponents and 1–3 ranks, and one
//! started on some ranks resumes on others to the same bytes.
use std::path::Path;

use crate::common::*;
use crate::mpi_common::*;

/// Every file of a predator–prey run directory that holds results.
const FILES: [&str; 10] = [
    "config.toml",
    "scenario.svg",
    "hunters.csv",
    "prey.csv",
    "ciao.csv",
    "hall-of-fame.jsonl",
    "checkpoint.json",
    "champions.json",
    "figures/ciao.svg",
    "figures/coevolution.svg",
];

/// The flags of the short runs compared (the same thread count everywhere:
/// a run's config records it).
const FLAGS: [&str; 11] = [
    "evolve",
    "-q",
    "--task",
    "predator-prey",
    "--population",
    "14",
    "--steps",
    "120",
    "--seed",
    "5",
    "--threads",
];

fn assert_same_run(a: &Path, b: &Path) {
    for name in FILES {
        assert!(
            read(a, name) == read(b, name),
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn a_predator_prey_run_gives_the_single_process_files_under_mpi_and_resumes() {
    let dir = scratch("mpi-predator-prey");
    let hall = dir.join("hall.toml");
    std::fs::write(
        &hall,
        "[experiment]\ntask = \"predator-prey\"\n[coevolution]\nopponents = \"hall-of-fame\"\nsample = 3\n",
    )
    .unwrap();
    let fixed = dir.join("fixed.toml");
    let best = dir.join("best-reference");
    let prey = format!("{:?}", best.to_string_lossy());
    std::fs::write(
        &fixed,
        format!("[experiment]\ntask = \"predator-prey\"\n[coevolution]\nopponents = \"fixed\"\nfixed_prey = {prey}\n"),
    )
    .unwrap();
    let kinds = [
        ("best", None),
        ("hall", Some(&hall)),
        ("fixed", Some(&fixed)),
    ];
    for (name, config) in kinds {
        let with_config = |cmd: &mut std::process::Command, out: &Path| {
            cmd.args(FLAGS).args(["1", "--generations", "4"]);
            if let Some(c) = config {
                cmd.arg("--config").arg(c);
            }
            cmd.arg("--out").arg(out);
        };
        let reference = dir.join(format!("{name}-reference"));
        let mut cmd = vivae();
        with_config(&mut cmd, &reference);
        let line = ok(&mut cmd);
        for n in 1..=3 {
            let out = dir.join(format!("{name}-n{n}"));
            let mut cmd = mpirun(n);
            with_config(&mut cmd, &out);
            let spread = ok(&mut cmd);
            assert_same_run(&reference, &out);
            let path = |s: &str, p: &Path| s.replace(&*p.to_string_lossy(), "OUT");
            assert_eq!(path(&line, &reference), path(&spread, &out), "{name} n={n}");
        }
    }
    // Two generations on 3 ranks, then resumed to four on 2 ranks.
    let part = dir.join("hall-3-then-2");
    ok(mpirun(3)
        .args(FLAGS)
        .args(["1", "--generations", "2", "--config"])
        .arg(&hall)
        .arg("--out")
        .arg(&part));
    ok(mpirun(2)
        .args(["resume", "-q", "--generations", "4"])
        .arg(&part));
    assert_same_run(&dir.join("hall-reference"), &part);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn rank_zero_reports_the_meetings_traffic_unless_quiet() {
    let dir = scratch("mpi-predator-prey-traffic");
    let out = run(mpirun(2)
        .args(&FLAGS[..1])
        .args(&FLAGS[2..])
        .args(["1", "--generations", "2", "--out"])
        .arg(dir.join("run")));
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    // Each generation is two batches: its games, then its CIAO cells.
    let line = (stderr.lines())
        .find(|l| l.starts_with("mpi: 2 ranks, 4 batches of meetings"))
        .unwrap_or_else(|| panic!("no traffic line in: {stderr}"));
    assert!(line.contains("bytes sent to workers"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

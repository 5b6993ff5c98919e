//! `vivae evolve --task predator-prey` co-evolves hunters and prey with
//! either kind of opponents, writes both populations' files and the CIAO
//! matrix, names both champions on its summary line, resumes bit-identically
//! (after a crash left rows past its checkpoint, too) at any thread count,
//! and refuses what it cannot run in one line with exit code 2.

use std::io::Write as _;
use std::path::Path;

use crate::common::*;

/// Every file of a predator–prey run directory.
const FILES: [&str; 8] = [
    "config.toml",
    "scenario.svg",
    "hunters.csv",
    "prey.csv",
    "ciao.csv",
    "hall-of-fame.jsonl",
    "checkpoint.json",
    "champions.json",
];

/// `vivae evolve -q --task predator-prey` with `args` into `out`; its stdout.
fn evolve(out: &Path, args: &[&str]) -> String {
    ok(vivae()
        .args([
            "evolve",
            "-q",
            "--task",
            "predator-prey",
            "--population",
            "16",
        ])
        .args(["--steps", "150", "--seed", "4"])
        .args(args)
        .arg("--out")
        .arg(out))
}

fn append(path: &Path, text: &str) {
    let mut f = std::fs::OpenOptions::new().append(true).open(path).unwrap();
    f.write_all(text.as_bytes()).unwrap();
}

#[test]
fn both_kinds_of_opponents_run_and_resume_bit_identical() {
    let dir = scratch("predator-prey-resume");
    let hall = dir.join("hall.toml");
    std::fs::write(
        &hall,
        "[experiment]\ntask = \"predator-prey\"\n[coevolution]\nopponents = \"hall-of-fame\"\nsample = 3\n",
    )
    .unwrap();
    let hall = hall.to_string_lossy().into_owned();
    for (name, extra) in [("best", vec![]), ("hall", vec!["--config", hall.as_str()])] {
        let whole = dir.join(format!("{name}-whole"));
        let line = evolve(&whole, &[&extra[..], &["--generations", "6"]].concat());
        assert_eq!(field(&line, "task"), "predator-prey");
        assert_eq!(field(&line, "generations"), "6");
        for side in ["hunter", "prey"] {
            let g: u32 = field(&line, &format!("{side}_champion_generation"))
                .parse()
                .unwrap();
            assert!(g < 6, "{line}");
            let f: f64 = field(&line, &format!("{side}_master_fitness"))
                .parse()
                .unwrap();
            assert!((0.0..=2.0).contains(&f), "{line}");
        }
        // The CIAO matrix: every pair of generations once.
        let ciao = String::from_utf8(read(&whole, "ciao.csv")).unwrap();
        let mut pairs: Vec<(u32, u32)> = ciao
            .lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[0].parse().unwrap(), f[1].parse().unwrap())
            })
            .collect();
        pairs.sort_unstable();
        let all: Vec<(u32, u32)> = (0..6).flat_map(|h| (0..6).map(move |p| (h, p))).collect();
        assert_eq!(pairs, all, "{name}");
        let hunters = String::from_utf8(read(&whole, "hunters.csv")).unwrap();
        assert_eq!(hunters.lines().count(), 7, "{hunters}");
        if name == "hall" {
            // Generation 5 meets 3 of the 5 earlier prey champions.
            let last = hunters.lines().last().unwrap();
            assert_eq!(
                last.rsplit(',').next().unwrap().split(';').count(),
                3,
                "{last}"
            );
        }

        // Three generations, a crash that left rows past the checkpoint, a resume to six.
        let part = dir.join(format!("{name}-part"));
        evolve(&part, &[&extra[..], &["--generations", "3"]].concat());
        append(&part.join("ciao.csv"), "9,9,1,1\n");
        append(&part.join("hunters.csv"), "3,1,1,1,1,1,\n");
        let resumed = ok(vivae()
            .args(["resume", "-q", "--generations", "6"])
            .arg(&part));
        assert_eq!(
            resumed,
            line.replace(&*whole.to_string_lossy(), &part.to_string_lossy())
        );
        // The figures the end of a run draws are the same too.
        for file in FILES
            .iter()
            .chain(&["figures/ciao.svg", "figures/coevolution.svg"])
        {
            assert!(read(&whole, file) == read(&part, file), "{name}: {file}");
        }
        // The command that replays one-population runs refuses it in one line.
        let out = run(vivae().arg("replay").arg(&whole));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "replay: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("ciao.csv"), "replay: {err}");
        // One thread gives the same results (only the recorded thread count differs).
        let one = dir.join(format!("{name}-one-thread"));
        evolve(
            &one,
            &[&extra[..], &["--generations", "6", "--threads", "1"]].concat(),
        );
        for file in FILES[2..6].iter().chain(&FILES[7..]) {
            assert!(read(&whole, file) == read(&one, file), "{name}: {file}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn what_a_predator_prey_run_cannot_do_is_refused_in_one_line() {
    let dir = scratch("predator-prey-refused");
    for (args, needle) in [
        (&["--scenario", "roads"][..], "data-team=\"hunter\""),
        (&["--distance-rays", "3"][..], "[distance_sensors]"),
        (&["--strategy", "novelty"][..], "[strategy]"),
    ] {
        let out = run(vivae()
            .args([
                "evolve",
                "-q",
                "--task",
                "predator-prey",
                "--generations",
                "1",
            ])
            .args(args)
            .arg("--out")
            .arg(dir.join("run")));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

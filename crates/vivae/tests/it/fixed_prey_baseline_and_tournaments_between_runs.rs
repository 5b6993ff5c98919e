//! `[coevolution] opponents = "fixed"` evolves hunters only, against one
//! run's prey champion (copied into the run as `fixed-prey.json`), and
//! resumes bit-identically; `vivae tournament A B` plays one run's champions
//! against another's and agrees with the runs' own CIAO matrices; what
//! neither can do is refused in one line with exit code 2.

use std::path::Path;

use crate::common::*;

/// `vivae evolve -q --task predator-prey` (small) with `args` into `out`; its stdout.
fn evolve_pp(out: &Path, args: &[&str]) -> String {
    ok(vivae()
        .args(["evolve", "-q", "--task", "predator-prey"])
        .args(["--population", "16", "--steps", "150", "--seed", "4"])
        .args(args)
        .arg("--out")
        .arg(out))
}

/// The prey genomes of a run's `hall-of-fame.jsonl`, as JSON text.
fn prey_hall(dir: &Path) -> Vec<String> {
    let text = String::from_utf8(read(dir, "hall-of-fame.jsonl")).unwrap();
    text.lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["side"] == "prey")
        .map(|v| v["genome"].to_string())
        .collect()
}

fn refused(cmd: &mut std::process::Command, needle: &str) {
    let out = run(cmd);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{needle}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(needle), "{needle}: {err}");
}

#[test]
fn hunters_evolve_against_a_fixed_prey_and_runs_play_each_other() {
    let dir = scratch("fixed-prey");
    let coevolved = dir.join("coevolved");
    evolve_pp(&coevolved, &["--generations", "4"]);
    let fixed_toml = dir.join("fixed.toml");
    std::fs::write(
        &fixed_toml,
        format!(
            "[experiment]\ntask = \"predator-prey\"\n[coevolution]\nopponents = \"fixed\"\nfixed_prey = {:?}\n",
            coevolved.to_string_lossy()
        ),
    )
    .unwrap();
    let config = fixed_toml.to_string_lossy().into_owned();
    let whole = dir.join("fixed-whole");
    let line = evolve_pp(&whole, &["--config", &config, "--generations", "5"]);
    assert!(line.contains("generations=5"), "{line}");
    // Every prey of the hall of fame is the co-evolved run's prey champion.
    let champions: serde_json::Value =
        serde_json::from_slice(&read(&coevolved, "champions.json")).unwrap();
    let fixed = champions["prey"]["genome"].to_string();
    let hall = prey_hall(&whole);
    assert_eq!(hall.len(), 5);
    assert!(hall.iter().all(|g| *g == fixed));
    let copied: serde_json::Value =
        serde_json::from_slice(&read(&whole, "fixed-prey.json")).unwrap();
    assert_eq!(copied["genome"].to_string(), fixed);

    // Three generations, then a resume to five: the same bytes.
    let part = dir.join("fixed-part");
    evolve_pp(&part, &["--config", &config, "--generations", "3"]);
    ok(vivae()
        .args(["resume", "-q", "--generations", "5"])
        .arg(&part));
    for file in [
        "hunters.csv",
        "prey.csv",
        "ciao.csv",
        "hall-of-fame.jsonl",
        "checkpoint.json",
        "champions.json",
        "fixed-prey.json",
    ] {
        assert!(read(&whole, file) == read(&part, file), "{file}");
    }
    // A fixed-prey run's own fixed-prey.json names the same prey.
    let again = dir.join("fixed-again");
    let own = whole.join("fixed-prey.json").to_string_lossy().into_owned();
    let toml = std::fs::read_to_string(&fixed_toml).unwrap();
    let toml = toml.replace(&*coevolved.to_string_lossy(), &own);
    std::fs::write(&fixed_toml, toml).unwrap();
    evolve_pp(&again, &["--config", &config, "--generations", "5"]);
    assert!(read(&whole, "ciao.csv") == read(&again, "ciao.csv"));

    tournament_agrees_with_the_ciao_matrices(&dir, &coevolved, &whole);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `vivae tournament`'s rows against what the runs recorded.
fn tournament_agrees_with_the_ciao_matrices(dir: &Path, coevolved: &Path, fixed: &Path) {
    let csv = dir.join("t.csv");
    let table = ok(vivae()
        .arg("tournament")
        .arg(coevolved)
        .arg(fixed)
        .arg("--csv")
        .arg(&csv));
    assert_eq!(table.lines().count(), 9, "{table}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<String>> = (text.lines().skip(1))
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert_eq!(rows.len(), 8);
    let at = |hunters: &Path, sets: [&str; 2]| -> &Vec<String> {
        let h = hunters.to_string_lossy();
        (rows.iter())
            .find(|r| r[0] == h && r[2] == sets[0] && r[3] == sets[1])
            .unwrap()
    };
    // The co-evolved hunters' hall (4) against the fixed run's prey hall (5 of one prey).
    assert_eq!(at(coevolved, ["hall", "hall"])[4], "20");
    // The fixed run's hunters against its prey's source, the co-evolved run's prey champion:
    // the fixed run's CIAO matrix has those games (its champion's row).
    let champions: serde_json::Value =
        serde_json::from_slice(&read(fixed, "champions.json")).unwrap();
    let g = champions["hunter"]["generation"].as_u64().unwrap();
    let ciao = String::from_utf8(read(fixed, "ciao.csv")).unwrap();
    let cell: Vec<&str> = (ciao.lines())
        .find(|l| l.starts_with(&format!("{g},0,")))
        .unwrap()
        .split(',')
        .collect();
    let row = at(fixed, ["champion", "champion"]);
    assert_eq!(row[7], cell[2], "{row:?} {cell:?}");
    assert_eq!(row[5], cell[3]);
    // The same runs at one thread: the same table.
    let one = ok(vivae()
        .arg("tournament")
        .arg(coevolved)
        .arg(fixed)
        .args(["--threads", "1"]));
    assert_eq!(one, table);
}

#[test]
fn what_a_fixed_prey_or_a_tournament_cannot_do_is_refused_in_one_line() {
    let dir = scratch("fixed-prey-refused");
    let evolve = |toml: &str| {
        let path = dir.join("c.toml");
        std::fs::write(
            &path,
            format!("[experiment]\ntask = \"predator-prey\"\n{toml}"),
        )
        .unwrap();
        let mut cmd = vivae();
        cmd.args(["evolve", "-q", "--generations", "1", "--config"])
            .arg(&path)
            .arg("--out")
            .arg(dir.join("run"));
        cmd
    };
    refused(
        &mut evolve("[coevolution]\nopponents = \"fixed\"\n"),
        "coevolution.fixed_prey",
    );
    refused(
        &mut evolve("[coevolution]\nfixed_prey = \"x\"\n"),
        "coevolution.fixed_prey",
    );
    std::fs::write(dir.join("bad.json"), "{}").unwrap();
    let bad = dir.join("bad.json").to_string_lossy().into_owned();
    refused(
        &mut evolve(&format!(
            "[coevolution]\nopponents = \"fixed\"\nfixed_prey = {bad:?}\n"
        )),
        "champions.json",
    );
    let maze = dir.join("maze");
    ok(vivae()
        .args(["evolve", "-q", "--task", "maze", "--generations", "1"])
        .args(["--population", "8", "--steps", "20", "--out"])
        .arg(&maze));
    refused(
        vivae().arg("tournament").arg(&maze).arg(&maze),
        "not a predator-prey run",
    );
    refused(
        vivae().arg("tournament").arg(dir.join("none")).arg(&maze),
        "none",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

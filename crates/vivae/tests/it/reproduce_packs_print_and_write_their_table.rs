//! `vivae reproduce NAME` runs a pack's runs as `vivae evolve` would, prints
//! one Markdown table of ours beside the paper's and writes it to a file;
//! an unknown pack exits 2 naming the packs.

use crate::common::*;

#[test]
fn a_maze_pack_counts_the_runs_evolve_solves_and_writes_its_table() {
    let dir = scratch("reproduce-maze");
    let table_file = dir.join("t.md");
    let printed = ok(vivae()
        .args(["reproduce", "maze-hard", "--runs", "2", "--seed", "1"])
        .args(["--evaluations", "12000", "--threads", "1", "-q", "-o"])
        .arg(&table_file));
    assert_eq!(std::fs::read_to_string(&table_file).unwrap(), printed);
    assert!(printed.starts_with("### The hard maze"), "{printed}");
    assert!(
        printed.contains("Lehman & Stanley 2011, Evol. Comput. 19(2)"),
        "{printed}"
    );
    // The same runs from `vivae evolve`: 12,000 evaluations are 48 generations of 250.
    let mut solved = 0;
    for seed in ["1", "2"] {
        let line = ok(vivae()
            .args([
                "evolve",
                "-q",
                "--scenario",
                "hard-maze",
                "--strategy",
                "novelty",
            ])
            .args([
                "--generations",
                "48",
                "--threads",
                "1",
                "--seed",
                seed,
                "--out",
            ])
            .arg(dir.join(format!("run-{seed}"))));
        solved += usize::from(line.contains("solved=yes"));
    }
    let novelty = printed
        .lines()
        .find(|l| l.starts_with("| novelty search |"))
        .unwrap();
    assert!(novelty.contains(&format!("| {solved}/2 |")), "{novelty}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unknown_pack_exits_2_naming_the_packs() {
    let out = run(vivae().args(["reproduce", "maze-huge"]));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("maze-medium") && err.contains("maze-hard"),
        "{err}"
    );
    let list = ok(vivae().args(["reproduce", "--list"]));
    assert!(list.lines().any(|l| l.starts_with("maze-hard")), "{list}");
}

#[test]
fn every_pack_runs_at_tiny_settings_and_prints_its_sourced_table() {
    let dir = scratch("reproduce-every");
    let list = ok(vivae().args(["reproduce", "--list"]));
    let names: Vec<&str> = list
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    for name in [
        "xor",
        "pole-markov",
        "pole-nonmarkov",
        "boxes",
        "retina",
        "road",
    ] {
        assert!(names.contains(&name), "{name} not in {names:?}");
        let table_file = dir.join(format!("{name}.md"));
        let printed = ok(vivae()
            .args(["reproduce", name, "--runs", "1", "--evaluations", "200"])
            .args(["--threads", "1", "-q", "-o"])
            .arg(&table_file));
        assert_eq!(std::fs::read_to_string(&table_file).unwrap(), printed);
        assert!(printed.starts_with("### "), "{name}: {printed}");
        let header = printed.lines().find(|l| l.starts_with("| ")).unwrap();
        assert!(
            header.contains("ours") && header.ends_with("| source |"),
            "{name}: {header}"
        );
        let rows = printed.lines().filter(|l| l.starts_with("| ")).count();
        assert!(rows >= 3, "{name}: a header, its rule and a row: {printed}");
        assert!(
            printed.contains("seeds 1–1"),
            "{name}: the seeds are stated: {printed}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

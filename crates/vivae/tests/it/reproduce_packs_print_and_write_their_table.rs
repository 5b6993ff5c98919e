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
        "gym-classic",
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

#[test]
fn a_stopped_pack_continues_from_its_journal_and_picks_methods() {
    let dir = scratch("reproduce-journal");
    let table = dir.join("t.md");
    let pack = |extra: &[&str]| {
        let mut c = vivae();
        c.args(["reproduce", "maze-medium", "--runs", "2", "--seed", "4"])
            .args(["--evaluations", "1500", "--threads", "1", "-o"])
            .arg(&table)
            .args(extra);
        run(&mut c)
    };
    // One method first: the others' rows say so, and only its runs are journaled.
    let first = pack(&["--method", "neat"]);
    assert!(first.status.success(), "{first:?}");
    let printed = String::from_utf8_lossy(&first.stdout).to_string();
    let rows: Vec<&str> = printed.lines().filter(|l| l.starts_with("| ")).collect();
    assert!(rows[2].contains("not run (--method)"), "{printed}");
    assert!(
        rows[3].starts_with("| fitness-based NEAT | ") && rows[3].contains("/2 |"),
        "{printed}"
    );
    let journal = std::fs::read_to_string(dir.join("t.runs.tsv")).unwrap();
    assert_eq!(
        journal.lines().filter(|l| !l.starts_with('#')).count(),
        2,
        "{journal}"
    );
    // All methods: NEAT's runs come from the journal and give the same row.
    let all = pack(&[]);
    let err = String::from_utf8_lossy(&all.stderr);
    assert_eq!(err.matches("(from the journal)").count(), 2, "{err}");
    assert!(
        err.contains("medium-maze neat seed 5: ") && err.contains("medium-maze novelty seed 4: "),
        "{err}"
    );
    let again = String::from_utf8_lossy(&all.stdout).to_string();
    assert!(again.lines().any(|l| l == rows[3]), "{again}");
    // Without the journal every run is run, and the table is the same.
    let fresh = pack(&["--no-journal"]);
    assert_eq!(String::from_utf8_lossy(&fresh.stdout), again);
    assert!(!String::from_utf8_lossy(&fresh.stderr).contains("(from the journal)"));
    // A method the pack does not have, or a broken journal: one line, exit 2.
    let bad = pack(&["--method", "cma-es"]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no method \"cma-es\"") && err.contains("novelty, neat, map-elites"),
        "{err}"
    );
    // A file that is no journal is not vivae's to replace; a journal with a
    // broken line is refused naming the line.
    std::fs::write(dir.join("t.runs.tsv"), "garbage\n").unwrap();
    let broken = pack(&[]);
    let err = String::from_utf8_lossy(&broken.stderr);
    assert_eq!(broken.status.code(), Some(2), "{err}");
    assert!(
        err.contains("t.runs.tsv") && err.contains("not an earlier vivae reproduce journal"),
        "{err}"
    );
    let header = journal.lines().next().unwrap();
    std::fs::write(dir.join("t.runs.tsv"), format!("{header}\ngarbage\n")).unwrap();
    let broken = pack(&[]);
    let err = String::from_utf8_lossy(&broken.stderr);
    assert_eq!(broken.status.code(), Some(2), "{err}");
    assert!(
        err.contains("t.runs.tsv") && err.contains("line 2"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("t.runs.tsv")).unwrap(),
        format!("{header}\ngarbage\n")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `vivae report` refuses a run whose `generations.csv` or `population.csv`
//! is damaged (issue 24) with exit 2 and one line naming the file (and the
//! line, where there is one), and leaves `report.html` as it was: a fitness
//! that is not a finite number, no generation recorded, an empty file.

use std::path::Path;

use crate::common::*;

/// Replaces field `field` of line `line` (1-based, the header is line 1).
fn with_field(text: &str, line: usize, field: usize, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut f: Vec<&str> = lines[line - 1].split(',').collect();
    f[field] = value;
    lines[line - 1] = f.join(",");
    lines.join("\n") + "\n"
}

fn refused(run_dir: &Path, needles: &[&str]) {
    let before = read(run_dir, "report.html");
    let out = run(vivae().arg("report").arg(run_dir));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{needles:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err}");
    }
    assert!(
        before == read(run_dir, "report.html"),
        "report.html changed"
    );
}

#[test]
fn non_finite_fitness_missing_generations_and_empty_files_are_refused() {
    let dir = scratch("report-damaged");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let generations = String::from_utf8(read(&run_dir, "generations.csv")).unwrap();
    let population = String::from_utf8(read(&run_dir, "population.csv")).unwrap();
    let gpath = run_dir.join("generations.csv");
    let ppath = run_dir.join("population.csv");
    let header = |t: &str| format!("{}\n", t.lines().next().unwrap());
    let cases: Vec<(&Path, String, Vec<&str>)> = vec![
        (
            &ppath,
            with_field(&population, 2, 2, "NaN"),
            vec!["population.csv", "line 2", "finite"],
        ),
        (
            &ppath,
            with_field(&population, 5, 2, "inf"),
            vec!["population.csv", "line 5", "finite"],
        ),
        (
            &gpath,
            with_field(&generations, 3, 1, "NaN"),
            vec!["generations.csv", "line 3"],
        ),
        (
            &gpath,
            header(&generations),
            vec!["generations.csv", "no generation recorded"],
        ),
        (
            &ppath,
            header(&population),
            vec!["population.csv", "no generation recorded"],
        ),
        (&ppath, String::new(), vec!["population.csv"]),
        // Found by fuzzing: a generation far ahead used to allocate a row
        // for every generation skipped (24 GB for this one).
        (
            &ppath,
            format!("{}999999999,1,1\n", header(&population)),
            vec!["population.csv", "line 2", "generation 999999999"],
        ),
    ];
    for (path, text, needles) in cases {
        std::fs::write(path, text).unwrap();
        refused(&run_dir, &needles);
        std::fs::write(&gpath, &generations).unwrap();
        std::fs::write(&ppath, &population).unwrap();
    }
    ok(vivae().arg("report").arg(&run_dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

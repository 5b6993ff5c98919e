//! `vivae compare` groups runs by substrate (or `--label`), and its table and
//! CSV hold the medians of what the runs' `generations.csv` and `timing.csv`
//! say; a missing or corrupt run file is refused with exit 2 and one line
//! naming it, and nothing is written.

use crate::common::*;
use std::ffi::{OsStr, OsString};
use std::path::{Path, PathBuf};

fn a(s: impl AsRef<OsStr>) -> OsString {
    s.as_ref().to_owned()
}

/// Column `col` of a run CSV (header skipped).
fn column(dir: &Path, file: &str, col: usize) -> Vec<f64> {
    String::from_utf8(read(dir, file))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// The CSV's row for `group`, as (header, value) pairs.
fn csv_row(csv: &str, group: &str) -> Vec<(String, String)> {
    let mut lines = csv.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let row = lines
        .find(|l| l.split(',').next() == Some(group))
        .unwrap_or_else(|| panic!("no row {group} in {csv}"));
    head.into_iter()
        .zip(row.split(',').map(String::from))
        .collect()
}

fn get<'a>(row: &'a [(String, String)], key: &str) -> &'a str {
    &row.iter().find(|(k, _)| k == key).unwrap().1
}

/// Asserts exit 2 with one line on stderr containing `needle`, and no output written.
fn refused(args: &[OsString], out: &Path, needle: &str) {
    let result = run(vivae().arg("compare").args(args).arg("-o").arg(out));
    let stderr = String::from_utf8_lossy(&result.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(result.status.code(), Some(2), "{stderr}");
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(lines[0].contains(needle), "{needle:?} not in {stderr}");
    assert!(!stderr.contains("panicked"));
    assert!(!out.exists(), "{} written", out.display());
}

#[test]
fn table_and_csv_are_medians_of_the_runs_files() {
    let dir = scratch("compare");
    let config = write_small_config(&dir, 10);
    let runs: Vec<PathBuf> = ["a-s1", "a-s2", "b-s1"]
        .iter()
        .map(|n| dir.join(n))
        .collect();
    evolve(&config, &runs[0], &["--seed", "1"]);
    evolve(&config, &runs[1], &["--seed", "2"]);
    evolve(&config, &runs[2], &["--seed", "1", "--sensors", "3x6"]);

    let png = dir.join("cmp.png");
    let csv_path = dir.join("cmp.csv");
    let table = ok(vivae()
        .arg("compare")
        .args(&runs)
        .arg("-o")
        .arg(&png)
        .arg("--csv")
        .arg(&csv_path));
    assert!(read(&dir, "cmp.png").starts_with(b"\x89PNG"));
    let csv = String::from_utf8(read(&dir, "cmp.csv")).unwrap();

    // Two groups by substrate, in command-line order.
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| ---"))
        .collect();
    assert_eq!(rows.len(), 3, "{table}");
    assert!(rows[0].contains("best @ gen 10") && !rows[0].contains("gen 50"));
    assert!(rows[1].starts_with("| 3x5→3x3 | 2 | 10 |"), "{table}");
    assert!(rows[2].starts_with("| 3x6→3x3 | 1 | 10 |"), "{table}");

    let a = [&runs[0], &runs[1]];
    let best10 = median(
        a.iter()
            .map(|r| column(r, "generations.csv", 1)[9])
            .collect(),
    );
    let final_best = median(
        a.iter()
            .map(|r| {
                column(r, "generations.csv", 1)
                    .into_iter()
                    .fold(f64::MIN, f64::max)
            })
            .collect(),
    );
    let per_gen = median(
        a.iter()
            .map(|r| median(column(r, "timing.csv", 1)))
            .collect(),
    );
    let row = csv_row(&csv, "3x5→3x3");
    let num = |k: &str| get(&row, k).parse::<f64>().unwrap();
    assert_eq!(num("best_gen_10"), best10);
    assert_eq!(get(&row, "best_gen_10_runs"), "2");
    assert_eq!(get(&row, "best_gen_50"), "");
    assert_eq!(num("final_best"), final_best);
    assert!((num("seconds_per_generation") - per_gen).abs() < 1e-12);
    // The table shows the same numbers rounded.
    let cells: Vec<&str> = rows[1].split(" | ").collect();
    assert_eq!(cells[3], format!("{best10:.3}"));
    assert_eq!(cells[4], format!("{per_gen:.3}"));
    assert_eq!(cells.last().unwrap(), &format!("{final_best:.3} |"));
    // Tiny runs never last 30 s: not reached.
    assert_eq!(cells[5], "—");
    let single = csv_row(&csv, "3x6→3x3");
    assert_eq!(
        get(&single, "best_gen_10").parse::<f64>().unwrap(),
        column(&runs[2], "generations.csv", 1)[9]
    );

    // A label groups runs across substrates; unlabelled runs keep theirs.
    let svg = dir.join("cmp.svg");
    let table = ok(vivae()
        .arg("compare")
        .args(&runs)
        .args(["--label", "first seeds=*-s1"])
        .arg("-o")
        .arg(&svg));
    assert!(table.contains("| first seeds | 2 |"), "{table}");
    assert!(table.contains("| 3x5→3x3 | 1 |"), "{table}");
    assert!(
        String::from_utf8(read(&dir, "cmp.svg"))
            .unwrap()
            .contains("first seeds (2 runs")
    );
}

#[test]
fn missing_or_corrupt_run_files_exit_2_naming_the_file() {
    let dir = scratch("compare-bad");
    let config = write_small_config(&dir, 2);
    let good = dir.join("good");
    evolve(&config, &good, &[]);
    let out = dir.join("out.png");

    let copy = |name: &str| {
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        for f in ["generations.csv", "timing.csv", "config.toml"] {
            std::fs::copy(good.join(f), d.join(f)).unwrap();
        }
        d
    };
    let corrupt = copy("corrupt");
    let text = String::from_utf8(read(&corrupt, "generations.csv")).unwrap();
    std::fs::write(
        corrupt.join("generations.csv"),
        text.replacen("\n2,", "\n2,not-a-number", 1),
    )
    .unwrap();
    refused(
        &[a(&good), a(&corrupt)],
        &out,
        "corrupt/generations.csv: line 3",
    );

    let gap = copy("gap");
    let text = String::from_utf8(read(&gap, "timing.csv")).unwrap();
    std::fs::write(gap.join("timing.csv"), text.replacen("\n2,", "\n5,", 1)).unwrap();
    refused(
        &[a(&gap)],
        &out,
        "gap/timing.csv: line 3: generation 5 where 2 was expected",
    );

    let missing = copy("missing");
    std::fs::remove_file(missing.join("timing.csv")).unwrap();
    refused(&[a(&missing)], &out, "missing/timing.csv");

    let no_config = copy("no-config");
    std::fs::remove_file(no_config.join("config.toml")).unwrap();
    refused(&[a(&no_config)], &out, "no-config/config.toml");

    refused(
        &[a(dir.join("nowhere"))],
        &out,
        "nowhere: no such run directory",
    );
    refused(
        &[a(&good), a("--label"), a("x=zzz*")],
        &out,
        "--label x=zzz*: matches none",
    );
    refused(&[a(&good), a(&good)], &out, "given twice");
    // A missing folder is made (as evolve and replay make theirs); a file in the way is refused.
    let made = dir.join("made/for/it");
    ok(vivae()
        .arg("compare")
        .arg(&good)
        .arg("--csv")
        .arg(made.join("t.csv"))
        .arg("-o")
        .arg(made.join("c.png")));
    assert!(made.join("t.csv").is_file() && made.join("c.png").is_file());
    std::fs::write(dir.join("a-file"), b"").unwrap();
    refused(
        &[a(&good), a("--csv"), a(dir.join("a-file/t.csv"))],
        &out,
        "a-file is a file, not a folder",
    );
    let txt = dir.join("out.txt");
    refused(&[a(&good)], &txt, "must be a .png or .svg");

    // A run still writing its last line is read up to its last complete line
    // (this half-written one would not parse).
    let live = copy("live");
    let mut text = String::from_utf8(read(&live, "timing.csv")).unwrap();
    text.push_str("3,1e");
    std::fs::write(live.join("timing.csv"), text).unwrap();
    let table = ok(vivae().arg("compare").arg(&live).arg("-o").arg(&out));
    assert!(table.contains("| 3x5→3x3 | 1 | 2 |"), "{table}");
}

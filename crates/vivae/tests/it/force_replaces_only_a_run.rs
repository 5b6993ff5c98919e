//! `--force` replaces a vivae run and nothing else: a folder holding the
//! user's own files (beside a run's or instead of them), the working
//! directory, its parents and the home directory are refused with exit 2 and
//! one line, and every file in them is left as it was; a run (finished, with
//! its figures and report) is replaced by the new one.

use std::path::Path;

use crate::common::*;

/// `vivae evolve --force` of `config` into `out`, run from `cwd` with `home` as HOME.
fn forced(config: &Path, out: &Path, cwd: &Path, home: &Path) -> std::process::Output {
    run(vivae()
        .args(["evolve", "-q", "--force", "--config"])
        .arg(config)
        .arg("--out")
        .arg(out)
        .current_dir(cwd)
        .env("HOME", home))
}

fn assert_refused(out: &std::process::Output, why: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains(why), "{stderr}");
}

#[test]
fn force_replaces_a_run_and_refuses_every_other_folder() {
    let dir = scratch("force-only-runs");
    let config = write_small_config(&dir, 1);
    let home = dir.join("home");
    std::fs::create_dir(&home).unwrap();
    std::fs::write(home.join("thesis.tex"), "mine").unwrap();

    // A finished run (figures, report.html) is replaced.
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    assert!(run_dir.join("report.html").exists());
    let out = forced(&config, &run_dir, &dir, &home);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    assert!(run_dir.join("champion.json").exists());

    // The same run with a file of the user's: refused, nothing removed.
    std::fs::write(run_dir.join("notes.txt"), "mine").unwrap();
    let before = read(&run_dir, "generations.csv");
    assert_refused(
        &forced(&config, &run_dir, &dir, &home),
        "holds notes.txt, which vivae did not write",
    );
    assert_eq!(read(&run_dir, "notes.txt"), b"mine");
    assert_eq!(read(&run_dir, "generations.csv"), before);

    // A folder of the user's own files: refused.
    let mine = dir.join("mine");
    std::fs::create_dir_all(mine.join("sub")).unwrap();
    std::fs::write(mine.join("sub/data.csv"), "1,2\n").unwrap();
    assert_refused(&forced(&config, &mine, &dir, &home), "is not a vivae run");
    assert_eq!(read(&mine, "sub/data.csv"), b"1,2\n");

    // The working directory, a parent of it, the home directory.
    for (out, why) in [
        (Path::new("."), "is the working directory"),
        (Path::new(".."), "is a parent of the working directory"),
        (home.as_path(), "is the home directory"),
    ] {
        assert_refused(&forced(&config, out, &mine, &home), why);
    }
    assert_eq!(read(&mine, "sub/data.csv"), b"1,2\n");
    assert_eq!(read(&home, "thesis.tex"), b"mine");
    // Nothing was left beside them either.
    let mut left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["c.toml", "home", "mine", "run"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

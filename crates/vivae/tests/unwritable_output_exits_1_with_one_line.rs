//! An output the program cannot write is the machine's fault, not the user's
//! input: exit code 1 (not 2) with one line naming the path, and no panic.

mod common;
use common::*;

#[test]
fn unwritable_output_is_an_internal_error_naming_the_path() {
    let dir = scratch("unwritable");
    // A regular file where a folder is expected makes every write below it fail.
    let blocker = dir.join("not-a-folder");
    std::fs::write(&blocker, b"").unwrap();
    let figure = blocker.join("scenario.svg");
    let run_dir = blocker.join("run");
    let cases = [
        (
            vivae()
                .args(["scenario", "render", "-o"])
                .arg(&figure)
                .output()
                .unwrap(),
            figure,
        ),
        (
            vivae()
                .args(["evolve", "-q", "--generations", "1", "--out"])
                .arg(&run_dir)
                .output()
                .unwrap(),
            run_dir,
        ),
    ];
    for (out, path) in cases {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(&path.display().to_string()), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

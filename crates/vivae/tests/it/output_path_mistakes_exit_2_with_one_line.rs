//! An output path the user got wrong — `-o` into a missing folder or onto a
//! folder, `--out` below a file — is the user's mistake: exit code 2 with one
//! line naming the path, no panic, and nothing left behind. (A full disk or
//! another failure of the machine exits 1; see `vivae_lab::Error::is_bad_input`.)

use crate::common::*;

#[test]
fn output_path_mistakes_exit_2_naming_the_path() {
    let dir = scratch("unwritable");
    // A regular file where a folder is expected makes every write below it fail.
    let blocker = dir.join("not-a-folder");
    std::fs::write(&blocker, b"").unwrap();
    let a_folder = dir.join("a-folder");
    std::fs::create_dir(&a_folder).unwrap();
    let render = |out: &std::path::Path| {
        vivae()
            .args(["scenario", "render", "-o"])
            .arg(out)
            .output()
            .unwrap()
    };
    let below_file = blocker.join("scenario.svg");
    let missing_folder = dir.join("missing").join("scenario.svg");
    let run_dir = blocker.join("run");
    let cases = [
        (render(&below_file), below_file),
        (render(&missing_folder), missing_folder),
        (render(&a_folder), a_folder.clone()),
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
        assert_eq!(out.status.code(), Some(2), "{}: {stderr}", path.display());
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(&path.display().to_string()), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    // Nothing half-written next to the outputs, and the folder is untouched.
    let mut left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["a-folder", "not-a-folder"]);
    assert_eq!(std::fs::read_dir(&a_folder).unwrap().count(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

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

/// What a refused output must leave: exit code 2, one line naming the file
/// and `why`, and the file as it was (`before`: its bytes, or `None` when it
/// was not there and must still not be).
fn refused(out: std::process::Output, path: &std::path::Path, why: &str, before: Option<&[u8]>) {
    refused_in_one_line(out, path, why);
    let name = path.display();
    match before {
        Some(bytes) => assert_eq!(std::fs::read(path).unwrap(), bytes, "{name} changed"),
        None => assert!(std::fs::symlink_metadata(path).is_err(), "{name} appeared"),
    }
}

/// Exit code 2 and one line naming `path` and saying `why`.
fn refused_in_one_line(out: std::process::Output, path: &std::path::Path, why: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    let name = path.display().to_string();
    assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains(&name), "{name}: {stderr}");
    assert!(stderr.contains(why), "{why}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn every_output_flag_refuses_what_vivae_did_not_write_and_replaces_nothing() {
    let run = small_run("output-rules", 2);
    let dir = run.parent().unwrap().to_path_buf();
    let champion = run.join("champion.json");
    let champion_bytes = std::fs::read(&champion).unwrap();
    let export = |format: &str, out: &std::path::Path, extra: &[&str]| {
        vivae()
            .arg("export")
            .arg(&*run)
            .args(["--format", format, "-o"])
            .arg(out)
            .args(extra)
            .output()
            .unwrap()
    };
    // The run's own files, and anything else inside the run directory.
    refused(
        export("json", &champion, &["--force"]),
        &champion,
        "inside the run directory",
        Some(&champion_bytes),
    );
    let inside = run.join("figures").join("c.onnx");
    refused(
        export("onnx", &inside, &[]),
        &inside,
        "inside the run directory",
        None,
    );
    // A C file named as its header.
    let header = dir.join("x.h");
    refused(export("c", &header, &[]), &header, "ends in .h", None);
    // Special files: a FIFO, a symbolic link, a device, a folder.
    let fifo = dir.join("pipe.json");
    mkfifo(&fifo);
    refused_in_one_line(export("json", &fifo, &["--force"]), &fifo, "FIFO");
    use std::os::unix::fs::FileTypeExt;
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    let target = dir.join("target.json");
    std::fs::write(&target, b"mine").unwrap();
    let link = dir.join("link.json");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    refused(
        export("json", &link, &["--force"]),
        &link,
        "symbolic link",
        Some(b"mine"),
    );
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    let device = std::path::Path::new("/dev/null");
    refused_in_one_line(export("json", device, &["--force"]), device, "device");
    assert!(
        std::fs::metadata(device)
            .unwrap()
            .file_type()
            .is_char_device()
    );
    let folder = dir.join("a-folder");
    std::fs::create_dir(&folder).unwrap();
    refused_in_one_line(
        export("json", &folder, &["--force"]),
        &folder,
        "is a folder",
    );
    assert_eq!(std::fs::read_dir(&folder).unwrap().count(), 0);
    // A missing folder is named, not created.
    let missing = dir.join("missing").join("c.json");
    refused(export("json", &missing, &[]), &missing, "the folder", None);
    assert!(!dir.join("missing").exists());
    // Someone else's file: refused unless --force; an earlier export of the
    // same format is replaced, one of another format is not.
    let notes = dir.join("notes.json");
    std::fs::write(&notes, b"{\"mine\": true}").unwrap();
    refused(
        export("json", &notes, &[]),
        &notes,
        "--force",
        Some(b"{\"mine\": true}"),
    );
    ok(vivae()
        .arg("export")
        .arg(&*run)
        .args(["--format", "json", "--force", "-o"])
        .arg(&notes));
    assert_ne!(std::fs::read(&notes).unwrap(), b"{\"mine\": true}");
    let model = dir.join("c.onnx");
    for _ in 0..2 {
        ok(vivae()
            .arg("export")
            .arg(&*run)
            .args(["--format", "onnx", "-o"])
            .arg(&model));
    }
    let c = dir.join("ctl.c");
    for _ in 0..2 {
        ok(vivae()
            .arg("export")
            .arg(&*run)
            .args(["--format", "c", "-o"])
            .arg(&c));
    }
    let model_bytes = std::fs::read(&model).unwrap();
    refused(
        export("json", &model, &[]),
        &model,
        "not an earlier",
        Some(&model_bytes),
    );
    // The C file's header beside it is checked too.
    let theirs = dir.join("theirs.c");
    std::fs::write(dir.join("theirs.h"), b"/* mine */").unwrap();
    refused(
        export("c", &theirs, &[]),
        &dir.join("theirs.h"),
        "--force",
        Some(b"/* mine */"),
    );
    assert!(!theirs.exists());

    // The other commands' outputs follow the same rules, before any work.
    let nowhere = dir.join("no-such-run");
    let out = vivae()
        .arg("tournament")
        .arg(&nowhere)
        .arg(&nowhere)
        .arg("--csv")
        .arg(&champion)
        .output()
        .unwrap();
    refused(
        out,
        &champion,
        "inside the run directory",
        Some(&champion_bytes),
    );
    let out = vivae()
        .arg("tournament")
        .arg(&nowhere)
        .arg(&nowhere)
        .arg("--csv")
        .arg(&notes)
        .output()
        .unwrap();
    let notes_bytes = std::fs::read(&notes).unwrap();
    refused(
        out,
        &notes,
        "not an earlier vivae tournament CSV",
        Some(&notes_bytes),
    );
    let frame = dir.join("frame.png");
    for (flag, path, why) in [
        ("-o", &champion, "inside the run directory"),
        ("-o", &notes, "not an earlier vivae drive-image CSV"),
        (
            "--draw-map",
            &notes,
            "not an earlier vivae drive-image --draw-map PNG",
        ),
    ] {
        let before = std::fs::read(path).unwrap();
        let mut cmd = vivae();
        cmd.arg("drive-image").arg(&*run);
        if flag == "-o" {
            cmd.arg(&frame);
        }
        let out = cmd.arg(flag).arg(path).output().unwrap();
        refused(out, path, why, Some(&before));
    }
    let map = dir.join("map.png");
    for _ in 0..2 {
        ok(vivae()
            .arg("drive-image")
            .arg(&*run)
            .arg("--draw-map")
            .arg(&map));
    }
    let table = dir.join("r.md");
    let out = vivae()
        .args(["reproduce", "xor", "-o"])
        .arg(&table)
        .arg("--journal")
        .arg(&table)
        .output()
        .unwrap();
    refused(out, &table, "the same file as -o", None);
    let out = vivae()
        .args(["reproduce", "xor", "-o"])
        .arg(run.join("r.md"))
        .output()
        .unwrap();
    refused(out, &run.join("r.md"), "inside the run directory", None);
    let out = vivae()
        .args(["reproduce", "xor", "--no-journal", "-o"])
        .arg(&notes)
        .output()
        .unwrap();
    refused(
        out,
        &notes,
        "not an earlier vivae reproduce table",
        Some(&notes_bytes),
    );
    // Nothing was written into the run.
    assert_eq!(std::fs::read(&champion).unwrap(), champion_bytes);
    assert!(!inside.exists());
}

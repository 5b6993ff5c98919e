//! The one rule for a file the user names as an output (`-o`, `--csv`,
//! `--journal`, Python's `out=`): vivae never destroys what it did not write.
//!
//! [`check_outputs`] refuses, before anything is computed or written: an
//! empty name; a missing or non-folder parent (named; never created); a
//! path inside a run directory ([`crate::rundir::is_run_dir`]: its files
//! are the run's); a symbolic link, a folder, a FIFO, a device or a socket
//! (the atomic rename would replace it by a regular file); an existing
//! regular file that is not an earlier output of the same kind
//! ([`OutputKind`]) unless forced; and two outputs of one command naming
//! the same file. Each refusal is bad input on one line naming the file.

use std::fs;
use std::path::{Path, PathBuf};

use crate::error::{Error, Refusal, Result};
use crate::export::Format;
use crate::io::{bad_input, open_regular};

/// How many leading bytes of an existing file [`OutputKind::earlier`] sees.
pub const SNIFF_BYTES: usize = 4096;

/// What an output file is (declared in `io`, below the tasks that declare
/// kinds of their own).
pub use crate::io::OutputKind;

/// One output of a command: the file, the flag that named it, its kind.
#[derive(Debug, Clone)]
pub struct Output {
    /// The file as the user named it.
    pub path: PathBuf,
    /// The flag or argument that named it (`-o`, `--csv`, `out=`), for messages.
    pub flag: String,
    /// What the command writes there.
    pub kind: OutputKind,
}

impl Output {
    /// `path`, named by `flag`, to be written as `kind`.
    pub fn new(path: impl Into<PathBuf>, flag: impl Into<String>, kind: OutputKind) -> Output {
        Output {
            path: path.into(),
            flag: flag.into(),
            kind,
        }
    }

    /// The flag and the file as messages name them (`-o x.c`, `out='x.c'`).
    fn named(&self) -> String {
        if self.flag.ends_with('=') {
            format!("{}{:?}", self.flag, self.path.display().to_string())
        } else {
            format!("{} {}", self.flag, self.path.display())
        }
    }
}

/// `text` at the start of the file, after nothing else.
fn starts(bytes: &[u8], text: &str) -> bool {
    bytes.starts_with(text.as_bytes())
}

/// `vivae export --format c`'s C file and header: both open with this comment.
pub const C_EXPORT: OutputKind = OutputKind {
    what: "vivae export C file",
    earlier: |b| starts(b, "/* Written by vivae export: "),
};

/// `vivae export --format json`: a document whose first key names the format.
pub const JSON_EXPORT: OutputKind = OutputKind {
    what: "vivae export JSON file",
    earlier: |b| {
        let head = String::from_utf8_lossy(b);
        let first_key = format!("\"format\": \"{}\"", crate::export::json::FORMAT);
        head.trim_start().starts_with('{')
            && (head.lines().take(3)).any(|l| l.trim_start().starts_with(&first_key))
    },
};

/// `vivae export --format onnx`: a model whose IR version (field 1, a
/// varint) is followed by the producer name `vivae` (field 2).
pub const ONNX_EXPORT: OutputKind = OutputKind {
    what: "vivae export ONNX model",
    earlier: |b| {
        let Some(rest) = b.strip_prefix(&[0x08]) else {
            return false;
        };
        let varint = rest.iter().take_while(|&&x| x & 0x80 != 0).count() + 1;
        rest.get(varint..)
            .is_some_and(|r| r.starts_with(b"\x12\x05vivae"))
    },
};

/// `vivae reproduce`'s Markdown table: a `### ` heading, a blank line, then
/// a table's heading row and its `| --- |` rule.
pub const REPRODUCE_TABLE: OutputKind = OutputKind {
    what: "vivae reproduce table",
    earlier: |b| {
        let head = String::from_utf8_lossy(b);
        let lines: Vec<&str> = head.lines().take(4).collect();
        match lines[..] {
            [title, "", columns, rule] => {
                title.starts_with("### ")
                    && columns.starts_with("| ")
                    && rule.starts_with("| --- |")
                    && rule.trim_end().ends_with("--- |")
            }
            _ => false,
        }
    },
};

/// `vivae reproduce`'s journal of finished runs.
pub const REPRODUCE_JOURNAL: OutputKind = OutputKind {
    what: "vivae reproduce journal",
    earlier: |b| starts(b, crate::reproduce::JOURNAL_HEADER),
};

/// The files `vivae export --format FORMAT -o path` writes, each with its
/// kind: the C file and its header beside it (`.h`, so the C file may not
/// itself end in `.h`), or the one model or document.
pub fn export_outputs(format: Format, path: &Path, flag: &str) -> Result<Vec<Output>> {
    let one = |kind| Ok(vec![Output::new(path, flag, kind)]);
    match format {
        Format::Json => one(JSON_EXPORT),
        Format::Onnx => one(ONNX_EXPORT),
        Format::C => {
            let out = Output::new(path, flag, C_EXPORT);
            if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("h"))
            {
                return Err(bad_input(format!(
                    "{}: the C file's name ends in .h, but its header is written beside it \
                     with that name (name the C file, e.g. {})",
                    out.named(),
                    path.with_extension("c").display()
                )));
            }
            let header = Output::new(path.with_extension("h"), flag, C_EXPORT);
            Ok(vec![out, header])
        }
    }
}

/// Checks that every one of a command's `outputs` may be written (see the
/// module's rules); `force` allows replacing an existing regular file that
/// is not an earlier output of its kind. Nothing is created or changed.
pub fn check_outputs(outputs: &[Output], force: bool) -> Result<()> {
    let mut seen: Vec<(PathBuf, &Output)> = Vec::new();
    for out in outputs {
        let at = check_one(out, force)?;
        if let Some((_, first)) = seen.iter().find(|(p, _)| *p == at) {
            return Err(bad_input(format!(
                "{}: the same file as {}; each output needs a file of its own",
                out.named(),
                first.named()
            )));
        }
        seen.push((at, out));
    }
    Ok(())
}

/// [`check_outputs`] for a command's one output.
pub fn check_output(output: &Output, force: bool) -> Result<()> {
    check_outputs(std::slice::from_ref(output), force)
}

/// Checks one output; returns where it is (its folder resolved), to compare.
fn check_one(out: &Output, force: bool) -> Result<PathBuf> {
    let refuse = |why: String| Err(bad_input(format!("{}: {why}", out.named())));
    let path = &out.path;
    if path.as_os_str().is_empty() {
        return refuse("the file name is empty".into());
    }
    let Some(name) = path.file_name() else {
        return refuse("names a folder, not a file".into());
    };
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let folder = match fs::canonicalize(parent) {
        Ok(f) if f.is_dir() => f,
        Ok(_) => return refuse(format!("{} is not a folder", parent.display())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return refuse(format!(
                "the folder {} does not exist (create it first)",
                parent.display()
            ));
        }
        Err(e) => {
            return refuse(format!(
                "{}: {}",
                parent.display(),
                crate::io::io_reason(&e)
            ));
        }
    };
    if let Some(run) = folder.ancestors().find(|a| crate::rundir::is_run_dir(a)) {
        return refuse(format!(
            "is inside the run directory {}, whose files are the run's (choose a file outside it)",
            run.display()
        ));
    }
    let meta = match fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(folder.join(name)),
        Err(e) => return refuse(crate::io::io_reason(&e)),
    };
    let ft = meta.file_type();
    use std::os::unix::fs::FileTypeExt;
    let special = if ft.is_symlink() {
        Some("is a symbolic link (vivae replaces only a regular file; name the file itself)")
    } else if ft.is_dir() {
        Some("is a folder (name a file in it)")
    } else if ft.is_fifo() {
        Some("is a FIFO (named pipe), not a regular file")
    } else if ft.is_char_device() || ft.is_block_device() {
        Some("is a device, not a regular file")
    } else if ft.is_socket() {
        Some("is a socket, not a regular file")
    } else if !ft.is_file() {
        Some("is not a regular file")
    } else {
        None
    };
    if let Some(why) = special {
        return refuse(why.into());
    }
    if !force && !is_earlier(path, out.kind) {
        return Err(Error::Refused(
            Refusal::text(format!(
                "{}: exists and is not an earlier {} (choose another file, or pass ",
                out.named(),
                out.kind.what
            ))
            .on("force")
            .then(" to replace it)"),
        ));
    }
    Ok(folder.join(name))
}

/// Whether the regular file at `path` begins as an earlier output of `kind`.
fn is_earlier(path: &Path, kind: OutputKind) -> bool {
    let Ok((file, _)) = open_regular(path) else {
        return false;
    };
    let mut head = Vec::with_capacity(SNIFF_BYTES);
    let read = std::io::Read::read_to_end(
        &mut std::io::Read::take(file, SNIFF_BYTES as u64),
        &mut head,
    );
    read.is_ok() && (kind.earlier)(&head)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vivae-output-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn refusal(out: &Output, force: bool) -> String {
        let e = check_output(out, force).unwrap_err();
        assert!(e.is_bad_input(), "{e:?}");
        let m = e.to_string();
        assert_eq!(m.lines().count(), 1, "{m}");
        m
    }

    #[test]
    fn each_rule_refuses_naming_the_file_and_what_is_wrong() {
        let dir = scratch("rules");
        let json = |p: &Path| Output::new(p, "-o", JSON_EXPORT);
        assert!(check_output(&json(&dir.join("new.json")), false).is_ok());
        let m = refusal(&json(Path::new("")), false);
        assert!(m.contains("empty"), "{m}");
        let m = refusal(&json(&dir.join("missing/x.json")), true);
        assert!(m.contains("missing") && m.contains("does not exist"), "{m}");
        let m = refusal(&json(&dir), true);
        assert!(m.contains("is a folder"), "{m}");
        std::os::unix::fs::symlink(dir.join("new.json"), dir.join("link.json")).unwrap();
        let m = refusal(&json(&dir.join("link.json")), true);
        assert!(m.contains("symbolic link"), "{m}");
        let m = refusal(&json(Path::new("/dev/null")), true);
        assert!(m.contains("device"), "{m}");
        fs::write(dir.join("mine.json"), "{\"mine\": 1}").unwrap();
        let m = refusal(&json(&dir.join("mine.json")), false);
        assert!(
            m.contains("mine.json") && m.contains("`force = true`"),
            "{m}"
        );
        assert!(check_output(&json(&dir.join("mine.json")), true).is_ok());
        fs::write(
            dir.join("earlier.json"),
            "{\n  \"format\": \"vivae-controller\",\n",
        )
        .unwrap();
        assert!(check_output(&json(&dir.join("earlier.json")), false).is_ok());
        // Another kind's earlier file is not this kind's.
        let c = Output::new(dir.join("earlier.json"), "-o", C_EXPORT);
        assert!(check_output(&c, false).is_err());

        let run = dir.join("run");
        fs::create_dir_all(run.join("checkpoints/deeper")).unwrap();
        fs::write(run.join("config.toml"), "").unwrap();
        for p in [run.join("champion.json"), run.join("checkpoints/deeper/x")] {
            let m = refusal(&json(&p), true);
            assert!(m.contains("inside the run directory"), "{m}");
        }
        // The run directory itself is a folder, not a file.
        let m = refusal(&json(&run), true);
        assert!(m.contains("is a folder"), "{m}");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_c_file_may_not_be_a_header_and_two_outputs_may_not_share_a_file() {
        let dir = scratch("pairs");
        let e = export_outputs(Format::C, &dir.join("x.h"), "-o").unwrap_err();
        assert!(e.to_string().contains("x.c"), "{e}");
        let outs = export_outputs(Format::C, &dir.join("x.c"), "-o").unwrap();
        assert_eq!(outs[1].path, dir.join("x.h"));
        check_outputs(&outs, false).unwrap();
        let same = [
            Output::new(dir.join("r.md"), "-o", REPRODUCE_TABLE),
            Output::new(dir.join(".").join("r.md"), "--journal", REPRODUCE_JOURNAL),
        ];
        let e = check_outputs(&same, false).unwrap_err().to_string();
        assert!(
            e.contains("--journal") && e.contains("same file as -o"),
            "{e}"
        );
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn earlier_outputs_are_recognised_by_their_first_bytes() {
        assert!((ONNX_EXPORT.earlier)(b"\x08\x08\x12\x05vivae\x1a"));
        assert!(!(ONNX_EXPORT.earlier)(b"\x08\x08\x12\x07pytorch"));
        assert!((REPRODUCE_TABLE.earlier)(
            b"### T\n\n| a | b |\n| --- | --- |\n"
        ));
        assert!(!(REPRODUCE_TABLE.earlier)(b"### My notes\n\nsome text\n"));
        assert!((C_EXPORT.earlier)(
            b"/* Written by vivae export: champion. */\n"
        ));
    }
}

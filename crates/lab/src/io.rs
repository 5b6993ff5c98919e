//! File input and output: atomic writes, reading inputs with one-line errors.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use vivae_sim::Scenario;

use crate::error::{Error, Result};

pub use crate::error::one_line;

/// FNV-1a 64 of `bytes`: the checksum of checkpoints and stored training maps.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// `name` with every character but ASCII letters, digits, `-` and `_`
/// replaced by `_`: a file-name stem every file system accepts.
pub fn safe_file_stem(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// An [`Error::Invalid`]: bad input from the user (exit code 2) that is not about one file.
pub fn bad_input(message: impl Into<String>) -> Error {
    Error::Invalid(message.into())
}

/// The default scenario shipped in the binary (`scenarios/roads.svg`).
pub const DEFAULT_SCENARIO: &str = vivae_sim::ROADS_SVG;

/// Name the embedded default scenario goes by in messages.
pub const DEFAULT_SCENARIO_NAME: &str = "roads.svg (embedded default)";

/// Writes `bytes` to `path` atomically: a temporary file beside it, then rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| -> std::io::Result<()> {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = fs::remove_file(&tmp);
        return Err(Error::io("write", path)(e));
    }
    Ok(())
}

/// Largest input file read (scenario, config, genome, checkpoint), in bytes.
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// Reads a whole input file as UTF-8; errors are bad input naming the file.
///
/// Every file the user names goes through here. Only regular files (after
/// following symlinks) of at most [`MAX_INPUT_BYTES`] are read: a FIFO would
/// block forever and `/dev/zero` would be read until memory runs out.
pub fn read_text(path: &Path) -> Result<String> {
    let unreadable = |reason: String| Error::Read {
        path: path.to_path_buf(),
        reason,
    };
    let bytes = read_regular(path, MAX_INPUT_BYTES).map_err(|e| unreadable(io_reason(&e)))?;
    String::from_utf8(bytes).map_err(|_| unreadable("not UTF-8 text".into()))
}

/// `open(2)`'s `O_NONBLOCK`: opening a FIFO with it returns at once instead
/// of waiting for a writer (the file is then refused as not regular).
const O_NONBLOCK: i32 = libc::O_NONBLOCK;

/// Opens `path` (following symlinks) for reading if it is a regular file.
///
/// Opened without blocking, then checked on the open file: a FIFO, a device
/// or a socket, even one swapped in after a check, is refused without
/// waiting, with an error whose message says what it is.
pub fn open_regular(path: &Path) -> std::io::Result<(fs::File, fs::Metadata)> {
    use std::os::unix::fs::OpenOptionsExt;
    let file = fs::OpenOptions::new()
        .read(true)
        .custom_flags(O_NONBLOCK)
        .open(path)?;
    let meta = file.metadata()?;
    check_kind(&meta)
        .map_err(|what| std::io::Error::new(std::io::ErrorKind::InvalidInput, what))?;
    Ok((file, meta))
}

/// Reads the whole of the regular file `path`, refusing one over `max` bytes
/// (also one that grows past it while read); see [`open_regular`].
pub fn read_regular(path: &Path, max: u64) -> std::io::Result<Vec<u8>> {
    let (file, meta) = open_regular(path)?;
    let over = || std::io::Error::new(std::io::ErrorKind::InvalidData, too_big_for(max));
    if meta.len() > max {
        return Err(over());
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::io::Read::read_to_end(&mut std::io::Read::take(file, max + 1), &mut bytes)?;
    if bytes.len() as u64 > max {
        return Err(over());
    }
    Ok(bytes)
}

/// [`read_regular`] as UTF-8 text.
pub fn read_regular_text(path: &Path, max: u64) -> std::io::Result<String> {
    String::from_utf8(read_regular(path, max)?)
        .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"))
}

fn too_big_for(max: u64) -> String {
    if max >= 1 << 20 {
        format!("larger than the input size limit of {} MiB", max >> 20)
    } else {
        format!("larger than the input size limit of {max} bytes")
    }
}

/// Refuses anything but a regular file, saying what it is instead.
fn check_kind(meta: &fs::Metadata) -> std::result::Result<(), String> {
    let ft = meta.file_type();
    if ft.is_file() {
        return Ok(());
    }
    use std::os::unix::fs::FileTypeExt;
    let what = if ft.is_dir() {
        "is a directory"
    } else if ft.is_fifo() {
        "is a FIFO (named pipe), not a regular file"
    } else if ft.is_char_device() || ft.is_block_device() {
        "is a device, not a regular file"
    } else if ft.is_socket() {
        "is a socket, not a regular file"
    } else {
        "is not a regular file"
    };
    Err(what.into())
}

/// A short reason for an I/O error, without the OS error code noise.
pub fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file or directory".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        std::io::ErrorKind::IsADirectory => "is a directory".into(),
        _ => e.to_string(),
    }
}

/// A scenario and the SVG text it was loaded from.
#[derive(Debug, Clone)]
pub struct LoadedScenario {
    /// The parsed scenario.
    pub scenario: Scenario,
    /// Its SVG text (copied into run directories).
    pub text: String,
}

/// Creates `path` and its missing parents; a file in the way is the user's
/// mistake and is named (the OS would only say "File exists").
pub fn create_dirs(path: &Path) -> Result<()> {
    create_dirs_for(path, path)
}

/// [`create_dirs`] for the folders that will hold `output`: errors name `output`.
pub fn create_dirs_for(path: &Path, output: &Path) -> Result<()> {
    fs::create_dir_all(path).map_err(|e| {
        let blocker = path
            .ancestors()
            .find(|a| !a.as_os_str().is_empty() && a.exists() && !a.is_dir());
        match blocker {
            Some(b) => bad_input(format!(
                "cannot create {}: {} is a file, not a folder",
                output.display(),
                b.display()
            )),
            None => Error::io("create", output)(e),
        }
    })
}

/// A fresh `runs/<timestamp>` directory name (suffixed if taken).
pub fn default_run_dir() -> PathBuf {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let stamp = utc_stamp(secs);
    let base = PathBuf::from("runs").join(&stamp);
    if !base.exists() {
        return base;
    }
    (2..)
        .map(|i| PathBuf::from("runs").join(format!("{stamp}-{i}")))
        .find(|p| !p.exists())
        .expect("some suffix is free")
}

/// `YYYYMMDD-HHMMSS` in UTC for a Unix time (no time-zone database needed).
fn utc_stamp(secs: u64) -> String {
    let days = secs / 86_400;
    let rem = secs % 86_400;
    // Civil-from-days (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = if m <= 2 { y + 1 } else { y };
    format!(
        "{y:04}{m:02}{d:02}-{:02}{:02}{:02}",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

/// Short name of a scenario for file names and titles: its file stem, or
/// `roads` for the embedded default.
pub fn scenario_name(path: Option<&Path>) -> String {
    path.and_then(Path::file_stem)
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "roads".to_string())
}

/// `field` as one CSV field (RFC 4180): quoted, its quotes doubled, when it
/// holds a comma, a quote or a line break; as it is otherwise.
pub fn csv_field(field: &str) -> std::borrow::Cow<'_, str> {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\"")).into()
    } else {
        field.into()
    }
}

/// What an output file is, so that an existing file can be recognised as an
/// earlier one of the same kind (which is replaced without `--force`).
#[derive(Debug, Clone, Copy)]
pub struct OutputKind {
    /// What it is, for messages (`vivae export's C file`).
    pub what: &'static str,
    /// Whether an existing file's first bytes (at most [`crate::output_path::SNIFF_BYTES`]) are an
    /// earlier output of this kind.
    pub earlier: fn(&[u8]) -> bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_stamp_known_dates() {
        assert_eq!(utc_stamp(0), "19700101-000000");
        assert_eq!(utc_stamp(951_782_400), "20000229-000000");
        assert_eq!(utc_stamp(1_795_303_182), "20261121-231942");
    }

    #[test]
    fn atomic_write_replaces_and_leaves_no_temp() {
        let dir = std::env::temp_dir().join(format!("vivae-io-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"two");
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1);
        fs::remove_dir_all(&dir).unwrap();
    }
}

//! Replacing a run directory (`--force`, `force=True`): only a vivae run is
//! ever replaced, and only by swapping a complete new run in its place, so
//! that `--force` never deletes a file vivae did not write and a failure
//! leaves the old run as it was.
//!
//! A directory is a vivae run when it holds `config.toml` and `checkpoints/`
//! and nothing but the files and folders [`crate::rundir`] and the program
//! write there (their names are listed in [`crate::rundir::files`]). The
//! working directory, its parents and the home directory are refused even
//! when they look like a run: replacing them would pull the ground from
//! under the user's shell.

use std::fs;
use std::path::{Path, PathBuf};

use crate::error::{Error, Refusal, Result};
use crate::rundir::{MANIFEST, MAPS_DIR, RunLock, files};

/// Top-level files every run directory may hold; beside them, the files
/// the search strategies write ([`is_run_file`]).
const RUN_FILES: [&str; 10] = [
    files::CONFIG,
    files::SCENARIO,
    files::GENERATIONS,
    files::POPULATION,
    files::TIMING,
    files::CHAMPION,
    files::INIT_POPULATION,
    files::BEST_GENOMES,
    files::REPORT,
    files::VALIDATION,
];

/// Whether a run directory may hold a top-level file called `name`: one of
/// [`RUN_FILES`] or one of `strategy_files`, those the registered search
/// strategies write with each checkpoint (their entries' `files`, which the
/// caller collects: this module sits below the strategies).
fn is_run_file(name: &str, strategy_files: &[&str]) -> bool {
    RUN_FILES.contains(&name) || strategy_files.contains(&name)
}

/// The folder `vivae replay RUN` writes its outputs to by default.
pub const REPLAY_DIR: &str = "replay";

/// A run directory about to be replaced, locked so that no other process
/// writes it meanwhile.
pub(crate) struct OldRun {
    _lock: RunLock,
    /// The files beside [`RUN_FILES`] that a run may hold (strategies').
    strategy_files: Vec<&'static str>,
}

/// Checks that a new run may be written at `dir`: `None` when nothing is
/// there; with `force`, the existing run (locked) that the new one replaces;
/// anything else is refused in one line. A run may hold `strategy_files`
/// beside the files every run holds (see [`is_run_file`]).
pub(crate) fn check_target(
    dir: &Path,
    force: bool,
    strategy_files: &[&'static str],
) -> Result<Option<OldRun>> {
    let meta = match fs::symlink_metadata(dir) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(Error::io("inspect", dir)(e)),
    };
    if !force {
        return Err(Error::Refused(
            Refusal::text(format!(
                "{}: already exists (choose another ",
                dir.display()
            ))
            .key("out")
            .then(", or pass ")
            .on("force")
            .then(" to replace the run there)"),
        ));
    }
    let refuse = |why: String| {
        Err(Error::Refused(
            Refusal::text(format!("{}: {why}; ", dir.display()))
                .on("force")
                .then(" replaces only a vivae run directory (choose another ")
                .key("out")
                .then(")"),
        ))
    };
    if let Some(why) = protected(dir) {
        return refuse(why);
    }
    if meta.file_type().is_symlink() {
        return refuse("is a symbolic link".into());
    }
    if !meta.is_dir() {
        return refuse("exists and is not a directory".into());
    }
    if let Some(why) = not_a_run(dir, strategy_files)? {
        return refuse(why);
    }
    Ok(Some(OldRun {
        _lock: RunLock::acquire(dir)?,
        strategy_files: strategy_files.to_vec(),
    }))
}

/// Why `dir` may never be replaced: it is the working directory, one of its
/// parents, the home directory or one of its parents.
fn protected(dir: &Path) -> Option<String> {
    let target = fs::canonicalize(dir).ok()?;
    if let Ok(cwd) = std::env::current_dir().and_then(fs::canonicalize)
        && cwd.starts_with(&target)
    {
        return Some(if cwd == target {
            "is the working directory".into()
        } else {
            "is a parent of the working directory".into()
        });
    }
    let home = std::env::var_os("HOME").and_then(|h| fs::canonicalize(h).ok());
    match home {
        Some(h) if h.starts_with(&target) => Some(if h == target {
            "is the home directory".into()
        } else {
            "is a parent of the home directory".into()
        }),
        _ => None,
    }
}

/// Why the directory `dir` is not a run vivae may replace (`None`: it is one,
/// or it is empty).
fn not_a_run(dir: &Path, strategy_files: &[&str]) -> Result<Option<String>> {
    let entries = list(dir)?;
    if entries.is_empty() {
        return Ok(None);
    }
    let has = |name: &str| entries.iter().any(|(n, _)| n == name);
    if !has(files::CONFIG) || !has(files::CHECKPOINTS) {
        return Ok(Some(format!(
            "is not a vivae run (it has no {} and {}/)",
            files::CONFIG,
            files::CHECKPOINTS
        )));
    }
    Ok(foreign(dir, &entries, strategy_files)?.map(|path| {
        format!(
            "holds {}, which vivae did not write",
            path.strip_prefix(dir).unwrap_or(&path).display()
        )
    }))
}

/// The names in `dir` with whether each is a real directory (not a link to one).
fn list(dir: &Path) -> Result<Vec<(String, bool)>> {
    let mut out = Vec::new();
    for entry in fs::read_dir(dir).map_err(Error::io("list", dir))? {
        let entry = entry.map_err(Error::io("list", dir))?;
        let is_dir = entry.file_type().map(|t| t.is_dir()).unwrap_or(false);
        out.push((entry.file_name().to_string_lossy().into_owned(), is_dir));
    }
    Ok(out)
}

/// The first entry of the run directory `dir` (listed as `entries`) that
/// vivae would not have written, if any.
fn foreign(
    dir: &Path,
    entries: &[(String, bool)],
    strategy_files: &[&str],
) -> Result<Option<PathBuf>> {
    for (name, is_dir) in entries {
        let known = match is_dir {
            false => is_run_file(name, strategy_files) || is_temporary(name),
            true => subfolder_accepts(name).is_some(),
        };
        if !known {
            return Ok(Some(dir.join(name)));
        }
        if let (true, Some(accepts)) = (is_dir, subfolder_accepts(name)) {
            let sub = dir.join(name);
            for (inner, inner_dir) in list(&sub)? {
                if inner_dir || !(accepts(&inner) || is_temporary(&inner)) {
                    return Ok(Some(sub.join(inner)));
                }
            }
        }
    }
    Ok(None)
}

/// For a folder vivae writes in a run directory, which file names it holds.
fn subfolder_accepts(name: &str) -> Option<fn(&str) -> bool> {
    fn checkpoint(n: &str) -> bool {
        n.starts_with("gen-") && n.ends_with(".ckpt")
    }
    fn figure(n: &str) -> bool {
        n == files::DRAWN || n.ends_with(".svg") || n.ends_with(".png")
    }
    fn map(n: &str) -> bool {
        n == MANIFEST || n.ends_with(".svg")
    }
    fn replay(n: &str) -> bool {
        [".svg", ".png", ".json", ".txt", ".csv"]
            .iter()
            .any(|ext| n.ends_with(ext))
    }
    match name {
        files::CHECKPOINTS => Some(checkpoint),
        files::FIGURES => Some(figure),
        MAPS_DIR => Some(map),
        REPLAY_DIR => Some(replay),
        _ => None,
    }
}

/// A temporary file of an atomic write (`.NAME.tmp-PID`).
fn is_temporary(name: &str) -> bool {
    name.starts_with('.') && name.contains(".tmp-")
}

/// Puts the complete new run `new` at `dir`, in place of `old` if any: the
/// old run is renamed aside, the new one renamed in, and only then the old
/// one's files are removed (put back if the second rename fails).
pub(crate) fn swap_in(new: &Path, dir: &Path, old: Option<OldRun>) -> Result<()> {
    let Some(old) = old else {
        return fs::rename(new, dir).map_err(Error::io("create", dir));
    };
    let aside = aside_path(dir);
    fs::rename(dir, &aside).map_err(Error::io("move aside", dir))?;
    if let Err(e) = fs::rename(new, dir) {
        let _ = fs::rename(&aside, dir);
        return Err(Error::io("create", dir)(e));
    }
    remove_run_files(&aside, &old.strategy_files);
    drop(old);
    Ok(())
}

/// The hidden sibling the old run is moved to while it is replaced.
fn aside_path(dir: &Path) -> PathBuf {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into());
    dir.with_file_name(format!(".{name}.old-{}", std::process::id()))
}

/// Removes the files of the old run at `dir` one by one, only those vivae
/// writes (a file that appeared since it was checked stays, with its folder).
fn remove_run_files(dir: &Path, strategy_files: &[&str]) {
    let Ok(entries) = list(dir) else {
        return;
    };
    for (name, is_dir) in entries {
        let path = dir.join(&name);
        match (is_dir, subfolder_accepts(&name)) {
            (false, _) if is_run_file(&name, strategy_files) || is_temporary(&name) => {
                let _ = fs::remove_file(&path);
            }
            (true, Some(accepts)) => {
                for (inner, inner_dir) in list(&path).unwrap_or_default() {
                    if !inner_dir && (accepts(&inner) || is_temporary(&inner)) {
                        let _ = fs::remove_file(path.join(inner));
                    }
                }
                let _ = fs::remove_dir(&path);
            }
            _ => {}
        }
    }
    let _ = fs::remove_dir(dir);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rundir::tests::scratch;

    /// A folder shaped like a run: config, a checkpoint, a figure.
    fn fake_run(dir: &Path) {
        fs::create_dir_all(dir.join("checkpoints")).unwrap();
        fs::create_dir_all(dir.join("figures")).unwrap();
        fs::write(dir.join("config.toml"), "").unwrap();
        fs::write(dir.join("checkpoints/gen-000001.ckpt"), "x").unwrap();
        fs::write(dir.join("figures/network.png"), "x").unwrap();
    }

    #[test]
    fn only_a_run_or_an_empty_folder_is_replaceable() {
        let root = scratch("check");
        let run = root.join("run");
        fake_run(&run);
        assert!(check_target(&run, true, &[]).unwrap().is_some());
        let e = check_target(&run, false, &[]).err().unwrap();
        // The library names the settings by key; a front end spells them.
        let own = e.to_string();
        assert!(
            own.contains("`force = true`") && own.contains("`out`"),
            "{own}"
        );
        let flags = crate::run::prepare::Spelling {
            origin: "command line",
            key: |k| format!("--{k} "),
            on: |k| format!("--{k}"),
        };
        let said = flags.error(&e);
        assert!(
            said.ends_with("(choose another --out, or pass --force to replace the run there)"),
            "{said}"
        );
        assert!(
            check_target(&root.join("none"), false, &[])
                .unwrap()
                .is_none()
        );
        fs::create_dir(root.join("empty")).unwrap();
        assert!(
            check_target(&root.join("empty"), true, &[])
                .unwrap()
                .is_some()
        );

        fs::write(run.join("notes.txt"), "mine").unwrap();
        let e = check_target(&run, true, &[]).err().unwrap();
        assert!(e.is_bad_input());
        assert!(e.to_string().contains("holds notes.txt"), "{e}");
        // A file a strategy writes is a run's when the caller names it.
        assert!(check_target(&run, true, &["notes.txt"]).unwrap().is_some());
        fs::remove_file(run.join("notes.txt")).unwrap();
        fs::write(run.join("figures/mine.pdf"), "mine").unwrap();
        let e = check_target(&run, true, &[]).err().unwrap();
        assert!(e.to_string().contains("figures/mine.pdf"), "{e}");

        let other = root.join("other");
        fs::create_dir(&other).unwrap();
        fs::write(other.join("thesis.tex"), "mine").unwrap();
        let e = check_target(&other, true, &[]).err().unwrap();
        assert!(e.to_string().contains("is not a vivae run"), "{e}");
        for protected in [Path::new("."), Path::new(".."), Path::new("/")] {
            let e = check_target(protected, true, &[]).err().unwrap();
            assert!(e.to_string().contains("working directory"), "{e}");
            assert_eq!(e.to_string().lines().count(), 1);
        }
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_swap_removes_only_what_vivae_wrote_and_a_failed_one_keeps_the_old_run() {
        let root = scratch("swap");
        let run = root.join("run");
        fake_run(&run);
        let new = root.join(".run.tmp-1");
        fake_run(&new);
        fs::write(new.join("config.toml"), "new").unwrap();
        let old = check_target(&run, true, &[]).unwrap();
        swap_in(&new, &run, old).unwrap();
        assert_eq!(fs::read_to_string(run.join("config.toml")).unwrap(), "new");
        assert!(!aside_path(&run).exists());

        // A new run that is not there to rename: the old run stays.
        let old = check_target(&run, true, &[]).unwrap();
        assert!(swap_in(&root.join("missing"), &run, old).is_err());
        assert_eq!(fs::read_to_string(run.join("config.toml")).unwrap(), "new");

        // A file that appears after the check is kept.
        let stray = aside_path(&run).join("late.txt");
        fs::create_dir_all(aside_path(&run)).unwrap();
        fs::write(&stray, "mine").unwrap();
        remove_run_files(&aside_path(&run), &[]);
        assert!(stray.exists());
        fs::remove_dir_all(&root).unwrap();
    }
}

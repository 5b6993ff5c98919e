//! A run directory's life: created beside its place and renamed in, locked, cleaned of what a killed process left, marked drawn.

use super::*;

/// Forgets that `dir`'s figures and report are drawn: called before they are
/// redrawn, so that a crash while drawing leaves them marked as stale.
pub fn unmark_drawn(dir: &Path) -> Result<()> {
    let path = dir.join(files::FIGURES).join(files::DRAWN);
    match fs::remove_file(&path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::Io {
            action: "remove",
            path,
            error: e,
        }),
        _ => Ok(()),
    }
}

/// Records (atomically, after everything else) that `dir`'s figures and
/// `report.html` show its first `generations` generations.
pub fn mark_drawn(dir: &Path, generations: u32) -> Result<()> {
    let path = dir.join(files::FIGURES).join(files::DRAWN);
    write_atomic(&path, format!("{generations}\n").as_bytes())
}

/// How many generations `dir`'s figures and report show, if their drawing
/// finished; `None` when it did not (or predates the record): redraw them.
pub fn drawn_generations(dir: &Path) -> Option<u32> {
    let text = read_text(&dir.join(files::FIGURES).join(files::DRAWN)).ok()?;
    text.strip_suffix('\n')?.parse().ok()
}

/// Removes temporary files a killed process left behind (`.NAME.tmp-PID`).
pub(crate) fn remove_stale_temporaries(dir: &Path) {
    for d in [
        dir.to_path_buf(),
        dir.join(files::CHECKPOINTS),
        dir.join(files::FIGURES),
    ] {
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            let name = name.to_string_lossy();
            if name.starts_with('.') && name.contains(".tmp-") {
                let _ = fs::remove_file(e.path());
            }
        }
    }
}

/// An exclusive advisory lock (flock) on a run directory, released when
/// dropped or when the process exits in any way.
pub(crate) struct RunLock(#[allow(dead_code)] fs::File);

impl RunLock {
    /// Locks `dir`, or refuses (bad input) when another process holds it.
    pub(crate) fn acquire(dir: &Path) -> Result<RunLock> {
        use std::os::fd::AsRawFd;
        let file = fs::File::open(dir).map_err(Error::io("open", dir))?;
        // SAFETY: flock on a valid descriptor owned by `file`; no memory is touched.
        let rc = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
        if rc != 0 {
            let e = std::io::Error::last_os_error();
            if e.kind() == std::io::ErrorKind::WouldBlock {
                return Err(bad_input(format!(
                    "{}: another vivae process is writing this run directory",
                    dir.display()
                )));
            }
            return Err(Error::io("lock", dir)(e));
        }
        Ok(RunLock(file))
    }
}

/// Removes hidden `.NAME.tmp-PID` folders that runs killed before their first
/// checkpoint left in `parent`: those whose process is gone and whose lock is
/// free (both, so neither a live run's fresh folder nor a reused PID is hit).
pub(crate) fn remove_abandoned_builds(parent: &Path, name: &str) {
    let prefix = format!(".{name}.tmp-");
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|p| p.parse::<i32>().ok())
        else {
            continue;
        };
        // SAFETY: kill with signal 0 sends nothing; it only asks whether `pid` exists.
        let gone = pid > 0
            && unsafe { libc::kill(pid, 0) } != 0
            && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH);
        let path = entry.path();
        if gone
            && path.is_dir()
            && !path.is_symlink()
            && let Ok(lock) = RunLock::acquire(&path)
        {
            let _ = fs::remove_dir_all(&path);
            drop(lock);
        }
    }
}

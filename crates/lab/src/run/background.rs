//! Checkpoints written while the run goes on.
//!
//! A checkpoint after every generation is the run's crash insurance, but
//! encoding it and waiting for the disk (the file is synced before it is
//! renamed into place) took a tenth of the default run's wall time, with
//! both cores idle. Here the encode, the synced write and the pruning run
//! on a thread of their own while the next generation is evaluated. At most
//! one checkpoint is under way: the next one waits for it, so checkpoints
//! reach the disk in order and memory holds one snapshot at most. A crash
//! while one is under way leaves the one before it, as a crash between
//! generations always has (the file appears only by rename).

use std::path::PathBuf;
use std::thread::JoinHandle;

use super::checkpoint::{Checkpoint, write_checkpoint_file};
use crate::error::{Error, Result};

/// Writes one checkpoint at a time on a background thread.
#[derive(Default)]
pub(crate) struct CheckpointWriter {
    /// The checkpoint under way, if any.
    pending: Option<JoinHandle<Result<()>>>,
}

impl CheckpointWriter {
    /// Waits for the checkpoint under way, if any, and returns how its write went.
    pub(crate) fn wait(&mut self) -> Result<()> {
        match self.pending.take() {
            None => Ok(()),
            Some(h) => h
                .join()
                .unwrap_or_else(|_| Err(Error::Threads("the checkpoint writer panicked".into()))),
        }
    }

    /// Starts writing `cp` into the run directory `dir`, keeping the newest
    /// `keep` checkpoints, once the one under way is written (its error, if
    /// any, is returned and `cp` is not written).
    pub(crate) fn start(&mut self, dir: PathBuf, keep: usize, cp: Checkpoint) -> Result<()> {
        self.wait()?;
        let handle = std::thread::Builder::new()
            .name("vivae-checkpoint".into())
            .spawn(move || write_checkpoint_file(&dir, keep, &cp))
            .map_err(|e| Error::Threads(format!("cannot start the checkpoint writer: {e}")))?;
        self.pending = Some(handle);
        Ok(())
    }
}

impl Drop for CheckpointWriter {
    /// A run that ends by an error still finishes the checkpoint under way
    /// (its error is the lesser one and is dropped).
    fn drop(&mut self) {
        let _ = self.wait();
    }
}

#[cfg(test)]
mod tests {
    use std::fs;
    use std::path::Path;

    use super::*;
    use crate::run::checkpoint::decode_checkpoint;
    use crate::run::checkpoint::tests::sample;
    use crate::rundir::{checkpoint_names, files};

    /// A fresh run folder named for the test.
    fn run_dir(name: &str, with_checkpoints: bool) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vivae-run-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        if with_checkpoints {
            fs::create_dir(dir.join(files::CHECKPOINTS)).unwrap();
        }
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        checkpoint_names(fs::read_dir(dir.join(files::CHECKPOINTS)).unwrap())
    }

    #[test]
    fn background_checkpoints_land_in_order_and_are_pruned() {
        let dir = run_dir("order", true);
        let mut writer = CheckpointWriter::default();
        for done in 1..=6 {
            writer.start(dir.clone(), 3, sample(done)).unwrap();
        }
        writer.wait().unwrap();
        assert_eq!(
            names(&dir),
            ["gen-000004.ckpt", "gen-000005.ckpt", "gen-000006.ckpt"]
        );
        let path = dir.join(files::CHECKPOINTS).join("gen-000006.ckpt");
        assert_eq!(decode_checkpoint(&path).unwrap(), sample(6));
        // Nothing half-written is left behind.
        let all: Vec<_> = fs::read_dir(dir.join(files::CHECKPOINTS))
            .unwrap()
            .collect();
        assert_eq!(all.len(), 3);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_background_write_is_reported_and_stops_the_next_one() {
        // No checkpoints folder: the write cannot create its file.
        let dir = run_dir("fails", false);
        let mut writer = CheckpointWriter::default();
        writer.start(dir.clone(), 3, sample(1)).unwrap();
        let e = writer.start(dir.clone(), 3, sample(2)).unwrap_err();
        assert!(e.to_string().contains("gen-000001.ckpt"), "{e}");
        // The second was refused, not started: nothing is under way.
        writer.wait().unwrap();
        assert!(!dir.join(files::CHECKPOINTS).exists());
        fs::remove_dir_all(&dir).unwrap();
    }
}

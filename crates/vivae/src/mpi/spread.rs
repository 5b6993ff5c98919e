//! Rank 0's side of a task that runs on a driver of its own (two
//! populations, not one [`super::MpiEvaluator`] generation at a time):
//! [`Spread`] hands each batch of the task's items over the job's ranks,
//! every result placed by its index, so a run's files are the
//! single-process run's at any rank count; and [`OwnDriverWork`], what each
//! rank prepares for the job's start-up handshake.

use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use serde::Serialize;
use serde::de::DeserializeOwned;
use vivae_lab::config::Config;

use super::leader::{Batch, leaders_workers, report_traffic};
use super::{MpiError, Work, WorkerRank, encode};

/// A task on its own driver as an MPI job runs it (its program-side tools' `mpi`).
#[derive(Debug, Clone, Copy)]
pub struct OwnDriverWork {
    /// What every rank prepares for a new run of a config.
    pub for_config: fn(&Config) -> vivae_lab::Result<Prepared>,
    /// What every rank prepares for the run in a directory (resumed).
    pub for_run: fn(&Path) -> vivae_lab::Result<Prepared>,
    /// Rank 0's players of the driver's batches, on this many threads of
    /// its own; `None` without workers.
    pub player: fn(usize) -> Result<Option<Players>, MpiError>,
}

/// What a rank prepares for a run on its task's own driver.
pub struct Prepared {
    /// The run's config.
    pub config: Config,
    /// What the rank does as a worker.
    pub work: Box<dyn Work>,
    /// The scenario's text (the handshake compares it).
    pub scenario_text: String,
}

/// Rank 0's players of a task's batches, as its driver's
/// [`vivae_lab::tasks::Session::players`] takes them.
pub type Players = Box<dyn std::any::Any + Sync>;

/// Spreads batches of items over the ranks of an MPI job (rank 0's side).
pub struct Spread {
    pool: rayon::ThreadPool,
    workers: Vec<WorkerRank>,
    /// What an item is, for messages: singular, and the batch's names for
    /// the traffic line (singular, plural) and its items'.
    names: [&'static str; 4],
    /// When the last batch returned.
    returned: Mutex<Option<Instant>>,
}

impl Spread {
    /// The spreader for rank 0 of a job whose workers passed the handshake,
    /// doing items on `threads` threads of its own (0 = one per core);
    /// `None` without MPI, in a job of one rank, or on a worker. `names`:
    /// an item (for messages), a batch, batches and items (for the traffic line).
    pub fn for_leader(
        threads: usize,
        names: [&'static str; 4],
    ) -> Result<Option<Spread>, MpiError> {
        let Some(workers) = leaders_workers() else {
            return Ok(None);
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| MpiError::Mpi(format!("rank 0: starting threads: {e}")))?;
        Ok(Some(Spread {
            pool,
            workers,
            names,
            returned: Mutex::new(None),
        }))
    }

    /// Does items `0..n` across the job: a worker gets `(i, item(i))` and
    /// sends back `(i, result)`; rank 0's threads do `local(i)`. The results
    /// in the items' order.
    pub fn spread<I: Serialize, O: Send + DeserializeOwned>(
        &self,
        n: usize,
        item: &dyn Fn(usize) -> I,
        local: &(dyn Fn(usize) -> Result<O, String> + Sync),
    ) -> Result<Vec<O>, String> {
        let encoded = |i: usize| encode(&(i as u64, item(i)));
        let batch = Batch {
            pool: &self.pool,
            workers: &self.workers,
            what: self.names[0],
        };
        let mut returned = self.returned.lock().unwrap_or_else(|e| e.into_inner());
        batch.spread(n, &encoded, local, &mut returned)
    }
}

impl Drop for Spread {
    fn drop(&mut self) {
        let [_, batch, batches, items] = self.names;
        report_traffic(batch, batches, items);
    }
}

//! Rank 0's player of the predator–prey task's meetings: [`MpiMeetings`]
//! spreads each batch of meetings (a generation's games, its CIAO cells)
//! over the job's ranks, every outcome placed by its index, so a run's
//! files are the single-process run's at any rank count.

use std::sync::Mutex;
use std::time::Instant;

use vivae_lab::tasks::predator_prey::meetings::{Meetings, MeetingsError, Pair};
use vivae_lab::tasks::predator_prey::{Arena, Outcome};

use super::leader::{Batch, leaders_workers, report_traffic};
use super::work::play_caught;
use super::{MpiError, WorkerRank, encode};

/// Plays batches of meetings across the ranks of an MPI job (rank 0's side).
pub struct MpiMeetings {
    pool: rayon::ThreadPool,
    workers: Vec<WorkerRank>,
    /// When the last batch returned.
    returned: Mutex<Option<Instant>>,
}

impl MpiMeetings {
    /// The player for rank 0 of a job whose workers passed the handshake,
    /// playing on `threads` threads of its own (0 = one per core); `None`
    /// without MPI, in a job of one rank, or on a worker.
    pub fn for_leader(threads: usize) -> Result<Option<MpiMeetings>, MpiError> {
        let Some(workers) = leaders_workers() else {
            return Ok(None);
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| MpiError::Mpi(format!("rank 0: starting threads: {e}")))?;
        Ok(Some(MpiMeetings {
            pool,
            workers,
            returned: Mutex::new(None),
        }))
    }
}

impl Drop for MpiMeetings {
    fn drop(&mut self) {
        report_traffic("batch of meetings", "batches of meetings", "meetings");
    }
}

impl Meetings for MpiMeetings {
    fn play(&self, arena: &Arena, pairs: &[Pair<'_>]) -> Result<Vec<Outcome>, MeetingsError> {
        let item = |i: usize| encode(&(i as u64, pairs[i].0, pairs[i].1));
        let local = |i: usize| {
            play_caught(arena, pairs[i].0, pairs[i].1)
                .map_err(|why| format!("rank 0: playing meeting {i} panicked: {why}"))
        };
        let batch = Batch {
            pool: &self.pool,
            workers: &self.workers,
            what: "meeting",
        };
        let mut returned = self.returned.lock().unwrap_or_else(|e| e.into_inner());
        (batch.spread(pairs.len(), &item, &local, &mut returned)).map_err(MeetingsError)
    }
}

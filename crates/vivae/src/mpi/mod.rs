//! Distributed evaluation over MPI (cargo feature `mpi`; see docs/distributed.md).
//!
//! Under `mpirun -n N vivae evolve …` every rank parses the same command line
//! and builds the same experiment. Rank 0 runs NEAT and writes every file
//! exactly as a single-process run does; ranks 1…N-1 are workers that
//! evaluate genomes (in a predator–prey run: play meetings, a hunter genome
//! against a prey genome) on their own rayon threads. Work is handed out one
//! item at a time from a shared queue (self-scheduling), with a few items in
//! flight per worker to hide the round trip; rank 0's own threads take from
//! the same queue. Every result is placed by its index, so the run's
//! results are bit-identical to the single-process run at any N and any
//! thread count.
//!
//! Start-up is a handshake: each worker sends rank 0 the fingerprint of its
//! binary, config and scenario, and rank 0 refuses the job with a one-line
//! message if any differ. MPI is initialised only when a launcher
//! (`mpirun`, `srun`) started the process; otherwise nothing changes.
//!
//! This file holds the process's place in the job ([`Launch`]) and the
//! message format; `handshake` is the start-up ([`start`]), `work` what a
//! worker does with an item (evaluate a genome; a task on its own driver
//! brings its own kind), `worker` a worker rank's loop, `leader` rank 0's
//! side of a batch and its [`MpiEvaluator`] for one-population runs,
//! `spread` its [`Spread`] of a task's own batches (the predator–prey task's
//! meetings: `crate::tasks`).

mod handshake;
mod leader;
mod spread;
mod work;
mod worker;

use std::sync::Mutex;
use std::time::Duration;

use mpi::Threading;
use mpi::point_to_point::Destination;
use mpi::topology::{Communicator, SimpleCommunicator};
use serde::{Deserialize, Serialize};

pub use handshake::{Setup, Started, start};
pub use leader::MpiEvaluator;
pub use spread::{OwnDriverWork, Players, Prepared, Spread};
pub use work::{Genomes, Work, caught, work_item};

/// Message tags. Rank 0 → worker: GO, WORK, STOP; worker → rank 0: HELLO, RESULT, FAILED.
const TAG_HELLO: i32 = 1;
const TAG_GO: i32 = 2;
const TAG_WORK: i32 = 3;
const TAG_RESULT: i32 = 4;
const TAG_FAILED: i32 = 5;
const TAG_STOP: i32 = 6;

/// How long an idle loop waits before looking for MPI messages again.
///
/// Polling instead of a blocking receive keeps an idle rank off the CPU
/// (Open MPI's blocking calls spin), so a rank's evaluation threads get the cores.
const POLL: Duration = Duration::from_micros(100);

/// Environment variables by which MPI launchers (Open MPI's and MPICH's
/// `mpirun`, Slurm's `srun` over PMI or PMIx) tell a process it is one rank of a job.
const LAUNCHER_VARS: [&str; 4] = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"];

/// Why a distributed run could not start or go on.
#[derive(Debug, thiserror::Error)]
pub enum MpiError {
    /// A rank was refused at start-up (different binary, config or scenario, or its own input was bad).
    #[error("{0}")]
    Refused(String),
    /// The MPI library or a message failed.
    #[error("mpi: {0}")]
    Mpi(String),
}

/// One worker as rank 0 sees it.
#[derive(Debug, Clone, Copy)]
struct WorkerRank {
    rank: i32,
    /// Genomes kept in flight at this worker: one per thread plus one queued.
    depth: usize,
}

/// Message traffic and timing of rank 0 over a run.
#[derive(Debug, Clone, Default)]
struct Traffic {
    /// Batches handed out (generations of a one-population run).
    batches: u64,
    /// Items in them (genomes, or meetings).
    items: u64,
    evaluated_by_rank0: u64,
    bytes_sent: u64,
    bytes_received: u64,
    messages_sent: u64,
    /// Wall time spent on batches.
    evaluating: Duration,
    /// Wall time between two batches: NEAT, files, checkpoints.
    outside: Duration,
    /// Gaps counted in `outside` (generations after the first).
    gaps: u64,
}

/// This process's place in the job.
#[derive(Debug)]
struct State {
    rank: i32,
    size: i32,
    quiet: bool,
    /// Workers that passed the handshake (rank 0 only; empty until then).
    workers: Vec<WorkerRank>,
    /// Rank 0 has told every worker to stop.
    stopped: bool,
    traffic: Traffic,
}

static STATE: Mutex<Option<State>> = Mutex::new(None);

fn state<R>(f: impl FnOnce(&mut Option<State>) -> R) -> R {
    f(&mut STATE.lock().unwrap_or_else(|e| e.into_inner()))
}

/// MPI for the life of the process: initialised by [`Launch::init`] when a
/// launcher started it, finalised on drop.
pub struct Launch {
    universe: Option<mpi::environment::Universe>,
}

impl Launch {
    /// Initialises MPI if (and only if) an MPI launcher started this process.
    pub fn init() -> Launch {
        if !launched_by_mpi() {
            return Launch { universe: None };
        }
        let Some((universe, threading)) = mpi::initialize_with_threading(Threading::Funneled)
        else {
            return Launch { universe: None };
        };
        if threading < Threading::Funneled {
            // Evaluation threads never call MPI; only the main thread does.
            eprintln!("warning: the MPI library offers no thread support ({threading:?})");
        }
        let world = universe.world();
        state(|s| {
            *s = Some(State {
                rank: world.rank(),
                size: world.size(),
                quiet: false,
                workers: Vec::new(),
                stopped: false,
                traffic: Traffic::default(),
            })
        });
        Launch {
            universe: Some(universe),
        }
    }

    /// This process's rank and the job's size, if MPI is in use.
    pub fn rank_and_size(&self) -> Option<(i32, i32)> {
        state(|s| s.as_ref().map(|s| (s.rank, s.size)))
    }
}

impl Drop for Launch {
    fn drop(&mut self) {
        if self.universe.is_none() {
            return;
        }
        state(|s| {
            // Workers wait for this whether rank 0 finished, failed or refused them.
            if let Some(s) = s.as_mut().filter(|s| s.rank == 0 && !s.stopped) {
                let world = SimpleCommunicator::world();
                for r in 1..s.size {
                    world.process_at_rank(r).send_with_tag(&[0u8][..], TAG_STOP);
                }
                s.stopped = true;
            }
        });
        // Dropping the universe finalises MPI.
        self.universe = None;
    }
}

/// Whether an MPI launcher started this process.
pub fn launched_by_mpi() -> bool {
    LAUNCHER_VARS
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|x| !x.is_empty()))
}

fn encode<T: Serialize + ?Sized>(value: &T) -> Result<Vec<u8>, MpiError> {
    postcard::to_allocvec(value).map_err(|e| MpiError::Mpi(format!("encoding a message: {e}")))
}

fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, postcard::Error> {
    postcard::from_bytes(bytes)
}

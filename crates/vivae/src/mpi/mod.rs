//! Distributed evaluation over MPI (cargo feature `mpi`; see docs/distributed.md).
//!
//! Under `mpirun -n N vivae evolve …` every rank parses the same command line
//! and builds the same experiment. Rank 0 runs NEAT and writes every file
//! exactly as a single-process run does; ranks 1…N-1 are workers that
//! evaluate genomes on their own rayon threads. Work is handed out one genome
//! at a time from a shared queue (self-scheduling), with a few genomes in
//! flight per worker to hide the round trip; rank 0's own threads take from
//! the same queue. Every evaluation is placed by its index, so the run's
//! results are bit-identical to the single-process run at any N and any
//! thread count.
//!
//! Start-up is a handshake: each worker sends rank 0 the fingerprint of its
//! binary, config and scenario, and rank 0 refuses the job with a one-line
//! message if any differ. MPI is initialised only when a launcher
//! (`mpirun`, `srun`) started the process; otherwise nothing changes.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use mpi::Threading;
use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};
use serde::{Deserialize, Serialize};
use vivae_neat::driver::{Evaluation, Evaluator, EvaluatorError, Task};
use vivae_neat::{EvalContext, Genome};

use vivae_lab::config::{Config, RunConfig};

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

/// What one rank tells rank 0 at start-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Hello {
    /// `vivae`'s version.
    version: String,
    /// Hash of the running executable's bytes.
    executable: u64,
    /// Hash of the evaluation-relevant config.
    config: u64,
    /// Hash of the scenario's text.
    scenario: u64,
    /// Evaluation threads of the rank.
    threads: usize,
    /// The rank's own set-up failed with this message.
    error: Option<String>,
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
    generations: u64,
    genomes: u64,
    evaluated_by_rank0: u64,
    bytes_sent: u64,
    bytes_received: u64,
    messages_sent: u64,
    /// Wall time inside `evaluate`.
    evaluating: Duration,
    /// Wall time between two `evaluate` calls: NEAT, files, checkpoints.
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

/// What a rank brings to the start-up handshake.
pub struct Setup<'a> {
    /// The resolved config.
    pub config: &'a Config,
    /// The scenario's text.
    pub scenario_text: &'a str,
    /// The task built from both (a run's `Training`, or any other task).
    pub task: &'a dyn Task,
    /// Evaluation threads for this rank (0 = one per core).
    pub threads: usize,
}

/// How [`start`] left this rank.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Started {
    /// Not under MPI, a job of one rank, or rank 0 of a job whose workers all
    /// checked in: go on as the run's only writer.
    Lead,
    /// A worker rank whose work is done (rank 0 stopped it): exit quietly.
    WorkerDone,
}

/// The start-up handshake; every rank of a job calls it once with its set-up.
///
/// Rank 0 gathers every worker's fingerprint and refuses the job if one
/// differs from its own or a worker's set-up failed. A worker sends its
/// fingerprint, then evaluates genomes until rank 0 stops it. Without MPI, or
/// in a job of one rank, this does nothing. When rank 0's own set-up failed it
/// returns [`Started::Lead`] so the caller reports that failure; its workers
/// are stopped when the [`Launch`] is dropped.
pub fn start(setup: Result<Setup<'_>, String>, quiet: bool) -> Result<Started, MpiError> {
    let Some((rank, size)) = state(|s| {
        s.as_mut().map(|s| {
            s.quiet = quiet;
            (s.rank, s.size)
        })
    }) else {
        return Ok(Started::Lead);
    };
    if size == 1 {
        return Ok(Started::Lead);
    }
    let world = SimpleCommunicator::world();
    let hello = hello(setup.as_ref());
    if rank != 0 {
        let bytes = encode(&hello)?;
        world
            .process_at_rank(0)
            .send_with_tag(&bytes[..], TAG_HELLO);
        let (_, tag) = wait_from_root(&world);
        return match (tag, setup) {
            (TAG_GO, Ok(setup)) => {
                serve(&world, setup.task, setup.threads)?;
                Ok(Started::WorkerDone)
            }
            (TAG_STOP, _) => Ok(Started::WorkerDone),
            (tag, _) => Err(MpiError::Mpi(format!(
                "rank {rank}: unexpected message (tag {tag}) from rank 0 at start-up"
            ))),
        };
    }
    if setup.is_err() {
        return Ok(Started::Lead);
    }
    let mut workers = Vec::with_capacity(size as usize - 1);
    for r in 1..size {
        let (bytes, _) = world
            .process_at_rank(r)
            .receive_vec_with_tag::<u8>(TAG_HELLO);
        let theirs: Hello = decode(&bytes).map_err(|e| {
            MpiError::Refused(format!(
                "rank {r} sent an unreadable start-up message ({e})"
            ))
        })?;
        if let Some(why) = refusal(&hello, &theirs) {
            return Err(MpiError::Refused(format!("rank {r} {why}")));
        }
        workers.push(WorkerRank {
            rank: r,
            depth: theirs.threads + 1,
        });
    }
    for w in &workers {
        world
            .process_at_rank(w.rank)
            .send_with_tag(&[0u8][..], TAG_GO);
    }
    state(|s| {
        if let Some(s) = s.as_mut() {
            s.workers = workers;
        }
    });
    Ok(Started::Lead)
}

/// This rank's fingerprint (version, executable, config, scenario, threads).
fn hello(setup: Result<&Setup<'_>, &String>) -> Hello {
    let executable = std::env::current_exe()
        .and_then(std::fs::read)
        .map_or(0, |bytes| hash(&bytes));
    match setup {
        Ok(s) => Hello {
            version: env!("CARGO_PKG_VERSION").into(),
            executable,
            config: hash(evaluation_config(s.config).as_bytes()),
            scenario: hash(s.scenario_text.as_bytes()),
            threads: resolved_threads(s.threads),
            error: None,
        },
        Err(e) => Hello {
            version: env!("CARGO_PKG_VERSION").into(),
            executable,
            config: 0,
            scenario: 0,
            threads: 0,
            error: Some(e.clone()),
        },
    }
}

/// Why rank 0 (`ours`) refuses a worker (`theirs`), if it does.
fn refusal(ours: &Hello, theirs: &Hello) -> Option<String> {
    if let Some(e) = &theirs.error {
        return Some(format!("could not start: {e}"));
    }
    if theirs.version != ours.version {
        return Some(format!(
            "runs vivae {} but rank 0 runs vivae {}: every rank must run the same binary",
            theirs.version, ours.version
        ));
    }
    if theirs.executable != ours.executable {
        return Some(
            "runs a different vivae executable than rank 0: every rank must run the same binary"
                .into(),
        );
    }
    if theirs.config != ours.config {
        return Some(
            "was started with a different config than rank 0: every rank must get the same command line and files"
                .into(),
        );
    }
    if theirs.scenario != ours.scenario {
        return Some(
            "was started with a different scenario than rank 0: every rank must get the same command line and files"
                .into(),
        );
    }
    None
}

/// The config as far as it decides evaluations: without the generation count,
/// file names (the scenario's text is compared separately, the starting
/// population only concerns rank 0) and how the run is executed.
fn evaluation_config(config: &Config) -> String {
    let mut c = config.clone();
    c.experiment.generations = 0;
    c.experiment.scenario.clear();
    c.experiment.scenarios.clear();
    c.experiment.init_population.clear();
    c.run = RunConfig::default();
    c.to_toml()
}

fn resolved_threads(threads: usize) -> usize {
    if threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        threads
    }
}

/// FNV-1a over 64-bit words: a fingerprint, not a defence against tampering.
fn hash(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ bytes.len() as u64;
    let mut chunks = bytes.chunks_exact(8);
    for c in &mut chunks {
        let w = u64::from_le_bytes(c.try_into().expect("8 bytes"));
        h = (h ^ w).wrapping_mul(0x0100_0000_01b3).rotate_left(29);
    }
    for &b in chunks.remainder() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    h
}

fn encode<T: Serialize + ?Sized>(value: &T) -> Result<Vec<u8>, MpiError> {
    postcard::to_allocvec(value).map_err(|e| MpiError::Mpi(format!("encoding a message: {e}")))
}

fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8]) -> Result<T, postcard::Error> {
    postcard::from_bytes(bytes)
}

/// Waits (without spinning) for the next message from rank 0; returns its bytes and tag.
fn wait_from_root(world: &SimpleCommunicator) -> (Vec<u8>, i32) {
    let root = world.process_at_rank(0);
    loop {
        if let Some((msg, status)) = root.immediate_matched_probe() {
            let (bytes, _) = (msg, status).matched_receive_vec::<u8>();
            return (bytes, status.tag());
        }
        std::thread::sleep(POLL);
    }
}

/// Evaluates `genome` in `ctx`, turning a panic into a message.
fn evaluate_caught(
    task: &dyn Task,
    genome: &Genome,
    ctx: &EvalContext,
) -> Result<Evaluation, String> {
    catch_unwind(AssertUnwindSafe(|| task.evaluate(genome, ctx))).map_err(|p| {
        p.downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into())
    })
}

/// A worker's life: evaluate what rank 0 sends until it says stop.
fn serve(world: &SimpleCommunicator, task: &dyn Task, threads: usize) -> Result<(), MpiError> {
    let rank = world.rank();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| MpiError::Mpi(format!("rank {rank}: starting worker threads: {e}")))?;
    let root = world.process_at_rank(0);
    let (tx, rx) = mpsc::channel::<(u64, Result<Evaluation, String>)>();
    let reply = |(index, result): (u64, Result<Evaluation, String>)| -> Result<(), MpiError> {
        match result {
            Ok(evaluation) => {
                root.send_with_tag(&encode(&(index, evaluation))?[..], TAG_RESULT);
            }
            Err(why) => {
                let text = format!("rank {rank}: evaluating genome {index} panicked: {why}");
                root.send_with_tag(text.as_bytes(), TAG_FAILED);
            }
        }
        Ok(())
    };
    pool.in_place_scope(|scope| -> Result<(), MpiError> {
        loop {
            while let Ok(done) = rx.try_recv() {
                reply(done)?;
            }
            if let Some((msg, status)) = root.immediate_matched_probe() {
                let (bytes, _) = (msg, status).matched_receive_vec::<u8>();
                match status.tag() {
                    TAG_WORK => {
                        let (ctx, genome): (EvalContext, Genome) = decode(&bytes).map_err(|e| {
                            MpiError::Mpi(format!("rank {rank}: unreadable work item: {e}"))
                        })?;
                        let tx = tx.clone();
                        scope.spawn(move |_| {
                            let result = evaluate_caught(task, &genome, &ctx);
                            let _ = tx.send((ctx.index as u64, result));
                        });
                    }
                    TAG_STOP => return Ok(()),
                    tag => {
                        return Err(MpiError::Mpi(format!(
                            "rank {rank}: unexpected message (tag {tag}) from rank 0"
                        )));
                    }
                }
                continue;
            }
            if let Ok(done) = rx.recv_timeout(POLL) {
                reply(done)?;
            }
        }
    })
}

/// Evaluates generations of any task across the ranks of an MPI job (rank 0's side).
pub struct MpiEvaluator<T> {
    task: T,
    pool: Arc<rayon::ThreadPool>,
    workers: Vec<WorkerRank>,
    /// When the last `evaluate` returned.
    returned: Option<Instant>,
}

impl<T: Task> MpiEvaluator<T> {
    /// The evaluator for rank 0 of a job whose workers passed the handshake;
    /// `None` without MPI, in a job of one rank, or on a worker.
    pub fn for_leader(task: T, pool: Arc<rayon::ThreadPool>) -> Option<MpiEvaluator<T>> {
        let workers = state(|s| {
            s.as_ref()
                .filter(|s| s.rank == 0 && !s.stopped && !s.workers.is_empty())
                .map(|s| s.workers.clone())
        })?;
        Some(MpiEvaluator {
            task,
            pool,
            workers,
            returned: None,
        })
    }
}

impl<T> Drop for MpiEvaluator<T> {
    /// Reports the run's traffic (before rank 0 goes on to draw the figures).
    fn drop(&mut self) {
        let summary = state(|s| {
            s.as_ref()
                .filter(|s| !s.quiet && s.traffic.generations > 0)
                .map(|s| s.traffic.summary(s.size))
        });
        if let Some(line) = summary {
            eprintln!("{line}");
        }
    }
}

/// One generation's traffic, added to the run's when it is done.
#[derive(Default)]
struct Tally {
    bytes_sent: u64,
    bytes_received: u64,
    messages_sent: u64,
    by_rank0: u64,
}

impl<T: Task> Evaluator for MpiEvaluator<T> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError> {
        let entered = Instant::now();
        let outside = self.returned.map(|t| entered - t);
        if genomes.len() != contexts.len() {
            return Err(EvaluatorError(format!(
                "{} genomes but {} evaluation contexts",
                genomes.len(),
                contexts.len()
            )));
        }
        let n = genomes.len();
        let next = AtomicUsize::new(0);
        let take = || {
            let i = next.fetch_add(1, Ordering::Relaxed);
            (i < n).then_some(i)
        };
        let task = &self.task;
        let mut round = Round {
            world: SimpleCommunicator::world(),
            genomes,
            contexts,
            results: vec![None; n],
            done: 0,
            tally: Tally::default(),
        };
        let outcome = self.pool.in_place_scope(|scope| {
            // Rank 0's own threads take genomes from the same queue.
            let (tx, rx) = mpsc::channel::<(usize, Result<Evaluation, String>)>();
            for _ in 0..self.pool.current_num_threads() {
                let tx = tx.clone();
                let take = &take;
                scope.spawn(move |_| {
                    while let Some(i) = take() {
                        let result = evaluate_caught(task, &genomes[i], &contexts[i]);
                        if tx.send((i, result)).is_err() {
                            break;
                        }
                    }
                });
            }
            drop(tx);
            let outcome = round.run(&self.workers, &take, &rx);
            if outcome.is_err() {
                // Rank 0's threads stop taking genomes (the scope waits for them);
                // workers are stopped when the process ends.
                next.store(n, Ordering::Relaxed);
            }
            outcome
        });
        outcome?;
        let evaluating = entered.elapsed();
        let tally = &round.tally;
        state(|s| {
            if let Some(s) = s.as_mut() {
                let t = &mut s.traffic;
                t.generations += 1;
                t.genomes += n as u64;
                t.evaluated_by_rank0 += tally.by_rank0;
                t.bytes_sent += tally.bytes_sent;
                t.bytes_received += tally.bytes_received;
                t.messages_sent += tally.messages_sent;
                t.evaluating += evaluating;
                if let Some(o) = outside {
                    t.outside += o;
                    t.gaps += 1;
                }
            }
        });
        self.returned = Some(Instant::now());
        round
            .results
            .into_iter()
            .enumerate()
            .map(|(i, r)| r.ok_or_else(|| EvaluatorError(format!("genome {i} was not evaluated"))))
            .collect()
    }
}

/// One generation being evaluated across the job (rank 0's main thread).
struct Round<'g> {
    world: SimpleCommunicator,
    genomes: &'g [Genome],
    contexts: &'g [EvalContext],
    results: Vec<Option<Evaluation>>,
    done: usize,
    tally: Tally,
}

impl Round<'_> {
    /// Hands out genomes and collects evaluations until every genome has one.
    fn run(
        &mut self,
        workers: &[WorkerRank],
        take: &dyn Fn() -> Option<usize>,
        local: &mpsc::Receiver<(usize, Result<Evaluation, String>)>,
    ) -> Result<(), EvaluatorError> {
        for w in workers {
            for _ in 0..w.depth {
                match take() {
                    Some(i) => self.send(w.rank, i)?,
                    None => break,
                }
            }
        }
        let n = self.results.len();
        while self.done < n {
            let mut progressed = false;
            while let Some((msg, status)) = self.world.any_process().immediate_matched_probe() {
                progressed = true;
                let (bytes, _) = (msg, status).matched_receive_vec::<u8>();
                self.tally.bytes_received += bytes.len() as u64;
                let from = status.source_rank();
                self.receive(from, status.tag(), &bytes)?;
                if let Some(i) = take() {
                    self.send(from, i)?;
                }
            }
            while let Ok((i, result)) = local.try_recv() {
                progressed = true;
                self.place_local(i, result)?;
            }
            if !progressed {
                // Nothing arrived: wait a little, waking early for a local result.
                match local.recv_timeout(POLL) {
                    Ok((i, result)) => self.place_local(i, result)?,
                    Err(RecvTimeoutError::Timeout) => {}
                    Err(RecvTimeoutError::Disconnected) => std::thread::sleep(POLL),
                }
            }
        }
        Ok(())
    }

    /// Sends genome `i` to worker `rank`.
    fn send(&mut self, rank: i32, i: usize) -> Result<(), EvaluatorError> {
        let bytes = encode(&(&self.contexts[i], &self.genomes[i]))
            .map_err(|e| EvaluatorError(e.to_string()))?;
        self.world
            .process_at_rank(rank)
            .send_with_tag(&bytes[..], TAG_WORK);
        self.tally.bytes_sent += bytes.len() as u64;
        self.tally.messages_sent += 1;
        Ok(())
    }

    /// Takes in a worker's message.
    fn receive(&mut self, from: i32, tag: i32, bytes: &[u8]) -> Result<(), EvaluatorError> {
        match tag {
            TAG_RESULT => {
                let (index, evaluation): (u64, Evaluation) = decode(bytes).map_err(|e| {
                    EvaluatorError(format!("rank {from} sent an unreadable result: {e}"))
                })?;
                let slot = usize::try_from(index)
                    .ok()
                    .and_then(|i| self.results.get_mut(i))
                    .filter(|r| r.is_none())
                    .ok_or_else(|| {
                        EvaluatorError(format!(
                            "rank {from} sent a result for genome {index}, which it was not given"
                        ))
                    })?;
                *slot = Some(evaluation);
                self.done += 1;
                Ok(())
            }
            TAG_FAILED => Err(EvaluatorError(String::from_utf8_lossy(bytes).into())),
            tag => Err(EvaluatorError(format!(
                "rank {from} sent an unexpected message (tag {tag})"
            ))),
        }
    }

    /// Places an evaluation made by rank 0's own threads.
    fn place_local(
        &mut self,
        i: usize,
        result: Result<Evaluation, String>,
    ) -> Result<(), EvaluatorError> {
        let evaluation = result.map_err(|why| {
            EvaluatorError(format!("rank 0: evaluating genome {i} panicked: {why}"))
        })?;
        self.results[i] = Some(evaluation);
        self.tally.by_rank0 += 1;
        self.done += 1;
        Ok(())
    }
}

impl Traffic {
    /// One line for the end of a run: per-generation bytes and rank 0's time.
    fn summary(&self, size: i32) -> String {
        let g = self.generations.max(1) as f64;
        format!(
            "mpi: {size} ranks, {} generations; per generation: {:.0} bytes sent to workers in {:.1} messages, {:.0} bytes received, evaluation {:.1} ms, rank 0 outside evaluation {:.2} ms; rank 0 evaluated {:.1}% of genomes",
            self.generations,
            self.bytes_sent as f64 / g,
            self.messages_sent as f64 / g,
            self.bytes_received as f64 / g,
            self.evaluating.as_secs_f64() * 1e3 / g,
            self.outside.as_secs_f64() * 1e3 / self.gaps.max(1) as f64,
            100.0 * self.evaluated_by_rank0 as f64 / self.genomes.max(1) as f64,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hello() -> Hello {
        Hello {
            version: "0.1.0".into(),
            executable: 1,
            config: 2,
            scenario: 3,
            threads: 2,
            error: None,
        }
    }

    #[test]
    fn same_fingerprint_is_accepted_whatever_the_threads() {
        let ours = hello();
        let theirs = Hello {
            threads: 7,
            ..hello()
        };
        assert_eq!(refusal(&ours, &theirs), None);
    }

    #[test]
    fn each_difference_is_named() {
        let ours = hello();
        let cases = [
            (
                Hello {
                    version: "0.2.0".into(),
                    ..hello()
                },
                "vivae 0.2.0",
            ),
            (
                Hello {
                    executable: 9,
                    ..hello()
                },
                "different vivae executable",
            ),
            (
                Hello {
                    config: 9,
                    ..hello()
                },
                "different config",
            ),
            (
                Hello {
                    scenario: 9,
                    ..hello()
                },
                "different scenario",
            ),
            (
                Hello {
                    error: Some("c.toml: no such file".into()),
                    ..hello()
                },
                "could not start: c.toml: no such file",
            ),
        ];
        for (theirs, expected) in cases {
            let why = refusal(&ours, &theirs).expect("refused");
            assert!(why.contains(expected), "{why}");
        }
    }

    #[test]
    fn evaluation_config_ignores_what_does_not_change_evaluations() {
        let a = Config::default();
        let mut b = a.clone();
        b.experiment.generations += 5;
        b.experiment.scenario = "elsewhere/roads.svg".into();
        b.run.threads = 3;
        b.run.checkpoint_keep = 9;
        assert_eq!(evaluation_config(&a), evaluation_config(&b));
        b.experiment.steps += 1;
        assert_ne!(evaluation_config(&a), evaluation_config(&b));
    }

    #[test]
    fn messages_round_trip_exactly() {
        let ctx = EvalContext {
            generation: 3,
            index: 17,
            seed: u64::MAX - 5,
        };
        let e = Evaluation {
            fitness: 0.1 + 0.2,
            metrics: vec![f64::MIN_POSITIVE, -0.0, 1e300],
            behaviour: vec![],
        };
        let bytes = encode(&(&ctx, 42u64, &e)).unwrap();
        let (ctx2, i, e2): (EvalContext, u64, Evaluation) = decode(&bytes).unwrap();
        assert_eq!(
            (ctx, 42, e.fitness.to_bits()),
            (ctx2, i, e2.fitness.to_bits())
        );
        assert_eq!(e, e2);
    }

    #[test]
    fn hash_sees_every_byte() {
        let a = vec![7u8; 1001];
        let mut b = a.clone();
        b[1000] = 8;
        let mut c = a.clone();
        c[3] = 8;
        assert_ne!(hash(&a), hash(&b));
        assert_ne!(hash(&a), hash(&c));
        assert_ne!(hash(&a), hash(&a[..1000]));
    }
}

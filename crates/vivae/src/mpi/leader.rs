//! Rank 0's side of a batch: [`spread`] hands a batch's items out to the
//! workers one at a time and does them on its own threads from the same
//! queue; [`MpiEvaluator`] spreads a one-population run's generations.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};
use serde::de::DeserializeOwned;
use vivae_neat::driver::{Evaluation, Evaluator, EvaluatorError, Task};
use vivae_neat::{EvalContext, Genome};

use super::work::{decode_result, evaluate_caught};
use super::{MpiError, POLL, TAG_FAILED, TAG_RESULT, TAG_WORK, WorkerRank, encode, state};

/// Evaluates generations of any task across the ranks of an MPI job (rank 0's side).
pub struct MpiEvaluator<T> {
    task: T,
    pool: Arc<rayon::ThreadPool>,
    workers: Vec<WorkerRank>,
    /// When the last `evaluate` returned.
    returned: Option<Instant>,
}

/// The workers of the job, on rank 0 of a job whose workers passed the
/// handshake; `None` without MPI, in a job of one rank, or on a worker.
pub(super) fn leaders_workers() -> Option<Vec<WorkerRank>> {
    state(|s| {
        s.as_ref()
            .filter(|s| s.rank == 0 && !s.stopped && !s.workers.is_empty())
            .map(|s| s.workers.clone())
    })
}

/// Reports the run's traffic (before rank 0 goes on to draw the figures),
/// its batches called `batch` (plural `batches`) and their items `items`.
pub(super) fn report_traffic(batch: &str, batches: &str, items: &str) {
    let summary = state(|s| {
        s.as_ref()
            .filter(|s| !s.quiet && s.traffic.batches > 0)
            .map(|s| s.traffic.summary(s.size, [batch, batches, items]))
    });
    if let Some(line) = summary {
        eprintln!("{line}");
    }
}

impl<T: Task> MpiEvaluator<T> {
    /// The evaluator for rank 0 of a job whose workers passed the handshake;
    /// `None` without MPI, in a job of one rank, or on a worker.
    pub fn for_leader(task: T, pool: Arc<rayon::ThreadPool>) -> Option<MpiEvaluator<T>> {
        Some(MpiEvaluator {
            task,
            pool,
            workers: leaders_workers()?,
            returned: None,
        })
    }
}

impl<T> Drop for MpiEvaluator<T> {
    fn drop(&mut self) {
        report_traffic("generation", "generations", "genomes");
    }
}

impl<T: Task> Evaluator for MpiEvaluator<T> {
    fn evaluate(
        &mut self,
        genomes: &[Genome],
        contexts: &[EvalContext],
    ) -> Result<Vec<Evaluation>, EvaluatorError> {
        EvaluatorError::unless_one_context_each(genomes, contexts)?;
        let item = |i: usize| encode(&(i as u64, &contexts[i], &genomes[i]));
        let local = |i: usize| {
            evaluate_caught(&self.task, &genomes[i], &contexts[i])
                .map_err(|why| format!("rank 0: evaluating genome {i} panicked: {why}"))
        };
        let batch = Batch {
            pool: &self.pool,
            workers: &self.workers,
            what: "genome",
        };
        let results = batch.spread(genomes.len(), &item, &local, &mut self.returned);
        results.map_err(EvaluatorError)
    }
}

/// Where a batch is done: rank 0's threads and the job's workers.
pub(super) struct Batch<'a> {
    pub pool: &'a rayon::ThreadPool,
    pub workers: &'a [WorkerRank],
    /// What an item is, for messages ("genome", "meeting").
    pub what: &'static str,
}

impl Batch<'_> {
    /// Does items `0..n` across the job: a worker gets item `i` as `item(i)`
    /// (its index first) and sends back `(i, result)`; rank 0's threads do
    /// `local(i)`. The results in the items' order; `returned` is when the
    /// last batch of the run returned (for the traffic report), set anew.
    pub fn spread<O: Send + DeserializeOwned>(
        &self,
        n: usize,
        item: &dyn Fn(usize) -> Result<Vec<u8>, MpiError>,
        local: &(dyn Fn(usize) -> Result<O, String> + Sync),
        returned: &mut Option<Instant>,
    ) -> Result<Vec<O>, String> {
        let entered = Instant::now();
        let outside = returned.map(|t| entered - t);
        let next = AtomicUsize::new(0);
        let take = || {
            let i = next.fetch_add(1, Ordering::Relaxed);
            (i < n).then_some(i)
        };
        let mut round = Round {
            world: SimpleCommunicator::world(),
            item,
            what: self.what,
            results: (0..n).map(|_| None).collect(),
            done: 0,
            tally: Tally::default(),
        };
        let outcome = self.pool.in_place_scope(|scope| {
            // Rank 0's own threads take items from the same queue.
            let (tx, rx) = mpsc::channel::<(usize, Result<O, String>)>();
            for _ in 0..self.pool.current_num_threads() {
                let tx = tx.clone();
                let take = &take;
                scope.spawn(move |_| {
                    while let Some(i) = take() {
                        if tx.send((i, local(i))).is_err() {
                            break;
                        }
                    }
                });
            }
            drop(tx);
            let outcome = round.run(self.workers, &take, &rx);
            if outcome.is_err() {
                // Rank 0's threads stop taking items (the scope waits for them);
                // workers are stopped when the process ends.
                next.store(n, Ordering::Relaxed);
            }
            outcome
        });
        outcome?;
        round.tally.add_to_run(n, entered.elapsed(), outside);
        *returned = Some(Instant::now());
        let what = self.what;
        (round.results.into_iter().enumerate())
            .map(|(i, r)| r.ok_or_else(|| format!("{what} {i} was not done")))
            .collect()
    }
}

/// One batch's traffic, added to the run's when it is done.
#[derive(Default)]
struct Tally {
    bytes_sent: u64,
    bytes_received: u64,
    messages_sent: u64,
    by_rank0: u64,
}

impl Tally {
    /// Adds this batch of `n` items, which took `took`, `outside` after the last one, to the run's traffic.
    fn add_to_run(&self, n: usize, took: Duration, outside: Option<Duration>) {
        state(|s| {
            if let Some(s) = s.as_mut() {
                let t = &mut s.traffic;
                t.batches += 1;
                t.items += n as u64;
                t.evaluated_by_rank0 += self.by_rank0;
                t.bytes_sent += self.bytes_sent;
                t.bytes_received += self.bytes_received;
                t.messages_sent += self.messages_sent;
                t.evaluating += took;
                if let Some(o) = outside {
                    t.outside += o;
                    t.gaps += 1;
                }
            }
        });
    }
}

/// One batch being done across the job (rank 0's main thread).
struct Round<'f, O> {
    world: SimpleCommunicator,
    item: &'f dyn Fn(usize) -> Result<Vec<u8>, MpiError>,
    what: &'static str,
    results: Vec<Option<O>>,
    done: usize,
    tally: Tally,
}

impl<O: DeserializeOwned> Round<'_, O> {
    /// Hands out items and collects results until every item has one.
    fn run(
        &mut self,
        workers: &[WorkerRank],
        take: &dyn Fn() -> Option<usize>,
        local: &mpsc::Receiver<(usize, Result<O, String>)>,
    ) -> Result<(), String> {
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

    /// Sends item `i` to worker `rank`.
    fn send(&mut self, rank: i32, i: usize) -> Result<(), String> {
        let bytes = (self.item)(i).map_err(|e| e.to_string())?;
        self.world
            .process_at_rank(rank)
            .send_with_tag(&bytes[..], TAG_WORK);
        self.tally.bytes_sent += bytes.len() as u64;
        self.tally.messages_sent += 1;
        Ok(())
    }

    /// Takes in a worker's message.
    fn receive(&mut self, from: i32, tag: i32, bytes: &[u8]) -> Result<(), String> {
        match tag {
            TAG_RESULT => {
                let (index, result): (u64, O) = decode_result(bytes)
                    .map_err(|e| format!("rank {from} sent an unreadable result: {e}"))?;
                let what = self.what;
                let slot = usize::try_from(index)
                    .ok()
                    .and_then(|i| self.results.get_mut(i))
                    .filter(|r| r.is_none())
                    .ok_or_else(|| {
                        format!(
                            "rank {from} sent a result for {what} {index}, which it was not given"
                        )
                    })?;
                *slot = Some(result);
                self.done += 1;
                Ok(())
            }
            TAG_FAILED => Err(String::from_utf8_lossy(bytes).into()),
            tag => Err(format!(
                "rank {from} sent an unexpected message (tag {tag})"
            )),
        }
    }

    /// Places a result of rank 0's own threads.
    fn place_local(&mut self, i: usize, result: Result<O, String>) -> Result<(), String> {
        self.results[i] = Some(result?);
        self.tally.by_rank0 += 1;
        self.done += 1;
        Ok(())
    }
}

impl super::Traffic {
    /// One line for the end of a run: per-batch bytes and rank 0's time,
    /// its batches called `batch` ("generation", plural `batches`) and
    /// their items `items` ("genomes").
    fn summary(&self, size: i32, [batch, batches, items]: [&str; 3]) -> String {
        let g = self.batches.max(1) as f64;
        format!(
            "mpi: {size} ranks, {} {batches}; per {batch}: {:.0} bytes sent to workers in {:.1} messages, {:.0} bytes received, evaluation {:.1} ms, rank 0 outside evaluation {:.2} ms; rank 0 evaluated {:.1}% of {items}",
            self.batches,
            self.bytes_sent as f64 / g,
            self.messages_sent as f64 / g,
            self.bytes_received as f64 / g,
            self.evaluating.as_secs_f64() * 1e3 / g,
            self.outside.as_secs_f64() * 1e3 / self.gaps.max(1) as f64,
            100.0 * self.evaluated_by_rank0 as f64 / self.items.max(1) as f64,
        )
    }
}

//! Rank 0's side: [`MpiEvaluator`] hands a generation's genomes out to the
//! workers one at a time and evaluates on its own threads from the same queue.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Instant;

use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};
use vivae_neat::driver::{Evaluation, Evaluator, EvaluatorError, Task};
use vivae_neat::{EvalContext, Genome};

use super::{
    POLL, TAG_FAILED, TAG_RESULT, TAG_WORK, Traffic, WorkerRank, decode, encode, evaluate_caught,
    state,
};

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

//! A worker rank's side: evaluate the genomes rank 0 sends until it says stop.

use std::sync::mpsc;

use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};
use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome};

use super::{
    MpiError, POLL, TAG_FAILED, TAG_RESULT, TAG_STOP, TAG_WORK, decode, encode, evaluate_caught,
};

/// Waits (without spinning) for the next message from rank 0; returns its bytes and tag.
pub(super) fn wait_from_root(world: &SimpleCommunicator) -> (Vec<u8>, i32) {
    let root = world.process_at_rank(0);
    loop {
        if let Some((msg, status)) = root.immediate_matched_probe() {
            let (bytes, _) = (msg, status).matched_receive_vec::<u8>();
            return (bytes, status.tag());
        }
        std::thread::sleep(POLL);
    }
}

/// A worker's life: evaluate what rank 0 sends until it says stop.
pub(super) fn serve(
    world: &SimpleCommunicator,
    task: &dyn Task,
    threads: usize,
) -> Result<(), MpiError> {
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

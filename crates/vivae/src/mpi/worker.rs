//! A worker rank's side: do the work items rank 0 sends (evaluate genomes,
//! or play meetings) until it says stop.

use std::sync::mpsc;

use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};

use super::{MpiError, POLL, TAG_FAILED, TAG_RESULT, TAG_STOP, TAG_WORK, Work};

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

/// A worker's life: do the work items rank 0 sends until it says stop.
pub(super) fn serve(
    world: &SimpleCommunicator,
    work: &dyn Work,
    threads: usize,
) -> Result<(), MpiError> {
    let rank = world.rank();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| MpiError::Mpi(format!("rank {rank}: starting worker threads: {e}")))?;
    let root = world.process_at_rank(0);
    let (tx, rx) = mpsc::channel::<Result<Vec<u8>, String>>();
    let reply = |done: Result<Vec<u8>, String>| match done {
        Ok(result) => root.send_with_tag(&result[..], TAG_RESULT),
        Err(why) => root.send_with_tag(format!("rank {rank}: {why}").as_bytes(), TAG_FAILED),
    };
    pool.in_place_scope(|scope| -> Result<(), MpiError> {
        loop {
            while let Ok(done) = rx.try_recv() {
                reply(done);
            }
            if let Some((msg, status)) = root.immediate_matched_probe() {
                let (bytes, _) = (msg, status).matched_receive_vec::<u8>();
                match status.tag() {
                    TAG_WORK => {
                        let tx = tx.clone();
                        scope.spawn(move |_| {
                            let _ = tx.send(work.work(&bytes));
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
                reply(done);
            }
        }
    })
}

//! What the workers of a job do with a work item: [`Work`], and its two
//! kinds: evaluating one genome of a one-population run ([`Genomes`]) and
//! playing one predator–prey meeting ([`MeetingsOf`]). An item carries its
//! index; a result goes back with it, so rank 0 places every result by its
//! index whoever produced it.

use std::panic::{AssertUnwindSafe, catch_unwind};

use serde::Serialize;
use serde::de::DeserializeOwned;
use vivae_lab::tasks::predator_prey::{Arena, Outcome};
use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::{EvalContext, Genome};

use super::{decode, encode};

/// What a worker rank does with the work items rank 0 sends it.
pub trait Work: Sync {
    /// Does the encoded item `item` (its index first): the encoded result
    /// (the index first), or why it could not (a line naming the item).
    fn work(&self, item: &[u8]) -> Result<Vec<u8>, String>;
}

/// Evaluating genomes of a task: an item is `(index, context, genome)`, a result `(index, evaluation)`.
pub struct Genomes<'a>(pub &'a dyn Task);

/// Playing meetings in an arena: an item is `(index, hunter, prey)`, a result `(index, outcome)`.
pub struct MeetingsOf<'a>(pub &'a Arena);

impl Work for Genomes<'_> {
    fn work(&self, item: &[u8]) -> Result<Vec<u8>, String> {
        let (index, ctx, genome): (u64, EvalContext, Genome) =
            decode(item).map_err(|e| format!("unreadable work item: {e}"))?;
        let evaluation = evaluate_caught(self.0, &genome, &ctx)
            .map_err(|why| format!("evaluating genome {index} panicked: {why}"))?;
        reply(index, &evaluation)
    }
}

impl Work for MeetingsOf<'_> {
    fn work(&self, item: &[u8]) -> Result<Vec<u8>, String> {
        let (index, hunter, prey): (u64, Genome, Genome) =
            decode(item).map_err(|e| format!("unreadable work item: {e}"))?;
        let outcome = play_caught(self.0, &hunter, &prey)
            .map_err(|why| format!("playing meeting {index} panicked: {why}"))?;
        reply(index, &outcome)
    }
}

fn reply<T: Serialize>(index: u64, result: &T) -> Result<Vec<u8>, String> {
    encode(&(index, result)).map_err(|e| e.to_string())
}

/// Decodes a result `(index, value)` a worker sent.
pub(super) fn decode_result<O: DeserializeOwned>(bytes: &[u8]) -> Result<(u64, O), String> {
    decode(bytes).map_err(|e| e.to_string())
}

/// Evaluates `genome` in `ctx`, turning a panic into a message.
pub(super) fn evaluate_caught(
    task: &dyn Task,
    genome: &Genome,
    ctx: &EvalContext,
) -> Result<Evaluation, String> {
    caught(|| task.evaluate(genome, ctx))
}

/// Plays `hunter` against `prey` in `arena`, turning a panic into a message.
pub(super) fn play_caught(
    arena: &Arena,
    hunter: &Genome,
    prey: &Genome,
) -> Result<Outcome, String> {
    caught(|| arena.play_genomes(hunter, prey))
}

/// Runs `f`, turning a panic into its message.
fn caught<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| {
        p.downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into())
    })
}

//! What the workers of a job do with a work item: [`Work`], and its kind
//! for a one-population run: evaluating one genome ([`Genomes`]); a task on
//! a driver of its own brings its own kind (e.g. playing one meeting of two
//! genomes) built on [`work_item`]. An item carries its index; a result goes
//! back with it, so rank 0 places every result by its index whoever
//! produced it.

use std::panic::{AssertUnwindSafe, catch_unwind};

use serde::Serialize;
use serde::de::DeserializeOwned;
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

impl Work for Genomes<'_> {
    fn work(&self, item: &[u8]) -> Result<Vec<u8>, String> {
        work_item(
            item,
            "evaluating genome",
            |(ctx, genome): (EvalContext, Genome)| self.0.evaluate(&genome, &ctx),
        )
    }
}

/// Does the encoded item `(index, input)` with `f` and encodes `(index,
/// output)`; an unreadable item, or a panic in `f` (a line naming the item:
/// `doing` and its index), is the error.
pub fn work_item<I: DeserializeOwned, O: Serialize>(
    item: &[u8],
    doing: &str,
    f: impl FnOnce(I) -> O,
) -> Result<Vec<u8>, String> {
    let (index, input): (u64, I) =
        decode(item).map_err(|e| format!("unreadable work item: {e}"))?;
    let output = caught(|| f(input)).map_err(|why| format!("{doing} {index} panicked: {why}"))?;
    encode(&(index, output)).map_err(|e| e.to_string())
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

/// Runs `f`, turning a panic into its message.
pub fn caught<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| {
        p.downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into())
    })
}

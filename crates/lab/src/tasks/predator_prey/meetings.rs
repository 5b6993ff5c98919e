//! Who plays a generation's meetings: [`Meetings`] takes a batch of
//! (hunter, prey) pairs and gives back their outcomes in the batch's order.
//! [`OnThreads`] plays them on this process's threads; the program plays
//! them across the ranks of an MPI job (it owns MPI: this library knows
//! none). A meeting depends on its two genomes and the arena alone, so the
//! outcomes, and the run's bits, are the same whoever plays them.

use std::any::Any;

use rayon::prelude::*;
use vivae_neat::Genome;

use crate::tasks::Session;
use crate::tasks::predator_prey::{Arena, Outcome};

/// One meeting to play: a hunter genome against a prey genome.
pub type Pair<'a> = (&'a Genome, &'a Genome);

/// Why a batch of meetings could not be played (e.g. a rank of an MPI job failed).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{0}")]
pub struct MeetingsError(pub String);

/// Plays batches of meetings in an arena.
pub trait Meetings: Sync {
    /// The outcome of each of `pairs` in `arena`, in the order of `pairs`.
    fn play(&self, arena: &Arena, pairs: &[Pair<'_>]) -> Result<Vec<Outcome>, MeetingsError>;
}

/// Plays meetings on the current rayon pool's threads.
#[derive(Debug, Clone, Copy, Default)]
pub struct OnThreads;

impl Meetings for OnThreads {
    fn play(&self, arena: &Arena, pairs: &[Pair<'_>]) -> Result<Vec<Outcome>, MeetingsError> {
        Ok(pairs
            .par_iter()
            .map(|&(h, p)| arena.play_genomes(h, p))
            .collect())
    }
}

/// `meetings` as a [`Session::players`] (the program's player across an MPI job's ranks).
pub fn player(meetings: Box<dyn Meetings>) -> Box<dyn Any + Sync> {
    Box::new(meetings)
}

/// Who plays `session`'s meetings when not this process's threads (`None`):
/// its players, when they are a [`player`].
pub fn played_by<'a>(session: &Session<'a>) -> Option<&'a dyn Meetings> {
    let players: &'a dyn Any = session.players?;
    players.downcast_ref::<Box<dyn Meetings>>().map(|m| &**m)
}

//! The predator–prey task under MPI: every rank builds the run's arena and
//! plays meetings in it as a worker ([`MeetingsOf`]); rank 0's player
//! ([`MpiMeetings`]) spreads each batch of meetings (a generation's games,
//! its CIAO cells) over the job's ranks, every outcome placed by its index,
//! so a run's files are the single-process run's at any rank count.

use std::path::Path;

use vivae_lab::config::Config;
use vivae_lab::tasks::predator_prey::meetings::{self, Meetings, MeetingsError, Pair};
use vivae_lab::tasks::predator_prey::run::{arena_for, arena_of_run};
use vivae_lab::tasks::predator_prey::{Arena, Outcome};
use vivae_neat::Genome;

use crate::mpi::{MpiError, OwnDriverWork, Players, Prepared, Spread, Work, caught, work_item};

/// How an MPI job runs the task.
pub const MPI: OwnDriverWork = OwnDriverWork {
    for_config,
    for_run,
    player,
};

/// Playing meetings in an arena: an item is `(index, hunter, prey)`, a result `(index, outcome)`.
pub struct MeetingsOf(pub Arena);

impl Work for MeetingsOf {
    fn work(&self, item: &[u8]) -> Result<Vec<u8>, String> {
        work_item(
            item,
            "playing meeting",
            |(hunter, prey): (Genome, Genome)| self.0.play_genomes(&hunter, &prey),
        )
    }
}

/// A new run of `config`: every rank builds its arena.
fn for_config(config: &Config) -> vivae_lab::Result<Prepared> {
    let (arena, scenario_text) = arena_for(config)?;
    Ok(Prepared {
        config: config.clone(),
        work: Box::new(MeetingsOf(arena)),
        scenario_text,
    })
}

/// The run in `dir`: every rank reads its last checkpoint's config and builds its arena.
fn for_run(dir: &Path) -> vivae_lab::Result<Prepared> {
    let (config, arena, scenario_text) = arena_of_run(dir)?;
    Ok(Prepared {
        config,
        work: Box::new(MeetingsOf(arena)),
        scenario_text,
    })
}

/// Rank 0's player of the run's meetings, as the driver's session takes it.
fn player(threads: usize) -> Result<Option<Players>, MpiError> {
    let names = [
        "meeting",
        "batch of meetings",
        "batches of meetings",
        "meetings",
    ];
    let spread = Spread::for_leader(threads, names)?;
    Ok(spread.map(|s| meetings::player(Box::new(MpiMeetings(s)))))
}

/// Plays batches of meetings across the ranks of an MPI job (rank 0's side).
pub struct MpiMeetings(Spread);

impl Meetings for MpiMeetings {
    fn play(&self, arena: &Arena, pairs: &[Pair<'_>]) -> Result<Vec<Outcome>, MeetingsError> {
        let item = |i: usize| pairs[i];
        let local = |i: usize| {
            caught(|| arena.play_genomes(pairs[i].0, pairs[i].1))
                .map_err(|why| format!("rank 0: playing meeting {i} panicked: {why}"))
        };
        (self.0.spread(pairs.len(), &item, &local)).map_err(MeetingsError)
    }
}

//! The program's side of the predator–prey task (two co-evolved
//! populations): its figures (`figures`: the CIAO heat map, both sides'
//! curves), its `report.html` (`report`), its viewer page (`view`: a hunter
//! and a prey of any generations meet), its MPI player of meetings (`mpi`)
//! and `vivae tournament`.

pub mod figures;
#[cfg(feature = "mpi")]
pub mod mpi;
pub mod report;
#[cfg(feature = "viewer")]
pub(crate) mod view;

use std::path::Path;

use vivae_lab::tasks::predator_prey::{TASK, tournament};

use super::{TaskTools, TournamentTables};

/// The task's program-side parts.
pub static TOOLS: TaskTools = TaskTools {
    entry: &TASK,
    report: report::write,
    finish: None,
    report_note: " (and figures/ciao.png, figures/coevolution.png)",
    records: "hunters.csv, prey.csv, ciao.csv and champions.json",
    tournament: Some(super::Tournament {
        play: tournament_tables,
        csv: tournament::CSV_KIND,
    }),
    replay: None,
    #[cfg(feature = "viewer")]
    view: Some(view::PAGE),
    #[cfg(feature = "viewer")]
    world: None,
    #[cfg(feature = "mpi")]
    mpi: Some(mpi::MPI),
};

/// One run's champions against another's: the table and its CSV.
fn tournament_tables(a: &Path, b: &Path, threads: usize) -> vivae_lab::Result<TournamentTables> {
    let rows = tournament::tournament(a, b, threads)?;
    Ok(TournamentTables {
        table: tournament::table(&rows),
        csv: tournament::csv(&rows),
    })
}

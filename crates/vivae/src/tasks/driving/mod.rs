//! The program's side of the driving task (robots on roads): the figures and
//! `report.html` of its runs, its replay (`replay`: the trajectories, and
//! the swerve of `--swerve`), and the viewer's live simulation of its robots.

pub mod replay;
pub mod report;
pub mod report_html;
pub mod swerve;
#[cfg(feature = "viewer")]
pub mod view;

use vivae_lab::tasks::driving::TASK;
use vivae_lab::tasks::driving::episode::Episode;

use super::TaskTools;
use crate::figures::network::RobotSubstrate;

/// The task's program-side parts.
pub static TOOLS: TaskTools = TaskTools {
    entry: &TASK,
    report: report_html::write,
    finish: Some(report::finish),
    report_note: "",
    records: "generations.csv, population.csv, best_genomes.txt and champion.json",
    tournament: None,
    replay: Some(replay::replay),
    #[cfg(feature = "viewer")]
    view: None,
    #[cfg(feature = "viewer")]
    world: Some(view::WORLD),
    #[cfg(feature = "mpi")]
    mpi: None,
};

/// The substrate of `experiment`'s robots, as the network figure draws it.
pub fn substrate(experiment: &Episode) -> RobotSubstrate<'_> {
    RobotSubstrate {
        spec: experiment.substrate_spec(),
        sensors: experiment.sensors(),
        es: experiment.es_setup(),
    }
}

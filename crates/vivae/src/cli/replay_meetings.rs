//! `vivae replay --meetings`: every learner's meetings with the blocks placed
//! for the episode (`vivae_lab::tasks::driving::meetings`), as a CSV beside
//! the trajectories, and their counts on stdout.

use std::path::Path;

use vivae_lab::config::Config;
use vivae_lab::io::bad_input;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::driving::meetings::{self, MeetingCounts};
use vivae_sim::DistanceSensors;

/// The rays whose sight a meeting records: the robots' own (re-sampled by
/// `--distance-rays`), or for robots without rays the default sheet's (5 rays
/// over 180°, 100 px): what rays would have shown the same paths.
pub fn sight(config: &Config) -> vivae_sim::DistanceGrid {
    let layout: DistanceSensors = config.distance_sensors.layout().unwrap_or_default();
    layout.grid()
}

/// Refuses `--meetings` on a course without a route (before anything is
/// written, so that the error stays one line).
pub fn check(experiment: &Episode) -> anyhow::Result<()> {
    let sc = experiment.world().scenario();
    if sc.routes.is_empty() {
        return Err(bad_input(format!(
            "--meetings: {}: meetings are measured along a route (a path labelled Route), and the scenario has none",
            sc.source
        ))
        .into());
    }
    Ok(())
}

/// Writes `meetings-pN[-blind-rays].csv` into `out` and prints the counts.
pub fn write(
    experiment: &Episode,
    config: &Config,
    genome: &vivae_neat::Genome,
    placement: u64,
    out: &Path,
) -> anyhow::Result<()> {
    let controller =
        (experiment.robot_controller(genome)).map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let all = meetings::meetings(experiment, &controller, Some(&sight(config)))
        .map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let blind = if experiment.blind_rays() {
        "-blind-rays"
    } else {
        ""
    };
    let path = out.join(format!("meetings-p{placement}{blind}.csv"));
    vivae_lab::io::write_atomic(&path, meetings::csv(&all).as_bytes())?;
    println!("{}", MeetingCounts::of(&all).fields());
    eprintln!("meetings: {}", path.display());
    Ok(())
}

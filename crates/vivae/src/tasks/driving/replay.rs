//! `vivae replay` of a driving genome: its trajectories on the run's
//! scenario (or another), the line of its fitness and behaviour, and with
//! `--swerve` the meeting that blinding the rays changes most.

use std::path::{Path, PathBuf};

use vivae_lab::config::Config;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::bad_input;
use vivae_lab::rundir::{Champion, files};
use vivae_lab::search::files::Member;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;

use super::report::trajectory_figure;
use crate::tasks::ReplayRequest;

/// Replays `r`'s genome on its config's scenario: draws its trajectories,
/// prints its line (and the swerve's, with `--swerve`).
pub fn replay(r: &ReplayRequest<'_>) -> anyhow::Result<()> {
    let config = r.config;
    // The config's single scenario file, if it names one (none: the embedded scenario).
    let path = (!config.experiment.scenario.is_empty())
        .then(|| std::path::PathBuf::from(&config.experiment.scenario));
    if let Some(p) = path.as_deref().filter(|p| !r.scenario_given && !p.exists()) {
        return Err(bad_input(format!(
            "{}: the champion's scenario {} is not there; name one with --scenario FILE",
            r.source.display(),
            p.display()
        ))
        .into());
    }
    let scenario = load_scenario(path.as_deref())?;
    let experiment = blinded(r, Episode::new(config, &scenario.scenario))?;
    if let Some(seed) = r.placement_seed.filter(|_| !experiment.varies()) {
        return Err(bad_input(format!(
            "--placement-seed {seed}: {} places no obstacles or traffic at random, so no seed changes the replay",
            scenario.scenario.source
        ))
        .into());
    }
    if experiment.varies() {
        eprintln!(
            "{}: obstacles and traffic at placement {}",
            scenario.scenario.source,
            r.placement_seed.unwrap_or(0)
        );
    }
    let experiment = experiment.with_placement_seed(r.placement_seed.unwrap_or(0));
    // Checked before anything is written: a genome that does not fit is bad input.
    experiment
        .robot_controller(&r.champion.genome)
        .map_err(|e| vivae_lab::Error::Genome {
            path: r.source.to_path_buf(),
            reason: format!("the genome's {e}"),
        })?;
    // Said once the genome is known to fit, so that an error stays one line.
    if r.champion.config.is_none() && !r.source.is_dir() {
        eprintln!(
            "warning: {} records no config (written by an older vivae): replaying with the default config and flags; replay its run directory instead if you have it",
            r.source.display()
        );
    }
    vivae_lab::io::create_dirs(&r.out)?;
    let name = replay_scenario_name(path.as_deref(), &scenario.text);
    let replay = draw(&experiment, config, r.champion, &name, &r.out, r.member)?;
    println!(
        "fitness={} on_road={:.4} speed={:.4} {}",
        replay.fitness,
        replay.on_road,
        replay.speed,
        replay.behaviour.fields()
    );
    eprintln!("figure: {}", replay.figure.display());
    if r.swerve {
        swerve_figure(r, &experiment)?;
    }
    if r.meetings {
        meetings_csv(r, &experiment)?;
    }
    Ok(())
}

/// The replay's episode, its rays blinded with `--blind-rays` (and, with
/// `--meetings`, checked to have a route): refused before anything is said
/// about the replay, so that an error stays one line.
fn blinded(
    r: &ReplayRequest<'_>,
    experiment: Result<Episode, vivae_lab::error::EpisodeError>,
) -> anyhow::Result<Episode> {
    let experiment = experiment.map_err(vivae_lab::Error::from)?;
    let sc = experiment.world().scenario();
    if r.meetings && sc.routes.is_empty() {
        return Err(bad_input(format!(
            "--meetings: {}: meetings are measured along a route (a path labelled Route), and the scenario has none",
            sc.source
        ))
        .into());
    }
    match r.blind_rays {
        true => {
            Ok((experiment.with_blind_rays())
                .map_err(|e| bad_input(format!("--blind-rays: {e}")))?)
        }
        false => Ok(experiment),
    }
}

/// `--meetings`: writes `meetings-pN[-blind-rays].csv` into the replay's
/// folder and prints the counts. The rays whose sight is recorded are the
/// robots' own (re-sampled by `--distance-rays`), or for robots without rays
/// the default sheet's (5 rays over 180°, 100 px): what rays would have
/// shown the same paths.
fn meetings_csv(r: &ReplayRequest<'_>, experiment: &Episode) -> anyhow::Result<()> {
    use vivae_lab::tasks::driving::meetings::{self, MeetingCounts};
    let controller = (experiment.robot_controller(&r.champion.genome))
        .map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let layout: vivae_sim::DistanceSensors = r.config.distance_sensors.layout().unwrap_or_default();
    let all = meetings::meetings(experiment, &controller, Some(&layout.grid()))
        .map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let blind = if experiment.blind_rays() {
        "-blind-rays"
    } else {
        ""
    };
    let placement = r.placement_seed.unwrap_or(0);
    let path = r.out.join(format!("meetings-p{placement}{blind}.csv"));
    vivae_lab::io::write_atomic(&path, meetings::csv(&all).as_bytes())?;
    println!("{}", MeetingCounts::of(&all).fields());
    eprintln!("meetings: {}", path.display());
    Ok(())
}

/// `--swerve`: the zoomed figure of the meeting blinding changes most, and its line.
fn swerve_figure(r: &ReplayRequest<'_>, experiment: &Episode) -> anyhow::Result<()> {
    let placement = r.placement_seed.unwrap_or(0);
    let blind = if r.blind_rays { "-blind-rays" } else { "" };
    // Named for its run (a run's scenario is its copy, scenario.svg).
    let run = match r.source.is_dir() {
        true => r.source,
        false => r.source.parent().unwrap_or(r.source),
    };
    let run = run
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let title = format!("{run}, placement {placement}");
    match super::swerve::swerve(experiment, &r.champion.genome, &title)? {
        None => eprintln!("swerve: the scenario has no placed block nor scripted robot to meet"),
        Some((figure, m)) => {
            let path = r.out.join(format!("swerve-p{placement}{blind}"));
            vivae_lab::io::write_atomic(&path.with_extension("svg"), figure.svg.as_bytes())?;
            vivae_lab::io::write_atomic(&path.with_extension("png"), &figure.png)?;
            let blinded = m.blinded.map_or(String::new(), |(gap, step)| {
                format!(" blinded_clearance={:.2} blinded_step={step}", gap.max(0.0))
            });
            println!(
                "swerve robot={} met=\"{}\" clearance={:.2} step={}{blinded}",
                m.robot + 1,
                m.what,
                m.seeing.0.max(0.0),
                m.seeing.1
            );
            eprintln!("swerve figure: {}", path.with_extension("png").display());
        }
    }
    Ok(())
}

/// A replay's result.
#[derive(Debug, Clone)]
pub struct Replay {
    /// Average speed.
    pub fitness: f64,
    /// Fraction of robot-steps on road.
    pub on_road: f64,
    /// Average speed (Σ odometer / robot-steps), whatever the fitness.
    pub speed: f64,
    /// Collisions, turns, loops and side of the road.
    pub behaviour: vivae_lab::tasks::driving::behaviour::Behaviour,
    /// The trajectory figure (PNG).
    pub figure: PathBuf,
}

/// Runs a champion on `experiment` (on scenario `scenario`) and draws its
/// trajectories into `out` as `replay-<scenario>-s<RxA>-n<RxA>`, followed by
/// the substrate's wiring where it is not the paper's ([`wiring_suffix`]), so
/// that replays with other wiring flags do not overwrite each other.
fn draw(
    experiment: &Episode,
    config: &Config,
    champion: &Champion,
    scenario: &str,
    out: &Path,
    member: Option<Member>,
) -> Result<Replay> {
    let s = &config.surface_sensors;
    let n = config.substrate.neurons;
    let safe = vivae_lab::io::safe_file_stem(scenario);
    // An archive or front member gets its own file and says what it is.
    let (who, tag) = match member {
        None => ("Champion".to_string(), String::new()),
        Some(Member::Elite(cell)) => (format!("Elite of cell {cell}"), format!("-elite{cell}")),
        Some(Member::Front(i)) => (format!("Front member {i}"), format!("-front{i}")),
    };
    // A blinded replay is drawn beside the seeing one, not over it.
    let (blind_tag, blind_title) = match experiment.blind_rays() {
        true => ("-blind-rays", ", rays blinded"),
        false => ("", ""),
    };
    let name = format!(
        "replay-{safe}-s{}x{}-n{}x{}{}{tag}{blind_tag}",
        s.rings,
        s.angles,
        n.rings,
        n.angles,
        wiring_suffix(config)
    );
    // Short enough that the fitness appended to it fits an 800 px figure.
    // A front member's generation is not recorded (its line says 0).
    let generation = match member {
        Some(Member::Front(_)) => String::new(),
        _ => format!(" (gen {})", champion.generation),
    };
    let title = format!(
        "{who}{generation} on {scenario}, s{}x{} n{}x{}{blind_title}",
        s.rings, s.angles, n.rings, n.angles
    );
    let episode = trajectory_figure(experiment, &champion.genome, &title, out, &name)?;
    Ok(Replay {
        fitness: episode.fitness,
        on_road: episode.on_road.unwrap_or_default(),
        speed: episode.speed.unwrap_or_default(),
        behaviour: episode.behaviour.ok_or(Error::Invalid(
            "the replay recorded no behaviour measures".into(),
        ))?,
        figure: out.join(format!("{name}.png")),
    })
}

/// The substrate settings of `config` that differ from the default (the
/// paper's), as a file-name suffix: `-recurrence-self-normalize-by-area`;
/// empty for the paper's wiring.
pub fn wiring_suffix(config: &Config) -> String {
    let ours = &config.substrate;
    let paper = Config::default().substrate;
    let word = |v: serde_json::Value| v.as_str().map_or_else(|| v.to_string(), str::to_string);
    let mut suffix = String::new();
    if ours.normalize != paper.normalize {
        suffix += &format!("-normalize-{}", ours.normalize);
    }
    if ours.normalize_by != paper.normalize_by {
        suffix += &format!(
            "-normalize-by-{}",
            word(serde_json::json!(ours.normalize_by))
        );
    }
    if ours.normalize_self_loops != paper.normalize_self_loops {
        suffix += &format!("-normalize-self-loops-{}", ours.normalize_self_loops);
    }
    if ours.recurrence != paper.recurrence {
        suffix += &format!("-recurrence-{}", word(serde_json::json!(ours.recurrence)));
    }
    suffix
}

/// The name a replay gives the scenario at `path` (whose SVG is `text`): a
/// run's copy (`scenario.svg`) is named for the file it was copied from, as
/// its SVG records it (Inkscape's `sodipodi:docname`), else for its file stem.
pub fn replay_scenario_name(path: Option<&Path>, text: &str) -> String {
    let copy = path.and_then(Path::file_name) == Some(std::ffi::OsStr::new(files::SCENARIO));
    let recorded = || {
        let start = text.find("sodipodi:docname=\"")? + "sodipodi:docname=\"".len();
        let end = text[start..].find('"')?;
        let stem = Path::new(&text[start..start + end]).file_stem()?;
        Some(stem.to_string_lossy().into_owned()).filter(|s| !s.is_empty())
    };
    match copy.then(recorded).flatten() {
        Some(name) => name,
        None => vivae_lab::io::scenario_name(path),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replay_names_a_runs_copy_for_its_original_and_marks_its_wiring() {
        let svg = r#"<svg sodipodi:docname="oval.svg"></svg>"#;
        let copy = Path::new("run/scenario.svg");
        assert_eq!(replay_scenario_name(Some(copy), svg), "oval");
        assert_eq!(replay_scenario_name(Some(copy), "<svg/>"), "scenario");
        let other = Path::new("maps/town.svg");
        assert_eq!(replay_scenario_name(Some(other), svg), "town");
        assert_eq!(replay_scenario_name(None, svg), "roads");

        let mut config = Config::default();
        assert_eq!(wiring_suffix(&config), "");
        config.substrate.recurrence = vivae_lab::config::Recurrence::SelfLoops;
        config.substrate.normalize_by = vivae_lab::config::NormalizeBy::Area;
        assert_eq!(wiring_suffix(&config), "-normalize-by-area-recurrence-self");
        config.substrate.normalize_self_loops = false;
        assert!(wiring_suffix(&config).contains("-normalize-self-loops-false"));
    }
}

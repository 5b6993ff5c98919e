//! `vivae replay`: runs a genome (a run's champion, an elite or a front
//! member, or a genome file) and draws its trajectories; the genome of a task
//! without figures prints its episode's end instead.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::report;
use clap::Args;
use vivae_lab::config::Config;
use vivae_lab::io::bad_input;
use vivae_lab::rundir;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;

use super::args::{EpisodeArgs, MemberChoice, Resolution, Wiring};
use super::overrides::{Overrides, apply_overrides, scenario_path};

/// Options of `vivae replay`.
#[derive(Args, Debug)]
#[command(mut_arg("steps", |a| a.help("Simulation steps")))]
#[command(mut_arg("robots", |a| a.help(
    "Robots: the scenario's first N, 0 = all (default: the run's number on \
     the run's scenario, all of them on another scenario)"
)))]
pub struct ReplayArgs {
    /// A run directory or a genome JSON file (champion.json).
    pub source: PathBuf,
    /// Scenario SVG file or shipped name (default: the run's).
    #[arg(long, value_name = "FILE|NAME")]
    pub scenario: Option<PathBuf>,
    #[command(flatten)]
    pub resolution: Resolution,
    #[command(flatten)]
    pub episode: EpisodeArgs,
    #[command(flatten)]
    pub member: MemberChoice,
    /// Folder for the trajectory figure (default: replay/ beside the source).
    #[arg(short, long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub wiring: Wiring,
    /// Placement of a scenario's random obstacles and traffic, as an
    /// evaluation with this seed has it (default 0); training draws its
    /// placements from hashed seeds, so small numbers are ones never trained on.
    #[arg(long, value_name = "N")]
    pub placement_seed: Option<u64>,
    /// Distance rays of the second input sheet, re-sampled from the run's
    /// (default: the run's).
    #[arg(long, value_name = "N")]
    pub distance_rays: Option<usize>,
    /// Blind the distance rays: every ray reads "nothing in range" whatever
    /// is in front of it, the rest of the robot as it was (to compare with
    /// the replay that sees).
    #[arg(long)]
    pub blind_rays: bool,
    /// Also draw the swerve: zoomed in on the block or scripted robot whose
    /// meeting blinding the rays changes most, the robot's path seeing and
    /// blinded (swerve-pN.png beside the trajectories); prints the least
    /// clearance of each in px, 0 where they touch.
    #[arg(long)]
    pub swerve: bool,
    /// Also write every robot's meetings with the blocks placed for the
    /// episode (meetings-pN.csv beside the trajectories: the line it came
    /// on, whether the block lay on it, touches, sideways shift, when a ray
    /// first showed the block) and print their counts.
    #[arg(long)]
    pub meetings: bool,
    /// Arithmetic of the controller (exact|fast; default: the run's): a
    /// champion evolved in one precision re-scored in the other.
    #[arg(long, value_name = "exact|fast")]
    pub precision: Option<vivae_neat::Precision>,
}

impl ReplayArgs {
    /// The config keys these options override; `robots` is the number of robots asked for.
    fn overrides(&self, robots: Option<usize>) -> Overrides {
        Overrides {
            scenario: self.scenario.iter().cloned().collect(),
            resolution: self.resolution,
            episode: EpisodeArgs {
                steps: self.episode.steps,
                robots,
            },
            wiring: self.wiring,
            distance_rays: self.distance_rays,
            precision: self.precision,
            ..Overrides::default()
        }
    }
}

/// A multi-map run replays on its first training map unless told otherwise.
fn first_map_unless_told(args: &ReplayArgs, config: &mut vivae_lab::config::Config) {
    if args.scenario.is_none() && vivae_lab::tasks::maps::is_multi_map(config) {
        let maps = std::mem::take(&mut config.experiment.scenarios);
        eprintln!(
            "replaying on the first training map, {} (of {}: {}); choose another with --scenario",
            maps[0],
            maps.len(),
            maps.join(", ")
        );
        config.experiment.scenario = maps[0].clone();
    }
}

/// Runs `vivae replay`.
pub fn run(args: ReplayArgs) -> anyhow::Result<ExitCode> {
    super::report::refuse_own_driver(&args.source, "replay")?;
    let (mut champion, mut config, base) = vivae_lab::tasks::load_genome_source(&args.source)?;
    let member = args.member.member();
    if let Some(member) = member {
        use vivae_lab::search::files::read_member;
        (champion.genome, champion.fitness, champion.generation) =
            read_member(&args.source, member)?;
    }
    if !vivae_lab::tasks::has_substrate(&config) {
        return replay_without_figures(&args, &champion, config);
    }
    first_map_unless_told(&args, &mut config);
    // Another scenario has its own robot starts: all of them, unless told.
    let robots = args.episode.robots.or(args.scenario.as_ref().map(|_| 0));
    apply_overrides(&mut config, &args.overrides(robots))?;
    let path = scenario_path(&config);
    if let Some(p) = path
        .as_deref()
        .filter(|p| args.scenario.is_none() && !p.exists())
    {
        return Err(bad_input(format!(
            "{}: the champion's scenario {} is not there; name one with --scenario FILE",
            args.source.display(),
            p.display()
        ))
        .into());
    }
    let scenario = load_scenario(path.as_deref())?;
    let experiment = blinded(&args, Episode::new(&config, &scenario.scenario))?;
    if let Some(seed) = args.placement_seed.filter(|_| !experiment.varies()) {
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
            args.placement_seed.unwrap_or(0)
        );
    }
    let experiment = experiment.with_placement_seed(args.placement_seed.unwrap_or(0));
    // Checked before anything is written: a genome that does not fit is bad input.
    experiment
        .robot_controller(&champion.genome)
        .map_err(|e| vivae_lab::Error::Genome {
            path: args.source.clone(),
            reason: format!("the genome's {e}"),
        })?;
    // Said once the genome is known to fit, so that an error stays one line.
    if champion.config.is_none() && !args.source.is_dir() {
        eprintln!(
            "warning: {} records no config (written by an older vivae): replaying with the default config and flags; replay its run directory instead if you have it",
            args.source.display()
        );
    }
    let out = args.out.clone().unwrap_or_else(|| base.join("replay"));
    vivae_lab::io::create_dirs(&out)?;
    let name = report::replay_scenario_name(path.as_deref(), &scenario.text);
    let replay = report::replay(&experiment, &config, &champion, &name, &out, member)?;
    println!(
        "fitness={} on_road={:.4} speed={:.4} {}",
        replay.fitness,
        replay.on_road,
        replay.speed,
        replay.behaviour.fields()
    );
    eprintln!("figure: {}", replay.figure.display());
    if args.swerve {
        swerve_figure(&args, &experiment, &champion, &out)?;
    }
    if args.meetings {
        meetings_csv(&experiment, &config, &champion.genome, &args, &out)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The replay's episode, its rays blinded with `--blind-rays` (and, with
/// `--meetings`, checked to have a route): refused before anything is said
/// about the replay, so that an error stays one line.
fn blinded(
    args: &ReplayArgs,
    experiment: Result<Episode, vivae_lab::error::EpisodeError>,
) -> anyhow::Result<Episode> {
    let experiment = experiment.map_err(vivae_lab::Error::from)?;
    let sc = experiment.world().scenario();
    if args.meetings && sc.routes.is_empty() {
        return Err(bad_input(format!(
            "--meetings: {}: meetings are measured along a route (a path labelled Route), and the scenario has none",
            sc.source
        ))
        .into());
    }
    match args.blind_rays {
        true => {
            Ok((experiment.with_blind_rays())
                .map_err(|e| bad_input(format!("--blind-rays: {e}")))?)
        }
        false => Ok(experiment),
    }
}

/// `--meetings`: writes `meetings-pN[-blind-rays].csv` into `out` and prints
/// the counts. The rays whose sight is recorded are the robots' own
/// (re-sampled by `--distance-rays`), or for robots without rays the default
/// sheet's (5 rays over 180°, 100 px): what rays would have shown the same paths.
fn meetings_csv(
    experiment: &Episode,
    config: &Config,
    genome: &vivae_neat::Genome,
    args: &ReplayArgs,
    out: &std::path::Path,
) -> anyhow::Result<()> {
    use vivae_lab::tasks::driving::meetings::{self, MeetingCounts};
    let controller =
        (experiment.robot_controller(genome)).map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let layout: vivae_sim::DistanceSensors = config.distance_sensors.layout().unwrap_or_default();
    let all = meetings::meetings(experiment, &controller, Some(&layout.grid()))
        .map_err(|e| bad_input(format!("--meetings: {e}")))?;
    let blind = if experiment.blind_rays() {
        "-blind-rays"
    } else {
        ""
    };
    let placement = args.placement_seed.unwrap_or(0);
    let path = out.join(format!("meetings-p{placement}{blind}.csv"));
    vivae_lab::io::write_atomic(&path, meetings::csv(&all).as_bytes())?;
    println!("{}", MeetingCounts::of(&all).fields());
    eprintln!("meetings: {}", path.display());
    Ok(())
}

/// `--swerve`: the zoomed figure of the meeting blinding changes most, and its line.
fn swerve_figure(
    args: &ReplayArgs,
    experiment: &Episode,
    champion: &rundir::Champion,
    out: &std::path::Path,
) -> anyhow::Result<()> {
    let placement = args.placement_seed.unwrap_or(0);
    let blind = if args.blind_rays { "-blind-rays" } else { "" };
    // Named for its run (a run's scenario is its copy, scenario.svg).
    let run = match args.source.is_dir() {
        true => args.source.as_path(),
        false => args.source.parent().unwrap_or(&args.source),
    };
    let run = run
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let title = format!("{run}, placement {placement}");
    match crate::figures::swerve::swerve(experiment, &champion.genome, &title)? {
        None => eprintln!("swerve: the scenario has no placed block nor scripted robot to meet"),
        Some((figure, m)) => {
            let path = out.join(format!("swerve-p{placement}{blind}"));
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

/// `vivae replay` of a genome of a task that draws no figures: its
/// episode's end (the task's replay text), on stdout.
fn replay_without_figures(
    args: &ReplayArgs,
    champion: &rundir::Champion,
    mut config: Config,
) -> anyhow::Result<ExitCode> {
    if let Some(seed) = args.placement_seed {
        return Err(bad_input(format!(
            "--placement-seed {seed}: a {} run places nothing at random, so no seed changes the replay",
            config.experiment.task.name()
        ))
        .into());
    }
    apply_overrides(&mut config, &args.overrides(args.episode.robots))?;
    let maps = vivae_lab::tasks::maps::load(&config)?;
    let task = vivae_lab::tasks::build(&config, &maps)?;
    task.check_genome(&champion.genome)
        .map_err(|reason| vivae_lab::Error::Genome {
            path: args.source.clone(),
            reason,
        })?;
    let name = config.experiment.task.name();
    let (line, note) = (task.replay_text(&champion.genome)).ok_or_else(|| {
        bad_input(format!(
            "{}: task {name} does not record episodes: replay needs a task that scores a genome again with a trace (a plain task's Plain::TRACES) or draws its own",
            args.source.display()
        ))
    })?;
    if let Some(csv) = task.episode_csv(&champion.genome) {
        let base = if args.source.is_dir() {
            args.source.clone()
        } else {
            args.source.parent().map(PathBuf::from).unwrap_or_default()
        };
        let out = (args.out.clone()).unwrap_or_else(|| base.join(rundir::replace::REPLAY_DIR));
        vivae_lab::io::create_dirs(&out)?;
        let path = out.join("episode.csv");
        vivae_lab::io::write_atomic(&path, csv.as_bytes())?;
        eprintln!("episode: {}", path.display());
    }
    println!("{line}");
    eprintln!("{note}");
    Ok(ExitCode::SUCCESS)
}

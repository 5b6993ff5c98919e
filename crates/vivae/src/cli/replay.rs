//! `vivae replay`: runs a genome (a run's champion, an elite or a front
//! member, or a genome file); a task that draws its replay (its
//! program-side tools' `replay`, e.g. the driving trajectories) draws it,
//! the genome of any other task prints its episode's end instead.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::tasks::ReplayRequest;
use clap::Args;
use vivae_lab::config::Config;
use vivae_lab::io::bad_input;
use vivae_lab::rundir;

use super::args::{EpisodeArgs, MemberChoice, Resolution, Wiring};
use super::overrides::apply_overrides;
use vivae_lab::run::prepare::Overrides;

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
            scenario: (self.scenario.iter())
                .map(|p| p.to_string_lossy().into_owned())
                .collect(),
            sensors: self.resolution.sensors,
            neurons: self.resolution.neurons,
            steps: self.episode.steps,
            robots,
            normalize_by: self.wiring.normalize_by,
            normalize_self_loops: self.wiring.normalize_self_loops,
            recurrence: self.wiring.recurrence,
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
    // A task that draws its replay (its program-side tools) is given the
    // genome and the config with the command's flags; any other prints its
    // replay text.
    let tools = crate::tasks::of_task(config.experiment.task.name());
    let Some(draw) = tools.and_then(|t| t.replay) else {
        return replay_without_figures(&args, &champion, config);
    };
    first_map_unless_told(&args, &mut config);
    // Another scenario has its own robot starts: all of them, unless told.
    let robots = args.episode.robots.or(args.scenario.as_ref().map(|_| 0));
    apply_overrides(&mut config, &args.overrides(robots))?;
    draw(&ReplayRequest {
        source: &args.source,
        champion: &champion,
        config: &config,
        scenario_given: args.scenario.is_some(),
        placement_seed: args.placement_seed,
        blind_rays: args.blind_rays,
        swerve: args.swerve,
        meetings: args.meetings,
        member,
        out: args.out.clone().unwrap_or_else(|| base.join("replay")),
    })?;
    Ok(ExitCode::SUCCESS)
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
            "--placement-seed {seed}: {} run places nothing at random, so no seed changes the replay",
            vivae_lab::error::a(config.experiment.task.name())
        ))
        .into());
    }
    // The drawing flags mean something only to a task that draws its
    // replay; silently ignoring one would let a user think it took effect.
    let drawing = [
        ("--blind-rays", args.blind_rays),
        ("--swerve", args.swerve),
        ("--meetings", args.meetings),
    ];
    if let Some((flag, _)) = drawing.iter().find(|(_, on)| *on) {
        return Err(bad_input(format!(
            "{flag}: {} run draws no replay of its own, and the flag applies only to a task that does",
            vivae_lab::error::a(config.experiment.task.name())
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

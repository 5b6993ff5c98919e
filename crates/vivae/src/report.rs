//! Reports of runs: figures at the end of a run, replays, scenario summaries.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use vivae_neat::Genome;
use vivae_sim::draw::{self, DrawOptions};
use vivae_sim::{Scenario, ScenarioSummary, SurfaceSensors, World};

use crate::figures;
use crate::figures::convergence::ConvergenceOptions;
use vivae_lab::config::Config;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::{bad_input, write_atomic};
use vivae_lab::run::Run;
use vivae_lab::rundir::{self, Champion, files};
use vivae_lab::search::files::Member;
use vivae_lab::tasks::driving::episode::{Episode, EpisodeRecord};
use vivae_lab::tasks::driving::training_of;

/// What the end of a run reports.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// The champion's fitness.
    pub champion_fitness: f64,
    /// The generation it was found in.
    pub champion_generation: u32,
    /// Its fraction of robot-steps on road.
    pub champion_on_road: f64,
    /// On several training maps, each map's label and the champion's fitness
    /// on it (their mean is `champion_fitness`); empty on one map.
    pub per_map: Vec<(String, f64)>,
}

/// Writes a figure as `NAME.svg` and `NAME.png` in `dir`.
fn write_figure(dir: &Path, name: &str, svg: &str, png: &[u8]) -> Result<()> {
    write_atomic(&dir.join(format!("{name}.svg")), svg.as_bytes())?;
    write_atomic(&dir.join(format!("{name}.png")), png)
}

/// Runs `genome` with trajectories recorded and draws them; returns the episode.
pub fn trajectory_figure(
    experiment: &Episode,
    genome: &Genome,
    title: &str,
    dir: &Path,
    name: &str,
) -> Result<EpisodeRecord> {
    let controller = experiment.robot_controller(genome)?;
    let (episode, world) = experiment.run_world(&controller, true);
    let on_road = episode
        .on_road
        .expect("a recorded episode measures time on road");
    let mut title = format!(
        "{title} — fitness {:.3} px/step, {:.1}% on road",
        episode.fitness,
        100.0 * on_road
    );
    // Where avoidance is the question, say what was hit.
    if let Some(b) = episode.behaviour.as_ref().filter(|_| {
        experiment.varies()
            || experiment.placement().is_some()
            || !experiment.world().traffic().is_empty()
    }) {
        let c = &b.contacts;
        title += &format!(
            "; contacts/1000 robot-steps: robot {:.2}, traffic {:.2}, obstacle {:.2}, wall {:.2}",
            c.robot, c.traffic, c.obstacle, c.wall
        );
    }
    let options = DrawOptions {
        trajectories: true,
        title: Some(title),
        ..DrawOptions::default()
    };
    let svg = draw::render_svg(&world, &options);
    let png = draw::render_png(&world, &options).map_err(|e| Error::Render {
        what: "trajectories",
        reason: e.to_string(),
    })?;
    write_figure(dir, name, &svg, &png)?;
    Ok(episode)
}

/// Writes every figure of a finished run into `RUN/figures/`, and `report.html`;
/// then, last, records how many generations they show
/// ([`vivae_lab::rundir::mark_drawn`]), so that a crash before the end leaves
/// them marked stale and `vivae resume` redraws them.
pub fn finish_run(run: &Run) -> Result<RunSummary> {
    let dir = run.dir().join(files::FIGURES);
    vivae_lab::io::create_dirs(&dir)?;
    vivae_lab::rundir::unmark_drawn(run.dir())?;
    let experiment = (training_of(run.task()).map(|t| t.primary())).ok_or_else(|| {
        let task = &run.config().experiment.task;
        bad_input(format!("a {task} run has no trajectory figures"))
    })?;
    let champion = run.champion().ok_or(Error::NoChampion)?;
    // The episodes' figures on one core, the network's and the population's
    // on the other: the two take about as long (each figure is its own files).
    let (drawn, network) = rayon::join(
        || episode_figures(run, experiment, &champion, &dir),
        || {
            let network = network_figure(run, experiment, &champion, &dir)?;
            population_figures(run, &dir)?;
            Ok::<_, Error>(network)
        },
    );
    let DrawnEpisodes {
        generations: episodes,
        champion: episode,
        maps: map_episodes,
    } = drawn?;
    let network_svg = network?;
    // The report shows the same episodes and network: reuse them rather than run them again.
    let mut reuse = crate::report_html::Reuse {
        episodes: episodes.iter().map(|(g, e)| (*g, e)).collect(),
        network_svg: Some(network_svg),
        map_episodes: map_episodes.iter().map(|(_, e)| e).collect(),
    };
    reuse.episodes.push((&champion.genome, &episode));
    crate::report_html::write_reusing(run.dir(), &reuse)?;
    vivae_lab::rundir::mark_drawn(run.dir(), run.done())?;

    // On several maps the champion's fitness is the mean over maps: its time on road too.
    let on_road = |e: &EpisodeRecord| e.on_road.unwrap_or_default();
    let champion_on_road = if map_episodes.is_empty() {
        on_road(&episode)
    } else {
        vivae_lab::tasks::maps::mean(
            &map_episodes
                .iter()
                .map(|(_, e)| on_road(e))
                .collect::<Vec<_>>(),
        )
    };
    Ok(RunSummary {
        champion_fitness: champion.fitness,
        champion_generation: champion.generation,
        champion_on_road,
        per_map: map_episodes
            .into_iter()
            .map(|(l, e)| (l, e.fitness))
            .collect(),
    })
}

/// The episodes [`episode_figures`] drew, which the report shows too.
struct DrawnEpisodes<'r> {
    /// Each figure generation's best genome and its episode.
    generations: Vec<(&'r Genome, EpisodeRecord)>,
    /// The champion's episode on the run's (first) map.
    champion: EpisodeRecord,
    /// The champion's episode on each training map, by map label (empty on one map).
    maps: Vec<(String, EpisodeRecord)>,
}

/// The episodes a finished run draws — the figure generations' bests and
/// the champion, on every training map; returns the episodes (the report
/// shows them too).
fn episode_figures<'r>(
    run: &'r Run,
    experiment: &Episode,
    champion: &Champion,
    dir: &Path,
) -> Result<DrawnEpisodes<'r>> {
    let mut episodes = Vec::new();
    for (generation, _, genome) in run.figure_genomes() {
        let episode = trajectory_figure(
            experiment,
            genome,
            &format!("Best of generation {generation}"),
            dir,
            &format!("trajectories-gen{generation:03}"),
        )?;
        episodes.push((genome, episode));
    }
    let episode = trajectory_figure(
        experiment,
        &champion.genome,
        &format!("Champion (generation {})", champion.generation),
        dir,
        "trajectories-champion",
    )?;
    let map_episodes = per_map_figures(run, &champion.genome, dir)?;
    Ok(DrawnEpisodes {
        generations: episodes,
        champion: episode,
        maps: map_episodes,
    })
}

/// The run's convergence figure and its strategy's own figure, if any.
fn population_figures(run: &Run, dir: &Path) -> Result<()> {
    let fitness = rundir::read_population_csv(&run.dir().join(files::POPULATION))?;
    let convergence = figures::convergence::render(&fitness, &ConvergenceOptions::default())?;
    write_figure(dir, "convergence", &convergence.svg, &convergence.png)?;
    strategy_figure(run, dir)
}

/// The champion's network figure; returns its SVG (the report shows it too).
fn network_figure(
    run: &Run,
    experiment: &Episode,
    champion: &Champion,
    dir: &Path,
) -> Result<String> {
    let controller = experiment.robot_controller(&champion.genome)?;
    let options = crate::report_html::network_options(
        champion.generation,
        champion.fitness,
        run.config().hyperneat.amplitude,
    );
    let network = figures::network::render_robot(experiment, &controller, &options)?;
    write_figure(dir, "network", &network.svg, &network.png)?;
    Ok(network.svg)
}

/// The strategy's own end-of-run figure, if it has one: a grid archive as
/// a heat map (`archive.png`/`.svg`), a two-objective Pareto front
/// (`front.png`/`.svg`).
fn strategy_figure(run: &Run, dir: &Path) -> Result<()> {
    use vivae_lab::search::StrategyFigure as F;
    let strategy = run.search().strategy();
    match strategy.figure(run.config(), run.done()) {
        None => Ok(()),
        Some(F::Grid(grid)) => {
            let figure = figures::archive::render(&grid)?;
            write_figure(dir, "archive", &figure.svg, &figure.png)
        }
        Some(F::Front(f)) => {
            let plot = figures::front::FrontPlot {
                axes: f.objectives.map(|o| figures::front::objective_axis(&o)),
                title: f.title,
                population: f.population,
                front: f.front,
            };
            let figure = figures::front::render(&plot)?;
            write_figure(dir, "front", &figure.svg, &figure.png)
        }
    }
}

/// On several training maps, the champion's trajectories on each, drawn as
/// `trajectories-champion-<map>` in `dir`; returns each map's label and
/// recorded episode. None on one map.
fn per_map_figures(
    run: &Run,
    champion: &Genome,
    dir: &Path,
) -> Result<Vec<(String, EpisodeRecord)>> {
    let Some(training) = training_of(run.task()) else {
        return Ok(Vec::new());
    };
    training
        .map_labels()
        .zip(training.map_experiments())
        .map(|(label, experiment)| {
            let episode = trajectory_figure(
                experiment,
                champion,
                &format!("Champion on training map {label}"),
                dir,
                &champion_map_figure(label),
            )?;
            Ok((label.to_string(), episode))
        })
        .collect()
}

/// The name (no extension) of the champion's figure on training map `label`.
pub fn champion_map_figure(label: &str) -> String {
    format!(
        "trajectories-champion-{}",
        vivae_lab::io::safe_file_stem(label)
    )
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
pub fn replay(
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

/// A plain-text scenario summary; `marks` are the position marks' names.
pub fn scenario_text(s: &ScenarioSummary, marks: &[String]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "arena: {:.1} x {:.1} px",
        s.arena.width, s.arena.height
    );
    let surfaces: Vec<String> = s.surfaces.iter().map(|(k, n)| format!("{k} {n}")).collect();
    let _ = writeln!(out, "surfaces: {}", surfaces.join(", "));
    let _ = writeln!(
        out,
        "fixed obstacles: {}, movable obstacles: {}, pucks: {}, marks: {}",
        s.fixed_obstacles, s.movable_obstacles, s.pucks, s.marks
    );
    if !marks.is_empty() {
        let _ = writeln!(out, "mark names: {}", marks.join(", "));
    }
    let _ = writeln!(out, "robots: {}", s.robots.len());
    if s.robots.is_empty() {
        // Said up front: evolve and replay refuse such a map later.
        let _ = writeln!(
            out,
            "warning: no robots: this scenario can be drawn (scenario render) but not evolved on or replayed; draw robots (see docs/scenario-format.md)"
        );
    }
    for r in &s.robots {
        let _ = writeln!(
            out,
            "  {}: x {:.1} y {:.1} heading {:.1}°",
            r.id, r.x, r.y, r.heading_deg
        );
    }
    for r in &s.routes {
        let shape = if r.closed { "loop" } else { "open" };
        let _ = writeln!(out, "route {}: {:.1} px, {shape}", r.id, r.length);
    }
    for r in &s.obstacle_regions {
        let _ = writeln!(out, "obstacle region {}: {} per episode", r.id, r.count);
    }
    for t in &s.traffic {
        let _ = writeln!(out, "scripted robot {}: follows {}", t.id, t.route);
    }
    for w in &s.warnings {
        let _ = writeln!(out, "warning: {w}");
    }
    out
}

/// Draws a scenario (with sensors of `sensors` on every robot) as SVG or PNG
/// by `out`'s extension. `sensors` is held to the limit an evolving run's
/// sensor sheet has ([`vivae_lab::config::MAX_SENSORS`]).
pub fn render_scenario(
    scenario: &Scenario,
    sensors: Option<PolarGrid>,
    out: &Path,
) -> Result<Vec<u8>> {
    if let Some(g) = sensors {
        let count = g.rings.saturating_mul(g.angles);
        let max = vivae_lab::config::MAX_SENSORS;
        if count > max {
            return Err(bad_input(format!(
                "--sensors {}x{} = {count} sensors: must be at most {max}",
                g.rings, g.angles
            )));
        }
    }
    let world = World::new(scenario, &Default::default()).map_err(|e| bad_input(e.to_string()))?;
    let options = DrawOptions {
        surface_sensors: sensors.map(|g| SurfaceSensors {
            rings: g.rings,
            angles: g.angles,
            ..SurfaceSensors::default()
        }),
        title: Some(scenario.source.clone()),
        ..DrawOptions::default()
    };
    match out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("svg") => Ok(draw::render_svg(&world, &options).into_bytes()),
        Some("png") => draw::render_png(&world, &options).map_err(|e| Error::Render {
            what: "scenario",
            reason: e.to_string(),
        }),
        _ => Err(bad_input(format!(
            "{}: output must end in .png or .svg",
            out.display()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scenario_without_robots_is_said_up_front() {
        let scenario = vivae_lab::tasks::scenarios::load_scenario(None)
            .unwrap()
            .scenario;
        let mut summary = scenario.summary();
        assert!(!scenario_text(&summary, &[]).contains("no robots"));
        summary.robots.clear();
        let text = scenario_text(&summary, &[]);
        assert!(
            text.contains("robots: 0\nwarning: no robots: this scenario can be drawn"),
            "{text}"
        );
    }

    #[test]
    fn scenario_text_rounds_and_names_robots_and_marks() {
        let scenario = vivae_lab::tasks::scenarios::load_scenario(None)
            .unwrap()
            .scenario;
        let mut summary = scenario.summary();
        summary.arena.width = 793.700_787_4;
        let text = scenario_text(&summary, &["start".to_string()]);
        assert!(text.starts_with("arena: 793.7 x 600.0 px\n"), "{text}");
        assert!(text.contains("mark names: start\n"), "{text}");
        assert!(text.contains("  robot1: x "), "{text}");
    }

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

//! `report.html`: one self-contained, offline page describing a finished run.
//!
//! Everything is read from the run directory (config, scenario, CSV files,
//! champion, per-generation best genomes), so `vivae report RUN_DIR` rebuilds
//! exactly what the end of a run writes. Data goes into the page as one JSON
//! block; the scripts that draw it are the viewer's own (`assets/`), inlined.

use std::path::{Path, PathBuf};

use serde::Serialize;
use vivae_neat::Genome;
use vivae_sim::draw::{self, DrawOptions};
use vivae_sim::{Scenario, World};

use crate::figures::convergence::{self, ConvergenceOptions};
use crate::figures::network::{self, NetworkOptions};
use vivae_lab::io::{bad_input, read_text, write_atomic};
use vivae_lab::rundir::GenerationRow;
use vivae_lab::rundir::{self, files};
use vivae_lab::search::StrategyReport;
use vivae_lab::tasks::driving::episode::{Episode, EpisodeRecord};
use vivae_lab::tasks::plain::REPLAY_SEED;
use vivae_lab::tasks::read_champion;
use vivae_lab::tasks::read_config;
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_lab::tasks::sketch::Film;

/// The page template; `/*VIVAE-DATA*/`, `/*VIVAE-CSS*/` and `/*VIVAE-JS*/` are filled in.
const TEMPLATE: &str = include_str!("../assets/report.html");
/// Styles shared with the viewer.
pub(crate) const STYLE_CSS: &str = include_str!("../assets/style.css");
/// Drawing of scenarios, robots and trails (shared with the viewer).
pub(crate) const SCENE_JS: &str = include_str!("../assets/scene.js");
/// Line, stacked-area and table drawing (shared with the viewer).
pub(crate) const PLOTS_JS: &str = include_str!("../assets/plots.js");
/// The report page's own script.
const REPORT_JS: &str = include_str!("../assets/report.js");
/// The animation of a task's film (its steps as shapes, any task's alike).
const FILM_JS: &str = include_str!("../assets/film.js");

/// One animated episode in the report.
#[derive(Debug, Serialize)]
struct EpisodeData {
    label: String,
    /// Index of its map in [`ReportData::scenes`].
    scene: usize,
    fitness: f64,
    on_road: f64,
    /// Per robot, `[x0, y0, x1, y1, …]` rounded to 0.01 px.
    paths: Vec<Vec<f64>>,
}

/// Everything the report page shows.
#[derive(Debug, Serialize)]
struct ReportData {
    title: String,
    config: String,
    /// The maps episodes run on: the run's scenario, or each training map.
    scenes: Vec<SceneData>,
    /// On several training maps, each map's name (else empty); the champion's
    /// episode on map `k` is `episodes[k]`.
    maps: Vec<String>,
    episodes: Vec<EpisodeData>,
    generations: Vec<GenerationRow>,
    /// Per generation, `[species id, members]`.
    species: Vec<Vec<(u32, usize)>>,
    convergence_svg: String,
    network_svg: String,
    /// Colours of the best and mean curves, as `convergence.png` draws them.
    curve_colours: [String; 2],
    /// What a strategy beyond NEAT adds (none for NEAT).
    strategy: Option<StrategyData>,
    /// The task of a report of curves alone (no scenario, episodes or network figure).
    #[serde(skip_serializing_if = "Option::is_none")]
    task: Option<String>,
    /// The champion's replay as pictures, for a task that draws its steps.
    #[serde(skip_serializing_if = "Option::is_none")]
    film: Option<FilmData>,
    /// The champion's validation on fresh episodes (`validation.json`), in a sentence.
    #[serde(skip_serializing_if = "Option::is_none")]
    validation: Option<String>,
}

/// The champion's replay as a task draws it, and what it is.
#[derive(Debug, Serialize)]
struct FilmData {
    /// Whose replay it is, and on which episodes.
    label: String,
    #[serde(flatten)]
    film: Film,
}

/// What a strategy other than NEAT adds to the report: its part
/// (from its own file in `vivae_lab::search`) and its columns of `generations.csv`.
#[derive(Debug, Serialize)]
struct StrategyData {
    #[serde(flatten)]
    report: StrategyReport,
    /// The strategy's own columns of `generations.csv`.
    columns: Vec<String>,
    /// Per generation, its values of those columns (`null` where empty).
    values: Vec<Vec<Option<f64>>>,
}

/// A scenario as the pages draw it: the static picture and the robot size.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct SceneData {
    /// Arena width in px.
    pub width: f64,
    /// Arena height in px.
    pub height: f64,
    /// Robot radius in px.
    pub robot_radius: f64,
    /// SVG of the arena without robots.
    pub svg: String,
}

impl SceneData {
    /// The static picture of `scenario` (its robots left out: the pages draw them).
    pub(crate) fn new(scenario: &Scenario, world: &World) -> SceneData {
        let mut empty = scenario.clone();
        empty.robots.clear();
        let svg = World::new(&empty, world.params())
            .map(|w| {
                draw::render_svg(
                    &w,
                    &DrawOptions {
                        trajectories: false,
                        // The page explains colours itself and lays robots over the arena.
                        legend: false,
                        ..DrawOptions::default()
                    },
                )
            })
            .unwrap_or_default();
        SceneData {
            width: scenario.width(),
            height: scenario.height(),
            robot_radius: world.params().robot_radius,
            svg,
        }
    }
}

/// Rounds to 0.01 so the page stays small.
fn round2(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

/// What the end of a run has computed already and the report can reuse
/// (recorded episodes by genome, the network figure's SVG): the file is the
/// same either way, only faster to build (at 32×96 → 9×9 the episodes and the
/// network dominate the end of a run).
#[derive(Debug, Default)]
pub struct Reuse<'a> {
    /// Episodes recorded with trajectories, and the genome each one ran.
    pub episodes: Vec<(&'a Genome, &'a EpisodeRecord)>,
    /// The champion's network figure, drawn with the report's own options.
    pub network_svg: Option<String>,
    /// On several training maps, the champion's episode on each, in map order.
    pub map_episodes: Vec<&'a EpisodeRecord>,
}

/// The episode of `genome` on `experiment` (map `scene`), taken from
/// `recorded` when it holds it with trajectories, else run now.
fn episode(
    experiment: &Episode,
    genome: &Genome,
    (label, scene): (String, usize),
    recorded: Option<&EpisodeRecord>,
) -> vivae_lab::Result<EpisodeData> {
    let recorded = recorded.filter(|e| e.trajectories.is_some() && e.on_road.is_some());
    let ran;
    let run = match recorded {
        Some(e) => e,
        None => {
            ran = experiment.run(&experiment.robot_controller(genome)?, true);
            &ran
        }
    };
    let paths = run
        .trajectories
        .as_deref()
        .unwrap_or_default()
        .iter()
        .map(|t| t.iter().flat_map(|p| [round2(p.x), round2(p.y)]).collect())
        .collect();
    Ok(EpisodeData {
        label,
        scene,
        fitness: run.fitness,
        on_road: run.on_road.unwrap_or_default(),
        paths,
    })
}

/// On several training maps, the champion's episode on each (labelled with
/// the map), each map's scene and the maps' names; nothing on one map.
fn map_episodes(
    dir: &Path,
    config: &vivae_lab::config::Config,
    champion: &rundir::Champion,
    reuse: &Reuse<'_>,
) -> vivae_lab::Result<(Vec<EpisodeData>, Vec<SceneData>, Vec<String>)> {
    if !vivae_lab::tasks::maps::is_multi_map(config) {
        return Ok(Default::default());
    }
    let loaded = vivae_lab::tasks::maps::load_run(dir, config, None)?;
    let training = vivae_lab::tasks::driving::training::Training::new(config, &loaded)?;
    let (mut episodes, mut scenes, mut maps) = (Vec::new(), Vec::new(), Vec::new());
    let count = loaded.len();
    for (k, ((label, experiment), map)) in training
        .map_labels()
        .zip(training.map_experiments())
        .zip(&loaded)
        .enumerate()
    {
        let name = format!(
            "Champion (generation {}) on {label}, map {} of {count}",
            champion.generation,
            k + 1
        );
        episodes.push(episode(
            experiment,
            &champion.genome,
            (name, k),
            reuse.map_episodes.get(k).copied(),
        )?);
        scenes.push(SceneData::new(&map.loaded.scenario, experiment.world()));
        maps.push(label.to_string());
    }
    Ok((episodes, scenes, maps))
}

/// The strategy's part of the report of the run in `dir` (none for NEAT):
/// what its own file reads of the run directory, the objectives named as
/// the figures name them, and its columns of `generations.csv`.
fn strategy_data(
    dir: &Path,
    config: &vivae_lab::config::Config,
    experiment: &Episode,
) -> vivae_lab::Result<Option<StrategyData>> {
    let entry = vivae_lab::search::entry_of(config)?;
    let Some(mut report) = (entry.report)(dir, config, experiment.robots())? else {
        return Ok(None);
    };
    report.objectives = (report.objectives.iter())
        .map(|o| crate::figures::front::objective_axis(o))
        .collect();
    let (columns, values) = strategy_columns(&dir.join(files::GENERATIONS), entry)?;
    Ok(Some(StrategyData {
        report,
        columns,
        values,
    }))
}

/// One generation's values of a strategy's columns (`None` where empty).
type Row = Vec<Option<f64>>;

/// The columns strategy `entry` adds to `generations.csv` at `path`, and
/// their values on each complete line (a running evolution may be writing
/// the last); an empty field is `None`.
fn strategy_columns(
    path: &Path,
    entry: &vivae_lab::search::StrategyEntry,
) -> vivae_lab::Result<(Vec<String>, Vec<Row>)> {
    let names: Vec<String> = (entry.extra_columns.split(',').skip(1))
        .map(String::from)
        .collect();
    let text = read_text(path)?;
    let complete = text.rsplit_once('\n').map_or("", |(done, _)| done);
    let mut values = Vec::new();
    for (i, line) in complete.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let Some(ours) = fields.len().checked_sub(names.len()).map(|k| &fields[k..]) else {
            return Err(vivae_lab::Error::RunFile {
                path: path.to_path_buf(),
                reason: format!("line {}: fewer fields than the strategy's columns", i + 1),
            });
        };
        let number = |f: &&str| f.parse::<f64>().ok().filter(|v| v.is_finite());
        values.push(ours.iter().map(number).collect());
    }
    Ok((names, values))
}

/// Embeds JSON in a `<script>` block: `</` cannot close it early.
fn script_safe(json: &str) -> String {
    json.replace("</", "<\\/")
}

/// Builds the report of the run in `dir` as one HTML document.
pub fn build(dir: &Path) -> vivae_lab::Result<String> {
    build_reusing(dir, &Reuse::default())
}

/// The champion's network figure options as the report and the end of a run draw it.
pub(crate) fn network_options(generation: u32, fitness: f64, amplitude: f64) -> NetworkOptions {
    NetworkOptions {
        title: format!("Champion controller (generation {generation}, fitness {fitness:.3})"),
        weight_scale: amplitude,
        ..NetworkOptions::default()
    }
}

/// The report's episodes: the champion's (on each training map, for several),
/// then the best of the figure generations on the first map; with the maps'
/// scenes and names (none on one map).
fn all_episodes(
    dir: &Path,
    config: &vivae_lab::config::Config,
    experiment: &Episode,
    champion: &rundir::Champion,
    best: &[rundir::GenerationBest],
    reuse: &Reuse<'_>,
) -> vivae_lab::Result<(Vec<EpisodeData>, Vec<SceneData>, Vec<String>)> {
    let recorded = |genome: &Genome| {
        reuse
            .episodes
            .iter()
            .find(|(g, _)| *g == genome)
            .map(|(_, e)| *e)
    };
    let (mut episodes, scenes, maps) = map_episodes(dir, config, champion, reuse)?;
    let on_first = if maps.is_empty() {
        String::new()
    } else {
        format!(" on {}", maps[0])
    };
    if maps.is_empty() {
        episodes.push(episode(
            experiment,
            &champion.genome,
            (format!("Champion (generation {})", champion.generation), 0),
            recorded(&champion.genome),
        )?);
    }
    for g in vivae_lab::run::FIGURE_GENERATIONS {
        if let Some(b) = best.iter().find(|b| b.generation == g) {
            episodes.push(episode(
                experiment,
                &b.genome,
                (format!("Best of generation {g}{on_first}"), 0),
                recorded(&b.genome),
            )?);
        }
    }
    Ok((episodes, scenes, maps))
}

/// What every run's report shows, read from the files every run writes: its
/// config, curves, species, convergence and table (no scenes, episodes,
/// network or strategy); and the best genome of each generation.
fn curves_data(dir: &Path) -> vivae_lab::Result<(ReportData, Vec<rundir::GenerationBest>)> {
    let best = rundir::read_best_genomes(&dir.join(files::BEST_GENOMES))?;
    let generations_csv = dir.join(files::GENERATIONS);
    let generations = rundir::read_generations(&generations_csv)?;
    if generations.is_empty() {
        return Err(vivae_lab::Error::RunFile {
            path: generations_csv,
            reason: "no generation recorded".into(),
        });
    }
    let fitness = rundir::read_population_csv(&dir.join(files::POPULATION))?;
    let data = ReportData {
        title: title_of(dir),
        config: read_text(&dir.join(files::CONFIG))?,
        scenes: Vec::new(),
        maps: Vec::new(),
        episodes: Vec::new(),
        generations,
        species: best.iter().map(|b| b.species.clone()).collect(),
        convergence_svg: convergence::render_svg(&fitness, &ConvergenceOptions::default())
            .map_err(vivae_lab::Error::from)?,
        network_svg: String::new(),
        curve_colours: [convergence::best_colour(), convergence::MEAN_COLOUR].map(convergence::hex),
        strategy: None,
        task: None,
        film: None,
        validation: None,
    };
    Ok((data, best))
}

/// The report of a run of a task without a substrate network: its curves
/// ([`curves_data`]), headed by its task, and its champion's replay
/// animated when the task draws its steps.
fn build_curves(dir: &Path, config: &vivae_lab::config::Config) -> vivae_lab::Result<String> {
    let (data, _) = curves_data(dir)?;
    page_of(&ReportData {
        task: Some(config.experiment.task.name().to_string()),
        film: film_of(dir, config)?,
        validation: vivae_lab::tasks::validation::read(dir)?.map(|v| {
            let mut s = v.sentence();
            if let Some(c) = s.get_mut(..1) {
                c.make_ascii_uppercase();
            }
            s + " (validation.json)"
        }),
        ..data
    })
}

/// The champion's replay as its task draws it; none for a task that draws
/// no steps, or before the run's first champion is written.
fn film_of(dir: &Path, config: &vivae_lab::config::Config) -> vivae_lab::Result<Option<FilmData>> {
    let path = dir.join(files::CHAMPION);
    if !path.is_file() {
        return Ok(None);
    }
    // A task whose episodes a host plays (Gymnasium's, in Python) cannot be
    // built by the program: no film here; its curves still show.
    if vivae_lab::tasks::entry_of(config).is_ok_and(|t| t.host.is_some()) {
        return Ok(None);
    }
    let champion = read_champion(&path)?;
    let maps = vivae_lab::tasks::maps::load_run(dir, config, None)?;
    let task = vivae_lab::tasks::build(config, &maps)?;
    task.check_genome(&champion.genome)
        .map_err(|reason| vivae_lab::Error::Genome { path, reason })?;
    Ok(task.film(&champion.genome).map(|film| FilmData {
        label: format!(
            "Champion (generation {}, fitness {:.3}) on the episodes of seed {REPLAY_SEED} (training used others)",
            champion.generation, champion.fitness
        ),
        film,
    }))
}

/// The run's name for the page's title: its directory's.
fn title_of(dir: &Path) -> String {
    dir.canonicalize()
        .unwrap_or_else(|_| dir.to_path_buf())
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into())
}

/// The page of `data`.
fn page_of(data: &ReportData) -> vivae_lab::Result<String> {
    let json =
        script_safe(
            &serde_json::to_string(data).map_err(|e| vivae_lab::Error::Serialize {
                what: "the report's data",
                reason: e.to_string(),
            })?,
        );
    let js = [SCENE_JS, PLOTS_JS, FILM_JS, REPORT_JS].join("\n");
    Ok(report_page(TEMPLATE, &js, &json))
}

/// [`build`], reusing what the end of a run computed already.
pub fn build_reusing(dir: &Path, reuse: &Reuse<'_>) -> vivae_lab::Result<String> {
    let config = read_config(&dir.join(files::CONFIG))?;
    if !vivae_lab::tasks::has_substrate(&config) {
        return build_curves(dir, &config);
    }
    let scenario = load_scenario(Some(&dir.join(files::SCENARIO)))?;
    let experiment = Episode::new(&config, &scenario.scenario)
        .map_err(|e| bad_input(format!("{}: {e}", dir.display())))?;
    let champion = read_champion(&dir.join(files::CHAMPION))?;
    let (curves, best) = curves_data(dir)?;
    let (episodes, scenes, maps) =
        all_episodes(dir, &config, &experiment, &champion, &best, reuse)?;
    let network_svg = match &reuse.network_svg {
        Some(svg) => svg.clone(),
        None => network::figure_svg_robot(
            &experiment,
            &experiment.robot_controller(&champion.genome)?,
            &network_options(
                champion.generation,
                champion.fitness,
                config.hyperneat.amplitude,
            ),
        )
        .map_err(vivae_lab::Error::from)?,
    };
    let data = ReportData {
        scenes: if scenes.is_empty() {
            vec![SceneData::new(&scenario.scenario, experiment.world())]
        } else {
            scenes
        },
        maps,
        episodes,
        network_svg,
        strategy: strategy_data(dir, &config, &experiment)?,
        ..curves
    };
    page_of(&data)
}

/// The end every report page shares (its last line of text, the data and the
/// scripts), put where a template says `<!--VIVAE-REPORT-END-->`.
const REPORT_END: &str = include_str!("../assets/report_end.html");

/// A report page's template with the shared end in its place.
pub(crate) fn with_report_end(template: &str) -> String {
    template.replacen("<!--VIVAE-REPORT-END-->\n", REPORT_END, 1)
}

/// A self-contained report page: `template` (see [`with_report_end`]) with
/// the style, the script `js` and the page's `data` (JSON already safe inside
/// a script block) in their slots.
pub(crate) fn report_page(template: &str, js: &str, data: &str) -> String {
    with_report_end(template)
        .replacen("/*VIVAE-CSS*/", STYLE_CSS, 1)
        .replacen("/*VIVAE-JS*/", js, 1)
        .replacen("/*VIVAE-DATA*/", data, 1)
}

/// Writes `report.html` into the run directory `dir`; returns its path.
pub fn write(dir: &Path) -> vivae_lab::Result<PathBuf> {
    write_reusing(dir, &Reuse::default())
}

/// [`write()`], reusing what the end of a run computed already.
pub fn write_reusing(dir: &Path, reuse: &Reuse<'_>) -> vivae_lab::Result<PathBuf> {
    let html = build_reusing(dir, reuse)?;
    let path = dir.join(files::REPORT);
    write_atomic(&path, html.as_bytes())?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_blocks_cannot_be_closed_by_data() {
        let s = script_safe(r#"{"a":"</script><script>alert(1)</script>"}"#);
        assert!(!s.contains("</script"));
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v["a"], "</script><script>alert(1)</script>");
    }

    #[test]
    fn scripts_never_close_their_block_and_load_nothing() {
        for js in [SCENE_JS, PLOTS_JS, FILM_JS, REPORT_JS] {
            assert!(!js.to_ascii_lowercase().contains("</script"));
        }
        for text in [
            REPORT_END, TEMPLATE, STYLE_CSS, SCENE_JS, PLOTS_JS, FILM_JS, REPORT_JS,
        ] {
            // The SVG namespace is a name, not a request.
            let stripped = text.replace("http://www.w3.org/2000/svg", "");
            assert!(!stripped.contains("http://") && !stripped.contains("https://"));
            assert!(!stripped.contains("@import") && !stripped.contains("url("));
        }
    }

    #[test]
    fn the_pages_curves_have_the_convergence_figures_colours() {
        let data = r##"{"curve_colours":["#45347e","#e66101"]}"##;
        let colours = [convergence::best_colour(), convergence::MEAN_COLOUR].map(convergence::hex);
        assert_eq!(
            serde_json::json!({ "curve_colours": colours }).to_string(),
            data
        );
        assert!(REPORT_JS.contains("data.curve_colours[0]"));
        assert!(REPORT_JS.contains("data.curve_colours[1]"));
    }

    #[test]
    fn template_has_every_slot_once() {
        let template = with_report_end(TEMPLATE);
        for slot in ["/*VIVAE-DATA*/", "/*VIVAE-CSS*/", "/*VIVAE-JS*/"] {
            assert_eq!(template.matches(slot).count(), 1, "{slot}");
        }
    }
}

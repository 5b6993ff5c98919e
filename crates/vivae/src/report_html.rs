//! `report.html`: one self-contained, offline page describing a finished run.
//!
//! Everything is read from the run directory (config, scenario, CSV files,
//! champion, per-generation best genomes), so `vivae report RUN_DIR` rebuilds
//! exactly what the end of a run writes. Data goes into the page as one JSON
//! block; the scripts that draw it are the viewer's own (`assets/`), inlined.

use std::path::{Path, PathBuf};

use serde::Serialize;
use vivae_sim::draw::{self, DrawOptions};
use vivae_sim::{Scenario, World};

use crate::figures::convergence::{self, ConvergenceOptions};
use crate::figures::network::NetworkOptions;
use vivae_lab::io::{read_text, write_atomic};
use vivae_lab::rundir::GenerationRow;
use vivae_lab::rundir::{self, files, pictures};
use vivae_lab::search::StrategyReport;
use vivae_lab::tasks::plain::REPLAY_SEED;
use vivae_lab::tasks::read_champion;
use vivae_lab::tasks::read_config;
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
pub(crate) struct EpisodeData {
    /// What it is (whose, on which map).
    pub label: String,
    /// Index of its map in [`ReportData::scenes`].
    pub scene: usize,
    /// Its fitness.
    pub fitness: f64,
    /// Its fraction of robot-steps on road.
    pub on_road: f64,
    /// Per robot, `[x0, y0, x1, y1, …]` rounded to 0.01 px.
    pub paths: Vec<Vec<f64>>,
}

/// Everything the report page shows; a task with a world (its program-side
/// tools) fills in the scenes, episodes, network and strategy.
#[derive(Debug, Serialize)]
pub(crate) struct ReportData {
    title: String,
    config: String,
    /// The maps episodes run on: the run's scenario, or each training map.
    pub scenes: Vec<SceneData>,
    /// On several training maps, each map's name (else empty); the champion's
    /// episode on map `k` is `episodes[k]`.
    pub maps: Vec<String>,
    /// The episodes animated.
    pub episodes: Vec<EpisodeData>,
    generations: Vec<GenerationRow>,
    /// Per generation, `[species id, members]`.
    species: Vec<Vec<(u32, usize)>>,
    convergence_svg: String,
    /// The champion's network figure.
    pub network_svg: String,
    /// Colours of the best and mean curves, as `convergence.png` draws them.
    curve_colours: [String; 2],
    /// What a strategy beyond NEAT adds (none for NEAT).
    pub strategy: Option<StrategyData>,
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
    film: Reel,
}

/// A film as the page plays it: drawn by the task, or pictures a host rendered.
#[derive(Debug, Serialize)]
#[serde(untagged)]
enum Reel {
    /// Shapes a task draws from its replay ([`Film`]).
    Drawn(Film),
    /// Frames a host rendered into the run directory ([`pictures::FILE`]).
    Rendered(pictures::Reel),
}

/// What a strategy other than NEAT adds to the report: its part
/// (from its own file in `vivae_lab::search`) and its columns of `generations.csv`.
#[derive(Debug, Serialize)]
pub(crate) struct StrategyData {
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
pub(crate) fn round2(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

/// The strategy's part of the report of the run in `dir` (none for NEAT):
/// what its own file reads of the run directory, the objectives named as
/// the figures name them, and its columns of `generations.csv`; `space` is
/// the task's behaviour descriptors'.
pub(crate) fn strategy_data(
    dir: &Path,
    config: &vivae_lab::config::Config,
    space: &vivae_lab::search::BehaviourSpace,
) -> vivae_lab::Result<Option<StrategyData>> {
    let entry = vivae_lab::search::entry_of(config)?;
    let Some(mut report) = (entry.report)(dir, config, space)? else {
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

/// Builds the report of the run in `dir` as one HTML document: its curves
/// alone, headed by its task (a task whose program-side tools draw more has
/// its own report, `crate::tasks`).
pub fn build(dir: &Path) -> vivae_lab::Result<String> {
    let config = read_config(&dir.join(files::CONFIG))?;
    build_curves(dir, &config)
}

/// The champion's network figure options as the report and the end of a run draw it.
pub(crate) fn network_options(generation: u32, fitness: f64, amplitude: f64) -> NetworkOptions {
    NetworkOptions {
        title: format!("Champion controller (generation {generation}, fitness {fitness:.3})"),
        weight_scale: amplitude,
        ..NetworkOptions::default()
    }
}

/// What every run's report shows, read from the files every run writes: its
/// config, curves, species, convergence and table (no scenes, episodes,
/// network or strategy); and the best genome of each generation.
pub(crate) fn curves_data(
    dir: &Path,
) -> vivae_lab::Result<(ReportData, Vec<rundir::GenerationBest>)> {
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
    // built by the program: the pictures its host rendered stand in, when
    // there are some; its curves show anyway.
    if vivae_lab::tasks::entry_of(config).is_ok_and(|t| t.host.is_some()) {
        return rendered_film(dir);
    }
    let champion = read_champion(&path)?;
    let maps = vivae_lab::tasks::maps::load_run(dir, config, None)?;
    let task = vivae_lab::tasks::build(config, &maps)?;
    task.check_genome(&champion.genome)
        .map_err(|reason| vivae_lab::Error::Genome { path, reason })?;
    let Some(film) = task.film(&champion.genome) else {
        return rendered_film(dir);
    };
    Ok(Some(FilmData {
        label: format!(
            "Champion (generation {}, fitness {:.3}) on the episodes of seed {REPLAY_SEED} (training used others)",
            champion.generation, champion.fitness
        ),
        film: Reel::Drawn(film),
    }))
}

/// The pictures of the champion's episode its host rendered into the run
/// directory, as a film; none when it rendered none.
fn rendered_film(dir: &Path) -> vivae_lab::Result<Option<FilmData>> {
    Ok(pictures::read(dir)?.map(|p| FilmData {
        label: format!(
            "Champion (generation {}, fitness {:.3}) in {}, episode seed {} (a validation episode: training used others), \
             return {:.3} in {} steps, a frame every {}",
            p.generation,
            p.fitness,
            p.env,
            p.seed,
            p.total,
            p.steps,
            if p.every == 1 { "step".to_string() } else { format!("{} steps", p.every) },
        ),
        film: Reel::Rendered(p.reel()),
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
pub(crate) fn page_of(data: &ReportData) -> vivae_lab::Result<String> {
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

/// Writes `report.html` of [`build`] into the run directory `dir`; returns its path.
pub fn write(dir: &Path) -> vivae_lab::Result<PathBuf> {
    write_page(dir, &build(dir)?)
}

/// Writes the page `html` as `report.html` into the run directory `dir`; returns its path.
pub(crate) fn write_page(dir: &Path, html: &str) -> vivae_lab::Result<PathBuf> {
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

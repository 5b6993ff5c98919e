//! The report of a predator–prey run (two co-evolved populations): the CIAO
//! figure (`figures/ciao.svg`, `.png`), both sides' curves
//! (`figures/coevolution.svg`, `.png`) and `report.html`, which shows them with the master
//! tournament's champions and an animation of the two champions meeting.
//! Everything is read from the run directory, so `vivae report RUN` rebuilds
//! what the end of a run writes.

use std::path::{Path, PathBuf};

use serde::Serialize;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::{read_text, write_atomic};
use vivae_lab::rundir::files as run_files;
use vivae_lab::tasks::predator_prey::coevo::{Champions, master_tournament};
use vivae_lab::tasks::predator_prey::run::{files, read_champions, read_ciao};
use vivae_lab::tasks::predator_prey::{Arena, Side};
use vivae_lab::tasks::read_config;
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_neat::Genome;
use vivae_sim::World;

use super::figures::{self as coevo, HUNTER_COLOUR, PREY_COLOUR, SideRow};
use crate::figures::convergence::hex;
use crate::report_html::{SCENE_JS, SceneData, report_page};

/// The page template; `/*VIVAE-DATA*/`, `/*VIVAE-CSS*/`, `/*VIVAE-JS*/`,
/// `<!--CIAO-->` and `<!--CURVES-->` are filled in.
const TEMPLATE: &str = include_str!("../../../assets/report_coevo.html");
/// The page's own script (the champions' match, animated).
const REPORT_JS: &str = include_str!("../../../assets/report_coevo.js");
/// The CIAO figure's file name, without extension.
pub const CIAO_FIGURE: &str = "ciao";
/// The curves figure's file name, without extension.
pub const CURVES_FIGURE: &str = "coevolution";

/// Reads `hunters.csv` or `prey.csv`.
pub fn read_side(path: &Path) -> Result<Vec<SideRow>> {
    let text = read_text(path)?;
    let bad = |line: usize| Error::RunFile {
        path: path.to_path_buf(),
        reason: format!(
            "line {}: not a row of generation,best_fitness,mean_fitness,catch_rate,…",
            line + 1
        ),
    };
    (text.lines().enumerate().skip(1))
        .map(|(i, line)| {
            let f: Vec<&str> = line.split(',').collect();
            let num = |k: usize| -> Result<f64> {
                f.get(k).and_then(|v| v.parse().ok()).ok_or_else(|| bad(i))
            };
            Ok(SideRow {
                generation: f
                    .first()
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| bad(i))?,
                best: num(1)?,
                mean: num(2)?,
                catch_rate: num(3)?,
            })
        })
        .collect()
}

/// The champions' match, as the page animates it.
#[derive(Debug, Serialize)]
struct MatchData {
    scene: SceneData,
    /// The hunter's and the prey's robot index in the scene.
    hunter: usize,
    prey: usize,
    /// Per step, per robot (scene order), `[x, y, heading]` rounded.
    frames: Vec<Vec<[f64; 3]>>,
    caught: bool,
    steps: u32,
    max_steps: u32,
    colours: [String; 2],
}

/// Plays `hunter` against `prey` in the run's arena, recording every step.
fn champions_match(dir: &Path, hunter: &Genome, prey: &Genome) -> Result<MatchData> {
    let config = read_config(&dir.join(run_files::CONFIG))?;
    let loaded = load_scenario(Some(&dir.join(run_files::SCENARIO)))?;
    let arena = Arena::of_config(&loaded.scenario, &config)
        .map_err(|e| vivae_lab::io::bad_input(e.to_string()))?;
    let round = |v: f64| (v * 100.0).round() / 100.0;
    let snapshot = |w: &World| -> Vec<[f64; 3]> {
        (w.robots().iter())
            .map(|r| [round(r.pos.x), round(r.pos.y), round(r.heading)])
            .collect()
    };
    let mut frames = vec![snapshot(arena.world())];
    let (mut h, mut p) = (
        arena.brain(Side::Hunter, hunter),
        arena.brain(Side::Prey, prey),
    );
    let out = arena.play(
        |i, o| h.act(i, o),
        |i, o| p.act(i, o),
        |w| frames.push(snapshot(w)),
    );
    Ok(MatchData {
        scene: SceneData::new(&loaded.scenario, arena.world()),
        hunter: arena.robot(Side::Hunter),
        prey: arena.robot(Side::Prey),
        frames,
        caught: out.caught,
        steps: out.steps,
        max_steps: out.max_steps,
        colours: [hex(HUNTER_COLOUR), hex(PREY_COLOUR)],
    })
}

/// What `report.html` shows of a run.
#[derive(Debug, Serialize)]
struct PageData {
    title: String,
    config: String,
    generations: usize,
    /// The master tournament's champions, when the run has written them.
    champions: Option<ChampionsData>,
    /// The champions meeting.
    game: Option<MatchData>,
}

#[derive(Debug, Serialize)]
struct ChampionsData {
    hunter_generation: u32,
    hunter_master_fitness: f64,
    hunter_links: usize,
    hunter_hidden: usize,
    prey_generation: u32,
    prey_master_fitness: f64,
    prey_links: usize,
    prey_hidden: usize,
}

impl ChampionsData {
    fn new(c: &Champions) -> ChampionsData {
        let links = |g: &Genome| g.num_enabled_links();
        ChampionsData {
            hunter_generation: c.hunter.generation,
            hunter_master_fitness: c.hunter.master_fitness,
            hunter_links: links(&c.hunter.genome),
            hunter_hidden: c.hunter.genome.num_hidden(),
            prey_generation: c.prey.generation,
            prey_master_fitness: c.prey.master_fitness,
            prey_links: links(&c.prey.genome),
            prey_hidden: c.prey.genome.num_hidden(),
        }
    }
}

/// Writes the figures and `report.html` of the predator–prey run in `dir`; returns the page's path.
pub fn write(dir: &Path) -> Result<PathBuf> {
    let hunters = read_side(&dir.join(files::HUNTERS))?;
    let prey = read_side(&dir.join(files::PREY))?;
    let cells = read_ciao(&dir.join(files::CIAO))?;
    let n = hunters.len().min(prey.len()) as u32;
    let cells: Vec<_> = cells
        .into_iter()
        .filter(|c| c.hunter < n && c.prey < n)
        .collect();
    let master = [Side::Hunter, Side::Prey].map(|s| master_tournament(&cells, n, s));
    let ciao = coevo::ciao(&cells, n)?;
    let curves = coevo::curves(&hunters, &prey, [&master[0], &master[1]])?;
    // In `figures/`, where every task's run keeps its figures.
    let figures = dir.join(run_files::FIGURES);
    vivae_lab::io::create_dirs(&figures)?;
    for (name, figure) in [(CIAO_FIGURE, &ciao), (CURVES_FIGURE, &curves)] {
        write_atomic(&figures.join(format!("{name}.svg")), figure.svg.as_bytes())?;
        write_atomic(&figures.join(format!("{name}.png")), &figure.png)?;
    }
    // champions.json is written when a run stops; a running one has none yet.
    let champions = dir
        .join(files::CHAMPIONS)
        .is_file()
        .then(|| read_champions(dir))
        .transpose()?;
    let game = (champions.as_ref())
        .map(|c| champions_match(dir, &c.hunter.genome, &c.prey.genome))
        .transpose()?;
    let data = PageData {
        title: dir
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        config: read_text(&dir.join(run_files::CONFIG))?,
        generations: n as usize,
        champions: champions.as_ref().map(ChampionsData::new),
        game,
    };
    let json = serde_json::to_string(&data).map_err(|e| Error::Serialize {
        what: "report data",
        reason: e.to_string(),
    })?;
    let template = TEMPLATE
        .replacen("<!--CIAO-->", &strip_xml_header(&ciao.svg), 1)
        .replacen("<!--CURVES-->", &strip_xml_header(&curves.svg), 1);
    let html = report_page(
        &template,
        &format!("{SCENE_JS}\n{REPORT_JS}"),
        &json.replace("</", "<\\/"),
    );
    let path = dir.join(run_files::REPORT);
    write_atomic(&path, html.as_bytes())?;
    Ok(path)
}

/// An SVG document without its XML declaration, to go inline into HTML.
fn strip_xml_header(svg: &str) -> String {
    match svg.strip_prefix("<?xml") {
        Some(rest) => rest
            .split_once("?>")
            .map_or(svg, |(_, r)| r)
            .trim_start()
            .to_string(),
        None => svg.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report_html::with_report_end;

    #[test]
    fn template_has_every_slot_once_and_scripts_load_nothing() {
        let template = with_report_end(TEMPLATE);
        for slot in [
            "/*VIVAE-DATA*/",
            "/*VIVAE-CSS*/",
            "/*VIVAE-JS*/",
            "<!--CIAO-->",
            "<!--CURVES-->",
        ] {
            assert_eq!(template.matches(slot).count(), 1, "{slot}");
        }
        for text in [template.as_str(), REPORT_JS] {
            let stripped = text.replace("http://www.w3.org/2000/svg", "");
            assert!(!stripped.contains("http://") && !stripped.contains("https://"));
            assert!(!text.to_ascii_lowercase().contains("</script") || text == template);
        }
    }

    #[test]
    fn the_xml_declaration_goes_and_the_svg_stays() {
        assert_eq!(
            strip_xml_header("<?xml version=\"1.0\"?>\n<svg/>"),
            "<svg/>"
        );
        assert_eq!(strip_xml_header("<svg/>"), "<svg/>");
    }
}

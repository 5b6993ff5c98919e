//! The driving run's `report.html`: beside every run's curves, its
//! scenario (or each training map), the champion's and the figure
//! generations' bests' episodes animated, the champion's network and the
//! strategy's part.

use std::path::{Path, PathBuf};

use vivae_neat::Genome;

use super::substrate;
use crate::figures::network;
use crate::report_html::{
    EpisodeData, SceneData, curves_data, network_options, page_of, round2, strategy_data,
    write_page,
};
use vivae_lab::io::bad_input;
use vivae_lab::rundir::{self, files};
use vivae_lab::tasks::driving::episode::{Episode, EpisodeRecord};
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_lab::tasks::{read_champion, read_config};

/// Writes the driving run's `report.html` into its directory `dir`; returns its path.
pub fn write(dir: &Path) -> vivae_lab::Result<PathBuf> {
    write_reusing(dir, &Reuse::default())
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

/// The report of the driving run in `dir` as one HTML document, reusing
/// what the end of a run computed already.
pub fn build_reusing(dir: &Path, reuse: &Reuse<'_>) -> vivae_lab::Result<String> {
    let config = read_config(&dir.join(files::CONFIG))?;
    let scenario = load_scenario(Some(&dir.join(files::SCENARIO)))?;
    let experiment = Episode::new(&config, &scenario.scenario)
        .map_err(|e| bad_input(format!("{}: {e}", dir.display())))?;
    let champion = read_champion(&dir.join(files::CHAMPION))?;
    let (mut data, best) = curves_data(dir)?;
    let (episodes, scenes, maps) =
        all_episodes(dir, &config, &experiment, &champion, &best, reuse)?;
    let network_svg = match &reuse.network_svg {
        Some(svg) => svg.clone(),
        None => network::figure_svg_robot(
            substrate(&experiment),
            &experiment.robot_controller(&champion.genome)?,
            &network_options(
                champion.generation,
                champion.fitness,
                config.hyperneat.amplitude,
            ),
        )
        .map_err(vivae_lab::Error::from)?,
    };
    data.scenes = if scenes.is_empty() {
        vec![SceneData::new(&scenario.scenario, experiment.world())]
    } else {
        scenes
    };
    (data.maps, data.episodes, data.network_svg) = (maps, episodes, network_svg);
    let space = vivae_lab::tasks::driving::descriptors::space(&config, experiment.robots());
    data.strategy = strategy_data(dir, &config, &space)?;
    page_of(&data)
}

/// Writes the driving run's `report.html` into its directory `dir`,
/// reusing what the end of a run computed already; returns its path.
pub fn write_reusing(dir: &Path, reuse: &Reuse<'_>) -> vivae_lab::Result<PathBuf> {
    write_page(dir, &build_reusing(dir, reuse)?)
}

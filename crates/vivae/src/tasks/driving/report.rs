//! The figures of a driving run at its end (`figures/`: each figure
//! generation's best and the champion driving, on every training map, and
//! the champion's network), then its `report.html`, reusing the episodes.

use std::path::Path;

use vivae_neat::Genome;
use vivae_sim::draw::{self, DrawOptions};

use super::substrate;
use crate::figures;
use crate::report::{RunSummary, champion_map_figure, population_figures, write_figure};
use vivae_lab::error::{Error, Result};
use vivae_lab::io::bad_input;
use vivae_lab::run::Run;
use vivae_lab::rundir::{Champion, files};
use vivae_lab::tasks::driving::episode::{Episode, EpisodeRecord};
use vivae_lab::tasks::driving::training_of;

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
pub fn finish(run: &Run) -> Result<RunSummary> {
    let dir = run.dir().join(files::FIGURES);
    vivae_lab::io::create_dirs(&dir)?;
    vivae_lab::rundir::unmark_drawn(run.dir())?;
    let experiment = (training_of(run.task()).map(|t| t.primary())).ok_or_else(|| {
        let task = &run.config().experiment.task;
        bad_input(format!(
            "{} run has no trajectory figures",
            vivae_lab::error::a(task.name())
        ))
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
    let mut reuse = super::report_html::Reuse {
        episodes: episodes.iter().map(|(g, e)| (*g, e)).collect(),
        network_svg: Some(network_svg),
        map_episodes: map_episodes.iter().map(|(_, e)| e).collect(),
    };
    reuse.episodes.push((&champion.genome, &episode));
    super::report_html::write_reusing(run.dir(), &reuse)?;
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
    let network = figures::network::render_robot(substrate(experiment), &controller, &options)?;
    write_figure(dir, "network", &network.svg, &network.png)?;
    Ok(network.svg)
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

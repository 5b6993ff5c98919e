//! What every run's figures share: the end of a run's summary, the
//! convergence figure and the strategy's own; and scenario summaries. A
//! task's own figures (a driving run's trajectories, its replay) are its
//! program-side tools' (`crate::tasks`).

use std::fmt::Write as _;
use std::path::Path;

use vivae_sim::draw::{self, DrawOptions};
use vivae_sim::{Scenario, ScenarioSummary, SurfaceSensors, World};

use crate::figures;
use crate::figures::convergence::ConvergenceOptions;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::{bad_input, write_atomic};
use vivae_lab::run::Run;
use vivae_lab::rundir::{self, files};

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
pub(crate) fn write_figure(dir: &Path, name: &str, svg: &str, png: &[u8]) -> Result<()> {
    write_atomic(&dir.join(format!("{name}.svg")), svg.as_bytes())?;
    write_atomic(&dir.join(format!("{name}.png")), png)
}

/// The run's convergence figure and its strategy's own figure, if any.
pub(crate) fn population_figures(run: &Run, dir: &Path) -> Result<()> {
    let fitness = rundir::read_population_csv(&run.dir().join(files::POPULATION))?;
    let convergence = figures::convergence::render(&fitness, &ConvergenceOptions::default())?;
    write_figure(dir, "convergence", &convergence.svg, &convergence.png)?;
    strategy_figure(run, dir)
}

/// The strategy's own end-of-run figure, if it has one: a grid archive as
/// a heat map (`archive.png`/`.svg`), a two-objective Pareto front
/// (`front.png`/`.svg`).
fn strategy_figure(run: &Run, dir: &Path) -> Result<()> {
    use vivae_lab::search::StrategyFigure as F;
    let strategy = run.search().strategy();
    let space = run.task().behaviour_space(run.config());
    match strategy.figure(run.config(), &space, run.done()) {
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

/// The name (no extension) of the champion's figure on training map `label`.
pub fn champion_map_figure(label: &str) -> String {
    format!(
        "trajectories-champion-{}",
        vivae_lab::io::safe_file_stem(label)
    )
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
}

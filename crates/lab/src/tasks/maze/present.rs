//! A maze run for a person: its header, its closing summary and a replay's
//! line. A maze run draws no figures (docs/howto/maze.md, "The maze from the
//! command line"): the summary says whether and when it was solved.

use vivae_neat::Genome;

use crate::config::Config;
use crate::tasks::maze::MazeModel;
use crate::tasks::maze::config::{MazeConfig, MazeRobot};
use crate::tasks::{Finished, HeaderContext};

/// The header of a maze run.
pub(super) fn header(config: &Config, ctx: &HeaderContext<'_>) -> String {
    let c = config;
    format!(
        "vivae {}: the maze {}\n\
         \x20 a plain NEAT network (11 inputs, 2 outputs) driving {}, {} steps per evaluation, population {}, \
         at most {} generations{}, seed {}{}\n\
         \x20 output: {}\n\
         \x20 fitness = 300 - the end distance to the goal in px; the run stops when a genome reaches the goal",
        ctx.command,
        ctx.scenario,
        robot(config),
        c.experiment.steps,
        c.neat.population_size,
        c.experiment.generations,
        ctx.start,
        c.experiment.seed,
        ctx.strategy,
        ctx.output,
    )
}

/// The robot of a maze run, for its header.
fn robot(config: &Config) -> String {
    let m = &MazeConfig::of(config);
    match m.robot {
        MazeRobot::Vivae => "our robot of [physics] (maze.robot = vivae)".into(),
        MazeRobot::Lehman => format!(
            "Lehman's robot ({}, {} walls, collision {})",
            if m.quirks {
                "his code's inputs"
            } else {
                "the paper's inputs"
            },
            m.walls,
            m.collision
        ),
    }
}

/// The closing lines and the summary line of a finished maze run.
pub(super) fn summary(task: &impl MazeModel, f: &Finished<'_>) -> (String, String) {
    let (progress, dir, wall, rate) = (f.progress, f.dir, f.wall, f.rate);
    let end = task.outcome(f.champion);
    let verdict = match (progress.solved_at, progress.solved_generation) {
        (Some(n), Some(g)) => format!("solved after {n} evaluations (generation {g})"),
        _ => format!("not solved in {} evaluations", progress.evaluations),
    };
    let person = format!(
        "done: {} generations in {wall:.1} s; {verdict}\n\
         champion: fitness {:.3} (generation {}), ends {:.1} px from the goal\n\
         run directory: {dir}/ (config.toml, champion.json, generations.csv, checkpoints/)\n\
         its end position: vivae replay {dir}",
        f.generations, f.fitness, f.generation, end.distance,
    );
    let line = format!(
        "evolve: generations={} best={} champion_generation={}{} best_distance={:.3} evaluations={}{} evaluations_reused={} wall_s={wall:.1} robot_steps_per_s={rate:.0} out={dir}",
        f.generations,
        f.fitness,
        f.generation,
        progress.summary_fields(),
        end.distance,
        progress.evaluations,
        f.strategy_fields,
        f.reused,
    );
    (person, line)
}

/// A replay of `genome` in `task`: the episode's end, and a note.
pub(super) fn replay(task: &impl MazeModel, genome: &Genome) -> (String, String) {
    let end = task.outcome(genome);
    let line = format!(
        "fitness={} solved={} distance={:.3} steps={} end_x={:.3} end_y={:.3}",
        end.fitness(),
        if end.solved { "yes" } else { "no" },
        end.distance,
        end.steps,
        end.end.x,
        end.end.y
    );
    let note = format!(
        "maze {}: a maze replay prints the episode's end and draws no figure",
        task.source()
    );
    (line, note)
}

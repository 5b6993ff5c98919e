//! What the evolving commands say to a person at the terminal: the header
//! before a run, the progress bar or lines during it, the closing summary
//! after it, and warnings about the run's maps.

use crate::report::{self, RunSummary};
use vivae_lab::config::Config;
use vivae_lab::run::Run;
use vivae_lab::rundir::{GenerationRecord, files};
use vivae_lab::tasks::HeaderContext;
use vivae_lab::tasks::maps::TrainingMap;

/// Warns (even with `-q`: the run's result is at stake) about a training
/// map given more than once, which trains twice and counts double.
pub fn warn_repeated_maps(maps: &[TrainingMap]) {
    for w in vivae_lab::tasks::maps::repeat_warnings(maps) {
        eprintln!("warning: {w}");
    }
}

/// What a run is about to do, for a person reading the terminal, under the
/// name of the `command` that runs it; `threads` is the evaluation pool's
/// size as asked for (0 = one per core).
pub fn header(run: &Run, command: &str, scenario: &str, threads: usize) -> String {
    let c = run.config();
    let threads = match threads {
        0 => format!(
            "{} (one per core)",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        ),
        t => t.to_string(),
    };
    let ctx = HeaderContext {
        command,
        scenario,
        start: &resuming_note(run),
        threads: &threads,
        strategy: &strategy_line(c),
        output: &run.dir().display().to_string(),
    };
    run.task().header(c, &ctx)
}

/// The header's note that a run goes on from a checkpoint (none for a new run).
fn resuming_note(run: &Run) -> String {
    match run.done() {
        0 => String::new(),
        d => format!(" (resuming after generation {d})"),
    }
}

/// The header's line on the search strategy (none for NEAT, the paper's).
fn strategy_line(c: &Config) -> String {
    // A run's config was checked, so its strategy is registered.
    vivae_lab::search::entry_of(c).map_or_else(|_| String::new(), |e| (e.header_line)(c))
}

/// The progress bar of a run of `total` generations, `done` of them already.
pub fn progress_bar(total: u32, done: u32) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(u64::from(total));
    bar.set_style(
        indicatif::ProgressStyle::with_template("gen {pos}/{len} [{bar:30}] {msg} ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_position(u64::from(done));
    bar
}

/// Shows a finished generation: on the progress bar if there is one, else as a
/// line (none with `quiet`).
pub fn show_generation(r: &GenerationRecord, bar: Option<&indicatif::ProgressBar>, quiet: bool) {
    match bar {
        Some(b) => {
            let row = &r.row;
            b.set_position(u64::from(row.generation));
            b.set_message(format!(
                "best {:.4} mean {:.4} species {}",
                row.best, row.mean, row.species
            ));
        }
        None if !quiet => eprintln!(
            "gen {}/{} best {:.4} mean {:.4} species {} best-ever {:.4}",
            r.row.generation, r.total, r.row.best, r.row.mean, r.row.species, r.best_ever
        ),
        None => {}
    }
}

/// The line that says where an interrupted run stopped and how to go on.
pub fn interrupted_line(run: &Run) -> String {
    format!(
        "interrupted after generation {}; checkpoint written. Resume with: vivae resume {}",
        run.done(),
        run.dir().display()
    )
}

/// The closing summary: rounded figures and the run directory's main files;
/// `started_after` is the generation this invocation started after (0 for a new run).
pub fn closing(
    run: &Run,
    summary: &RunSummary,
    started_after: u32,
    wall: f64,
    steps_per_s: f64,
) -> String {
    let dir = run.dir().display();
    let plural = |n: u32| if n == 1 { "" } else { "s" };
    let (done, ran) = (run.done(), run.done() - started_after);
    let done = match started_after {
        0 => format!("{done} generation{}", plural(done)),
        s => format!(
            "{ran} generation{} (generations {}–{done}; {done} in all)",
            plural(ran),
            s + 1
        ),
    };
    let per_map = match per_map_field(summary) {
        None => String::new(),
        Some(p) => format!("\n  on each training map: {}", p.replace(',', ", ")),
    };
    format!(
        "done: {done} in {wall:.1} s ({:.2} M robot-steps/s)\n\
         champion: fitness {:.3} px/step (generation {}), {:.1}% of robot-steps on road{per_map}\n\
         run directory: {dir}/\n\
         \x20 report.html     every figure on one page: open {dir}/{}\n\
         \x20 config.toml     the resolved config: vivae evolve --config {dir}/config.toml repeats the run\n\
         \x20 champion.json   the best genome and its config: vivae replay {dir}/champion.json\n\
         \x20 generations.csv, population.csv, timing.csv, checkpoints/\n\
         \x20 figures/        {} (and .svg)\n\
         watch them drive: vivae view {dir}",
        steps_per_s / 1e6,
        summary.champion_fitness,
        summary.champion_generation,
        100.0 * summary.champion_on_road,
        files::REPORT,
        figure_names(run, summary).join(", "),
    )
}

/// The figures a finished run's `figures/` holds, as the closing summary lists them.
fn figure_names(run: &Run, summary: &RunSummary) -> Vec<String> {
    let mut figures: Vec<String> = run
        .figure_genomes()
        .map(|(g, _, _)| format!("trajectories-gen{g:03}.png"))
        .collect();
    figures.push("trajectories-champion.png".into());
    figures.extend(
        summary
            .per_map
            .iter()
            .map(|(label, _)| format!("{}.png", report::champion_map_figure(label))),
    );
    figures.extend(["convergence.png", "network.png"].map(String::from));
    for name in ["archive.png", "front.png"] {
        if run.dir().join(files::FIGURES).join(name).exists() {
            figures.push(name.into());
        }
    }
    figures
}

/// The champion's fitness on each training map, `roads:3.1,oval:2.8` (3
/// decimals), or none on one map.
pub fn per_map_field(summary: &RunSummary) -> Option<String> {
    (!summary.per_map.is_empty()).then(|| {
        summary
            .per_map
            .iter()
            .map(|(label, f)| format!("{label}:{f:.3}"))
            .collect::<Vec<_>>()
            .join(",")
    })
}

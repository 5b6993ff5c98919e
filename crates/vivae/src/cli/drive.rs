//! Running a prepared run to its end, for `evolve`, `resume` and `retrain`:
//! Ctrl-C handling, progress, the figures, and the closing summary (for a
//! person, on stderr) and summary line (for scripts, on stdout).

use std::io::IsTerminal;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::Context as _;
use vivae_lab::io::bad_input;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::GenerationRecord;
use vivae_lab::tasks::Finished;

use super::mpi_job::run_generations;
use super::terminal::{
    closing, header, interrupted_line, per_map_field, progress_bar, show_generation,
};

/// Runs evolution with progress output, then writes the figures; `command`
/// and `scenario` name the run in the header, `threads` as asked for.
pub fn drive(
    mut run: Run,
    command: &str,
    scenario: &str,
    threads: usize,
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
) -> anyhow::Result<ExitCode> {
    install_ctrlc(interrupted);
    if !quiet {
        eprintln!("{}", header(&run, command, scenario, threads));
    }
    let started_after = run.done();
    let start = Instant::now();
    let total = run.config().experiment.generations;
    let bar = (!quiet && std::io::stderr().is_terminal()).then(|| progress_bar(total, run.done()));
    let mut robot_steps = 0.0;
    let mut busy = 0.0;
    let mut reused = 0;
    let outcome = run_generations(&mut run, interrupted, |r: &GenerationRecord| {
        robot_steps += r.robot_steps_per_second * r.seconds;
        busy += r.seconds;
        reused += r.reused as u64;
        show_generation(r, bar.as_ref(), quiet);
    })?;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let rate = robot_steps / busy.max(1e-9);
    conclude(&run, outcome, started_after, start, (rate, reused), quiet)
}

/// Sets `flag` on Ctrl-C; a second Ctrl-C while the generation finishes aborts at once.
pub(crate) fn install_ctrlc(flag: &Arc<AtomicBool>) {
    let flag = flag.clone();
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!(
            "\ninterrupt: finishing the current generation, then writing a checkpoint (Ctrl-C again to abort)"
        );
    });
}

/// The end of [`drive`]: figures, the closing summary and the summary line
/// (a task without figures' by [`conclude_without_figures`]); `rate` is
/// robot-steps per second, `reused` the evaluations copied instead of run.
fn conclude(
    run: &Run,
    outcome: Outcome,
    started_after: u32,
    start: Instant,
    (rate, reused): (f64, u64),
    quiet: bool,
) -> anyhow::Result<ExitCode> {
    let Some(finish) = crate::tasks::finish_of(run) else {
        let wall = start.elapsed().as_secs_f64();
        return conclude_without_figures(run, outcome, wall, (rate, reused), quiet);
    };
    if outcome == Outcome::Interrupted {
        // The figures show the run so far; a resumed run redraws them at its end.
        if run.done() > 0 {
            finish(run).context("writing figures")?;
        }
        eprintln!("{}", interrupted_line(run));
        return Ok(ExitCode::from(130));
    }
    let summary = finish(run).context("writing figures")?;
    let wall = start.elapsed().as_secs_f64();
    if !quiet {
        eprintln!("{}", closing(run, &summary, started_after, wall, rate));
    }
    // The machine-readable summary, for scripts.
    let per_map = per_map_field(&summary).map_or_else(String::new, |p| format!(" per_map={p}"));
    println!(
        "evolve: generations={} best={} champion_generation={} on_road={:.4}{per_map}{} evaluations_reused={reused} wall_s={:.1} robot_steps_per_s={:.0} out={}",
        run.done(),
        summary.champion_fitness,
        summary.champion_generation,
        summary.champion_on_road,
        vivae_lab::search::files::summary_fields(run.search()),
        wall,
        rate,
        run.dir().display(),
    );
    Ok(ExitCode::SUCCESS)
}

/// [`conclude`] for a task that draws no figures at a run's end (no
/// `finish` in its program-side tools): its own summary says how it went.
fn conclude_without_figures(
    run: &Run,
    outcome: Outcome,
    wall: f64,
    (rate, reused): (f64, u64),
    quiet: bool,
) -> anyhow::Result<ExitCode> {
    let dir = run.dir().display().to_string();
    if outcome == Outcome::Interrupted {
        eprintln!("{}", interrupted_line(run));
        return Ok(ExitCode::from(130));
    }
    let champion = run.champion().ok_or(vivae_lab::Error::NoChampion)?;
    let finished = Finished {
        champion: &champion.genome,
        fitness: champion.fitness,
        generation: champion.generation,
        progress: run.target_progress().copied().unwrap_or_default(),
        generations: run.done(),
        wall,
        rate,
        reused,
        dir: &dir,
        strategy_fields: &vivae_lab::search::files::summary_fields(run.search()),
    };
    let (person, line) = (run.task().summary(&finished))
        .ok_or_else(|| bad_input("the run's task has no summary"))?;
    // A task whose champion is validated: validation.json, before the report shows it.
    vivae_lab::tasks::validation::write(
        run.dir(),
        run.task(),
        &champion.genome,
        champion.generation,
        champion.fitness,
    )
    .context("writing validation.json")?;
    // A task without figures of its own: report.html with its curves.
    let report = (run.task().report_curves())
        .then(|| crate::report_html::write(run.dir()))
        .transpose()
        .context("writing report.html")?;
    if !quiet {
        eprintln!("{person}");
        if let Some(path) = report {
            eprintln!("report: {}", path.display());
        }
    }
    println!("{line}");
    Ok(ExitCode::SUCCESS)
}

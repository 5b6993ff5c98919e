//! Efficacy sampling as SharpNEAT's EfficacySampler does it: runs of a fixed
//! wall-clock length, reporting the distribution of the best fitness reached
//! and of the evaluations done per run, and evaluations per second.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use vivae_neat::driver::{
    Evaluator, Evolution, GenerationReport, GroupTask, GroupedEvaluator, HookError, NoCheckpoints,
    Observer, ParallelEvaluator, StopCriteria, Task,
};
use vivae_neat::{GenomeSpec, NeatParams, Population, stats};

use crate::common::{apply_overrides, cli, fail};

/// Best fitness and evaluations of one run; raises `stop` once `seconds` have passed.
struct Clock<'a> {
    start: Instant,
    seconds: f64,
    stop: &'a AtomicBool,
    best: f64,
    evals: usize,
    /// Sums over evaluated genomes of their enabled links and hidden nodes.
    links: f64,
    hidden: f64,
}

impl Observer for Clock<'_> {
    fn on_generation(&mut self, report: &GenerationReport<'_>) -> Result<(), HookError> {
        let n = report.evaluations.len();
        self.evals += n;
        self.links += report.stats.mean_links * n as f64;
        self.hidden += report.stats.mean_hidden * n as f64;
        for e in report.evaluations {
            self.best = self.best.max(e.fitness);
        }
        if self.start.elapsed().as_secs_f64() >= self.seconds {
            self.stop.store(true, Ordering::SeqCst);
        }
        Ok(())
    }
}

/// `--seconds T` (default 60): a positive number of seconds per run.
fn seconds(name: &str, args: &cli::Args) -> f64 {
    match args.options.iter().rev().find(|(k, _)| k == "--seconds") {
        None => 60.0,
        Some((_, v)) => match v.parse::<f64>() {
            Ok(s) if s.is_finite() && s > 0.0 => s,
            _ => fail(
                name,
                &format!("--seconds needs a positive number, got `{v}`"),
            ),
        },
    }
}

/// The `--help` text of the efficacy example `name`, headed by `title`.
fn usage(name: &str, title: &str) -> String {
    format!(
        "{title}: fixed-length runs, one summary line.

Usage: cargo run --release -p vivae-neat --example {name} -- [OPTIONS]

Options:
  --seconds T           wall-clock length of each run (default 60)
  --runs N              runs, with seeds S, S+1, ... (default 5)
  --seed S              seed of the first run (default 1)
  --max-generations G   also stop a run after G generations
  --set FIELD=JSON      override one NeatParams field (repeatable)
  --one-at-a-time       score each network alone, not side by side with others
                        as vector lanes (the sinewave; the same bits, slower)
  -h, --help            print this help

Prints `{name}: runs=N best_fitness(min/median/max)=... evals_per_run(median)=...
evals_per_s=...` on stdout (one thread) and one line per run on stderr.
"
    )
}

/// Runs `--runs N` (default 5) runs of `--seconds T` (default 60) each on one
/// thread, seeds S, S+1, ..., stopping early at `target`; prints one line per
/// run on stderr and returns the summary line (`None` after `--help`).
pub fn sample<T: Task + Clone>(
    name: &str,
    title: &str,
    params: NeatParams,
    spec: &GenomeSpec,
    target: f64,
    task: T,
) -> Option<String> {
    let (args, pool) = start(name, title)?;
    let make = || ParallelEvaluator::with_pool(task.clone(), &pool);
    Some(runs(name, &args, params, spec, target, make))
}

/// [`sample`] for a task that scores genomes a group at a time (their
/// networks side by side as vector lanes): the same runs, the same bits.
#[allow(dead_code)]
pub fn sample_grouped<T: GroupTask + Clone>(
    name: &str,
    title: &str,
    params: NeatParams,
    spec: &GenomeSpec,
    target: f64,
    task: T,
) -> Option<String> {
    let (args, pool) = start(name, title)?;
    let make = || GroupedEvaluator::with_pool(task.clone(), &pool);
    Some(runs(name, &args, params, spec, target, make))
}

/// The command line and a one-thread pool (`None` after `--help`).
fn start(name: &str, title: &str) -> Option<(cli::Args, rayon::ThreadPool)> {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = match cli::parse(&argv, &["--one-at-a-time"], &["--seconds"]) {
        Ok(cli::Parsed::Run(a)) => a,
        Ok(cli::Parsed::Help) => {
            print!("{}", usage(name, title));
            return None;
        }
        Err(e) => fail(name, &e),
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build();
    let pool = pool.unwrap_or_else(|e| fail(name, &format!("thread pool: {e}")));
    Some((args, pool))
}

/// The runs of [`sample`], each evaluating on a fresh `evaluator()`.
fn runs<E: Evaluator>(
    name: &str,
    args: &cli::Args,
    params: NeatParams,
    spec: &GenomeSpec,
    target: f64,
    evaluator: impl Fn() -> E,
) -> String {
    let seconds = seconds(name, args);
    let params = apply_overrides(params, &args.sets).unwrap_or_else(|e| fail(name, &e));
    let (runs, seed) = (args.runs.unwrap_or(5), args.seed.unwrap_or(1));
    let (mut bests, mut evals, mut secs) = (Vec::new(), Vec::new(), 0.0);
    for r in 0..runs as u64 {
        let pop = Population::new(params.clone(), spec.clone(), seed + r)
            .unwrap_or_else(|e| fail(name, &e.to_string()));
        let stop = AtomicBool::new(false);
        let criteria = StopCriteria {
            generations: args.max_generations,
            target_fitness: Some(target),
            ..StopCriteria::default()
        }
        .or_interrupt(&stop);
        let mut clock = Clock {
            start: Instant::now(),
            seconds,
            stop: &stop,
            best: 0.0,
            evals: 0,
            links: 0.0,
            hidden: 0.0,
        };
        let mut evolution = Evolution::new(pop, evaluator());
        let reason = evolution.run(&criteria, &mut clock, &mut NoCheckpoints);
        let reason = reason.unwrap_or_else(|e| fail(name, &e.to_string()));
        let s = clock.start.elapsed().as_secs_f64();
        eprintln!(
            "{name} seed={} best={} evals={} s={s:.1} stop={reason:?} mean_links={:.1} mean_hidden={:.1}",
            seed + r,
            clock.best,
            clock.evals,
            clock.links / clock.evals.max(1) as f64,
            clock.hidden / clock.evals.max(1) as f64,
        );
        bests.push(clock.best);
        evals.push(clock.evals as f64);
        secs += s;
    }
    let min = bests.iter().copied().fold(f64::INFINITY, f64::min);
    let max = bests.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let median = stats::median(&bests).unwrap_or(0.0);
    format!(
        "{name}: runs={runs} best_fitness(min/median/max)={min:.2}/{median:.2}/{max:.2} evals_per_run(median)={:.0} evals_per_s={:.0}",
        stats::median(&evals).unwrap_or(0.0),
        evals.iter().sum::<f64>() / secs.max(1e-9)
    )
}

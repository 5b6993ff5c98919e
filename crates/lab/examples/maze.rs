//! The maze benchmark of Lehman & Stanley 2011: novelty search, fitness-based
//! NEAT and MAP-Elites on the medium or hard maze, many seeded runs, one
//! summary line.
//!
//! `cargo run --release -p vivae-lab --example maze -- --maze hard --strategy novelty --runs 20`

#[path = "../../neat/examples/common/cli.rs"]
mod cli;

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use vivae_lab::tasks::maze::{Maze, MazeTask};
use vivae_neat::driver::{
    Evolution, GenerationReport, HookError, NoCheckpoints, Observer, ParallelEvaluator,
    StopCriteria, Strategy,
};
use vivae_neat::strategies::{Cells, MapElitesParams, NoveltyParams};
use vivae_neat::{MapElites, NeatParams, NoveltySearch, Population, stats};

const USAGE: &str = "\
The maze benchmark (Lehman & Stanley 2011): many seeded runs, one summary line.

Usage: cargo run --release -p vivae-lab --example maze -- [OPTIONS]

Options:
  --maze medium|hard        the maze (default hard)
  --strategy fitness|novelty|map-elites
                            fitness-based NEAT, novelty search or MAP-Elites (default novelty)
  --runs N                  runs, with seeds S, S+1, ... (default 20)
  --seed S                  seed of the first run (default 1)
  --evals MAX               evaluations before a run counts as unsolved (default 250000)
  --set FIELD=JSON          override one NeatParams field (repeatable)
  -h, --help                print this help

Population (or MAP-Elites batch) 250; a run stops at the first genome that
reaches the goal. Prints `maze-hard-novelty: solved=S/N mean_evals=...
median_evals=... mean_ms=...` on stdout (evaluations counted up to and
including the first solver) and one line per run on stderr.
";

/// Individuals per generation (the paper's population).
const POPULATION: usize = 250;
/// Novelty search's initial archive threshold ρ_min in px (Lehman's maze code, via goNEAT_NS).
const NOVELTY_THRESHOLD: f64 = 6.0;
/// MAP-Elites cell side, px.
const CELL: f64 = 10.0;

/// Counts evaluations and raises `solved` at the first solver.
struct Counter<'a> {
    evals: usize,
    solved_at: Option<usize>,
    flag: &'a AtomicBool,
}

impl<S: Strategy> Observer<S> for Counter<'_> {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        let first = report.evaluations.iter().position(|e| e.metrics[0] == 1.0);
        if let (None, Some(i)) = (self.solved_at, first) {
            self.solved_at = Some(self.evals + i + 1);
            self.flag.store(true, Ordering::SeqCst);
        }
        self.evals += report.evaluations.len();
        Ok(())
    }
}

/// Runs `strategy` on `task` until solved or `max_evals`: evaluations to solve.
fn solve<S: Strategy>(strategy: S, task: MazeTask, max_evals: usize) -> Option<usize> {
    let flag = AtomicBool::new(false);
    let generations = max_evals.div_ceil(POPULATION) as u32;
    let stop = StopCriteria {
        interrupt: Some(&flag),
        ..StopCriteria::generations(generations)
    };
    let mut counter = Counter {
        evals: 0,
        solved_at: None,
        flag: &flag,
    };
    let mut evolution = Evolution::new(strategy, ParallelEvaluator::new(task));
    evolution
        .run(&stop, &mut counter, &mut NoCheckpoints)
        .unwrap_or_else(|e| fail(&format!("run failed: {e}")));
    counter.solved_at.filter(|&e| e <= max_evals)
}

/// One run of `strategy` with `seed`.
fn run(
    strategy: &str,
    maze: Maze,
    params: &NeatParams,
    seed: u64,
    max_evals: usize,
) -> Option<usize> {
    let task = MazeTask::shipped(maze).unwrap_or_else(|e| fail(&e.to_string()));
    let pop = || {
        Population::new(params.clone(), MazeTask::spec(), seed)
            .unwrap_or_else(|e| fail(&e.to_string()))
    };
    match strategy {
        "fitness" => solve(pop(), task, max_evals),
        "novelty" => {
            let novelty = NoveltyParams {
                threshold: NOVELTY_THRESHOLD,
                ..NoveltyParams::default()
            };
            let ns = NoveltySearch::new(pop(), novelty).unwrap_or_else(|e| fail(&e.to_string()));
            solve(ns, task, max_evals)
        }
        _ => {
            let sc = task.world().scenario();
            let (w, h) = (sc.width(), sc.height());
            let bins = vec![(w / CELL).ceil() as usize, (h / CELL).ceil() as usize];
            let cells = Cells::grid(vec![0.0, 0.0], vec![w, h], bins)
                .unwrap_or_else(|e| fail(&e.to_string()));
            let map = MapElitesParams {
                batch_size: POPULATION,
                ..MapElitesParams::default()
            };
            let me = MapElites::new(params.clone(), MazeTask::spec(), map, cells, seed)
                .unwrap_or_else(|e| fail(&e.to_string()));
            solve(me, task, max_evals)
        }
    }
}

/// Prints `maze: MESSAGE` on stderr and exits with code 2 (bad input).
fn fail(message: &str) -> ! {
    eprintln!("maze: {message}");
    std::process::exit(2)
}

/// The value of option `name`, if given (the last one wins).
fn option<'a>(args: &'a cli::Args, name: &str) -> Option<&'a str> {
    let found = args.options.iter().rev().find(|(k, _)| k == name);
    found.map(|(_, v)| v.as_str())
}

fn neat_params(sets: &[String]) -> NeatParams {
    let mut params = NeatParams {
        population_size: POPULATION,
        ..NeatParams::plain_neat()
    };
    for kv in sets {
        let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
        let mut json = serde_json::to_value(&params).unwrap_or_else(|e| fail(&e.to_string()));
        if json.get(k).is_none() {
            fail(&format!("--set {kv}: unknown parameter `{k}`"));
        }
        json[k] = serde_json::from_str(v)
            .unwrap_or_else(|e| fail(&format!("--set {kv}: value is not JSON: {e}")));
        params = serde_json::from_value(json).unwrap_or_else(|e| fail(&format!("--set {kv}: {e}")));
    }
    params
        .validate()
        .unwrap_or_else(|e| fail(&format!("--set: {e}")));
    params
}

fn main() {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = match cli::parse(&argv, &[], &["--maze", "--strategy", "--evals"]) {
        Ok(cli::Parsed::Run(a)) => a,
        Ok(cli::Parsed::Help) => return print!("{USAGE}"),
        Err(e) => fail(&e),
    };
    if args.max_generations.is_some() {
        fail("--max-generations is not an option here: bound a run with --evals");
    }
    let maze_name = option(&args, "--maze").unwrap_or("hard");
    let maze = Maze::from_name(maze_name)
        .unwrap_or_else(|| fail(&format!("--maze must be medium or hard, got `{maze_name}`")));
    let strategy = option(&args, "--strategy").unwrap_or("novelty");
    if !["fitness", "novelty", "map-elites"].contains(&strategy) {
        fail(&format!(
            "--strategy must be fitness, novelty or map-elites, got `{strategy}`"
        ));
    }
    let max_evals: usize = match option(&args, "--evals").map(str::parse) {
        None => 250_000,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => fail("--evals needs a whole number ≥ 1"),
    };
    let params = neat_params(&args.sets);
    let (runs, seed) = (args.runs.unwrap_or(20), args.seed.unwrap_or(1));
    let name = format!("maze-{}-{strategy}", maze.name());
    let (mut evals, mut total_ms) = (Vec::new(), 0.0);
    for r in 0..runs {
        let t = Instant::now();
        let run_seed = seed.wrapping_add(r as u64);
        let solved = run(strategy, maze, &params, run_seed, max_evals);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        total_ms += ms;
        let shown = solved.map_or("unsolved".to_string(), |e| e.to_string());
        eprintln!("{name} seed={run_seed} evals={shown} ms={ms:.0}");
        evals.extend(solved.map(|e| e as f64));
    }
    println!(
        "{name}: solved={}/{runs} mean_evals={:.0} median_evals={:.0} max_evals={max_evals} mean_ms={:.0}",
        evals.len(),
        stats::mean(&evals).unwrap_or(0.0),
        stats::median(&evals).unwrap_or(0.0),
        total_ms / runs.max(1) as f64,
    );
}

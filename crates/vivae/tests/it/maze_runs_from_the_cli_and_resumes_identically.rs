//! `vivae evolve --task maze` runs Lehman & Stanley's maze with every
//! strategy, resumes bit-identically, is the `maze` example's run for the
//! same seed, stops when solved with `solved=` and `evals_to_solve=` on its
//! summary line, and bad combinations (and the commands that draw driving
//! runs) are refused in one line with exit code 2.

use std::path::Path;

use crate::common::*;
use vivae_lab::tasks::maze::{Maze, MazeTask};
use vivae_neat::driver::{
    Evolution, GenerationReport, HookError, NoCheckpoints, Observer, ParallelEvaluator,
    StopCriteria, Strategy,
};
use vivae_neat::strategies::{Cells, MapElitesParams, NoveltyParams};
use vivae_neat::{MapElites, NeatParams, NoveltySearch, Population};

/// `vivae evolve -q --task maze ARGS --out OUT`, which must succeed; returns stdout.
fn maze(out: &Path, args: &[&str]) -> String {
    ok(vivae()
        .args(["evolve", "-q", "--task", "maze"])
        .args(args)
        .arg("--out")
        .arg(out))
}

/// Asserts a command fails with exit 2 and one line of stderr containing `needle`.
fn refused(cmd: &mut std::process::Command, needle: &str) {
    let out = run(cmd);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(needle), "{needle}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn every_strategy_runs_the_maze_and_resumes_bit_identical() {
    let dir = scratch("maze-resume");
    for strategy in ["neat", "novelty", "map-elites", "nsga2"] {
        let common = ["--strategy", strategy, "--population", "40", "--seed", "3"];
        let whole = dir.join(format!("{strategy}-whole"));
        let line = maze(&whole, &[&common[..], &["--generations", "6"]].concat());
        let generations: u32 = field(&line, "generations").parse().unwrap();
        let part = dir.join(format!("{strategy}-part"));
        maze(&part, &[&common[..], &["--generations", "3"]].concat());
        let resumed = ok(vivae()
            .args(["resume", "-q", "--generations", "6"])
            .arg(&part));
        assert_same_results(&whole, &part);
        for name in ["best-genomes.jsonl", "config.toml"] {
            assert!(
                read(&whole, name) == read(&part, name),
                "{strategy}: {name}"
            );
        }
        assert_eq!(field(&resumed, "generations"), field(&line, "generations"));
        assert_eq!(field(&resumed, "strategy"), strategy);
        // Unsolved in 6 small generations, or solved and stopped early.
        match field(&line, "solved") {
            "no" => {
                assert_eq!(generations, 6, "{line}");
                assert_eq!(field(&line, "evals_to_solve"), "none");
            }
            "yes" => assert!(field(&line, "evals_to_solve").parse::<u64>().is_ok()),
            other => panic!("solved={other}"),
        }
        assert_eq!(field(&line, "evaluations"), (generations * 40).to_string());
        let csv = String::from_utf8(read(&whole, "generations.csv")).unwrap();
        let header = csv.lines().next().unwrap();
        assert!(
            header.ends_with(",best_distance,solvers,evaluations"),
            "{header}"
        );
        assert!(
            header.starts_with("generation,best,mean,median,worst,species,"),
            "{header}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_solved_maze_run_stops_and_counts_evaluations_to_the_first_solver() {
    let dir = scratch("maze-solved");
    let out = dir.join("run");
    let line = maze(
        &out,
        &[
            "--strategy",
            "novelty",
            "--seed",
            "1",
            "--generations",
            "100",
        ],
    );
    assert_eq!(field(&line, "solved"), "yes", "{line}");
    let at: u64 = field(&line, "evals_to_solve").parse().unwrap();
    let generations: usize = field(&line, "generations").parse().unwrap();
    assert!(generations < 100, "a solved run stops: {line}");
    // The solving generation is the last one written, the first with a solver.
    let csv = String::from_utf8(read(&out, "generations.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), generations);
    // The last two columns: solvers, evaluations so far.
    let tail = |r: &Vec<&str>, back: usize| r[r.len() - back].parse::<u64>().unwrap();
    let last = rows.last().unwrap();
    let (solvers, evaluations) = (tail(last, 2), tail(last, 1));
    let before = tail(&rows[rows.len() - 2], 1);
    assert!(
        solvers >= 1 && before < at && at <= evaluations,
        "{at} {csv}"
    );
    assert!(rows[..rows.len() - 1].iter().all(|r| r[r.len() - 2] == "0"));
    let replayed = ok(vivae().arg("replay").arg(&out));
    assert!(replayed.contains("solved=yes"), "{replayed}");
    let d: f64 = field(&replayed, "distance").parse().unwrap();
    assert!(d <= 5.0, "{replayed}");
    // Resuming a solved run does nothing: it is finished.
    let again = run(vivae()
        .args(["resume", "-q", "--generations", "80"])
        .arg(&out));
    assert!(again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("already finished"));
    assert_eq!(
        String::from_utf8(read(&out, "generations.csv")).unwrap(),
        csv
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Each generation's best fitness of the example's run (`crates/lab/examples/maze.rs`).
struct Bests(Vec<f64>);

impl<S: Strategy> Observer<S> for Bests {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        let best = report.evaluations.iter().map(|e| e.fitness);
        self.0.push(best.fold(f64::NEG_INFINITY, f64::max));
        Ok(())
    }
}

/// The example's run of `strategy` (fitness, novelty or map-elites) on the
/// hard maze with `seed`, for `generations`: each generation's best fitness.
fn example_run(strategy: &str, seed: u64, generations: u32) -> Vec<f64> {
    let task = MazeTask::shipped(Maze::Hard).unwrap();
    let params = NeatParams {
        population_size: 250,
        ..NeatParams::plain_neat()
    };
    let pop = || Population::new(params.clone(), MazeTask::spec(), seed).unwrap();
    let stop = StopCriteria::generations(generations);
    let mut bests = Bests(Vec::new());
    let eval = ParallelEvaluator::new(task.clone());
    match strategy {
        "neat" => {
            let mut e = Evolution::new(pop(), eval);
            e.run(&stop, &mut bests, &mut NoCheckpoints).unwrap();
        }
        "novelty" => {
            let novelty = NoveltyParams {
                threshold: 6.0,
                ..NoveltyParams::default()
            };
            let mut e = Evolution::new(NoveltySearch::new(pop(), novelty).unwrap(), eval);
            e.run(&stop, &mut bests, &mut NoCheckpoints).unwrap();
        }
        _ => {
            let cells = Cells::grid(vec![0.0, 0.0], vec![205.0, 205.0], vec![21, 21]).unwrap();
            let map = MapElitesParams {
                batch_size: 250,
                ..MapElitesParams::default()
            };
            let me = MapElites::new(params.clone(), MazeTask::spec(), map, cells, seed).unwrap();
            let mut e = Evolution::new(me, eval);
            e.run(&stop, &mut bests, &mut NoCheckpoints).unwrap();
        }
    }
    bests.0
}

#[test]
fn the_cli_maze_run_is_the_examples_run_for_the_same_seed() {
    let dir = scratch("maze-example");
    for strategy in ["neat", "novelty", "map-elites"] {
        let out = dir.join(strategy);
        maze(
            &out,
            // The example drives our robot (MazeTask): the CLI's `--robot vivae`.
            &[
                "--strategy",
                strategy,
                "--seed",
                "5",
                "--generations",
                "4",
                "--robot",
                "vivae",
            ],
        );
        // population.csv's rank-0 row of each generation is its best fitness.
        let csv = String::from_utf8(read(&out, "population.csv")).unwrap();
        let cli: Vec<f64> = csv
            .lines()
            .skip(1)
            .filter_map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[1] == "0").then(|| f[2].parse().unwrap())
            })
            .collect();
        let example = example_run(strategy, 5, cli.len() as u32);
        assert_eq!(cli.len(), example.len(), "{strategy}");
        assert!(
            cli.iter()
                .zip(&example)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{strategy}: the CLI's {cli:?}, the example's {example:?}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_maze_combinations_and_driving_only_commands_exit_2_with_one_line() {
    let dir = scratch("maze-refused");
    let out = dir.join("never");
    let evolve = |extra: &[&str]| {
        let mut c = vivae();
        c.args(["evolve", "-q", "--task", "maze", "--generations", "1"])
            .args(extra)
            .arg("--out")
            .arg(&out);
        c
    };
    refused(
        &mut evolve(&["--scenario", "hard-maze", "--scenario", "medium-maze"]),
        "experiment.scenarios",
    );
    refused(
        &mut evolve(&["--train-neurons", "3x3,5x5"]),
        "train_neurons",
    );
    refused(
        &mut evolve(&["--substrate", "es-hyperneat"]),
        "substrate.kind",
    );
    refused(
        &mut evolve(&["--behaviour", "side-speed"]),
        "strategy.behaviour",
    );
    refused(&mut evolve(&["--sensors", "3x7"]), "[surface_sensors]");
    refused(&mut evolve(&["--robots", "5"]), "experiment.robots");
    refused(&mut evolve(&["--scenario", "roads"]), "exactly one robot");
    let no_goal = dir.join("no-goal.svg");
    std::fs::write(
        &no_goal,
        vivae_lab::tasks::maze::HARD_MAZE_SVG.replace("id=\"goal\"", "id=\"exit\""),
    )
    .unwrap();
    refused(
        &mut evolve(&["--scenario", no_goal.to_str().unwrap()]),
        "no position mark with id \"goal\"",
    );
    let config = write_small_config(&dir, 1);
    refused(
        evolve(&[]).arg("--config").arg(&config),
        "--task maze: the config file's experiment.task is driving",
    );
    assert!(!out.exists(), "a refused run leaves no directory");
    // A maze run: its report shows its curves; the commands that need a
    // substrate network refuse it, naming the tasks that have one.
    let maze_run = dir.join("maze");
    maze(&maze_run, &["--generations", "1", "--population", "20"]);
    ok(vivae().arg("report").arg(&maze_run));
    assert!(maze_run.join("report.html").is_file());
    refused(vivae().arg("view").arg(&maze_run), "a maze run");
    refused(
        vivae().arg("view").arg(maze_run.join("champion.json")),
        "a maze run",
    );
    refused(
        vivae()
            .args(["retrain", "--neurons", "5x5", "--generations", "1"])
            .arg(&maze_run),
        "retrain works on runs of driving",
    );
    refused(
        vivae()
            .arg("replay")
            .arg(&maze_run)
            .args(["--neurons", "5x5"]),
        "maze",
    );
    let replayed = ok(vivae().arg("replay").arg(&maze_run));
    assert!(replayed.contains("solved=") && replayed.contains("distance="));
    // The shipped mazes are listed.
    let list = ok(vivae().args(["scenario", "list"]));
    for name in ["medium-maze", "hard-maze"] {
        assert!(list.lines().any(|l| l.starts_with(name)), "{list}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_shipped_maze_selects_the_maze_task_and_the_robot_flag_picks_the_model() {
    let dir = scratch("maze-selected");
    let evolve = |out: &str, extra: &[&str]| {
        ok(vivae()
            .args([
                "evolve",
                "-q",
                "--scenario",
                "hard-maze",
                "--generations",
                "2",
            ])
            .args(["--population", "20", "--seed", "2"])
            .args(extra)
            .arg("--out")
            .arg(dir.join(out)))
    };
    // No --task: the shipped hard maze is drawn for the maze task.
    let line = evolve("implicit", &[]);
    assert!(line.contains("best_distance="), "{line}");
    let explicit = evolve("explicit", &["--task", "maze"]);
    for key in ["best", "best_distance", "evaluations"] {
        assert_eq!(field(&line, key), field(&explicit, key), "{key}");
    }
    let config = String::from_utf8(read(&dir.join("implicit"), "config.toml")).unwrap();
    assert!(
        config.contains("task = \"maze\"") && !config.contains("[maze]"),
        "{config}"
    );
    // Our robot is another model: another run, recorded in the config.
    let ours = evolve("vivae", &["--robot", "vivae"]);
    assert_ne!(field(&ours, "best"), field(&line, "best"));
    let config = String::from_utf8(read(&dir.join("vivae"), "config.toml")).unwrap();
    assert!(config.contains("[maze]\nrobot = \"vivae\""), "{config}");
    refused(
        vivae()
            .args(["evolve", "-q", "--robot", "vivae", "--generations", "1"])
            .arg("--out")
            .arg(dir.join("driving")),
        "a driving run has one robot model",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

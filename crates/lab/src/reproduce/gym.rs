//! The `gym-classic` pack: Gymnasium's five classic-control environments
//! under one protocol (docs/howto/classic-control.md, "The protocol"). Each
//! run is the task's default `vivae evolve --task TASK --seed SEED` run,
//! which stops at the first genome whose mean return on its evaluation (5
//! episodes from the evaluation's seed) reaches the environment's threshold
//! and holds it on 100 check episodes ([`crate::tasks::classic::check`]:
//! their mean less three standard errors reaches it too),
//! that genome its champion; the champion
//! is then validated on 100 fresh episodes drawn from the run seed
//! ([`crate::tasks::classic::validation_seed`]), and the run is solved when
//! the validated mean reaches the threshold.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use super::{Journal, Options, Pack, ScratchDir, Table, thousands};
use crate::config::Config;
use crate::error::{Error, Result};
use crate::run::prepare::prepare;
use crate::tasks::TaskEntry;
use crate::tasks::classic::{CHECK_EPISODES, VALIDATION_EPISODES};
use crate::tasks::plain::CHECK_STANDARD_ERRORS;

/// Runs per task.
const RUNS: usize = 10;
/// `--quick`: runs per task and evaluations per run.
const QUICK: (usize, u64) = (3, 3_000);

/// The tasks, in the order the pack runs them (`--method`): every
/// registered task whose runs are validated against a reward threshold.
fn tasks() -> Vec<&'static TaskEntry> {
    let all = crate::tasks::entries().into_iter();
    all.filter(|t| t.reward_threshold.is_some()).collect()
}

/// The names of [`tasks`].
fn task_names() -> Vec<&'static str> {
    tasks().into_iter().map(|t| t.name).collect()
}

/// `vivae reproduce gym-classic`.
pub const GYM_CLASSIC: Pack = Pack {
    name: "gym-classic",
    what: "Gymnasium's classic control (CartPole-v1, Acrobot-v1, MountainCar-v0, MountainCarContinuous-v0, Pendulum-v1): solve rate, evaluations and wall time to solve, the champion's return validated on 100 fresh episodes",
    methods: task_names,
    run: run_pack,
};

/// What one run gave.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Outcome {
    /// Evaluations up to the first that reached the threshold, or all the run's.
    pub evaluations: u64,
    /// Whether a genome reached the threshold in training and held it on the check (the run stopped).
    pub stopped: bool,
    /// The champion's validated mean return.
    pub validated: f64,
    /// Whether that reaches the threshold: the run solved the task.
    pub solved: bool,
    /// Wall-clock seconds of the run and its validation.
    pub wall: f64,
}

impl Outcome {
    /// As the journal keeps it.
    fn text(&self) -> String {
        format!(
            "evaluations={} stopped={} validated={} solved={} wall_s={}",
            self.evaluations, self.stopped, self.validated, self.solved, self.wall
        )
    }

    /// From the journal's text.
    fn parse(text: &str) -> Option<Outcome> {
        let field = |k: &str| (text.split(' ')).find_map(|f| f.strip_prefix(k)?.strip_prefix('='));
        Some(Outcome {
            evaluations: field("evaluations")?.parse().ok()?,
            stopped: field("stopped")?.parse().ok()?,
            validated: field("validated")?.parse().ok()?,
            solved: field("solved")?.parse().ok()?,
            wall: field("wall_s")?.parse().ok()?,
        })
    }
}

/// The config of one run: `vivae evolve --task TASK --seed SEED
/// --generations budget/population`, the task's defaults otherwise.
pub fn config(task: &str, seed: u64, evaluations: Option<u64>, threads: usize) -> Result<Config> {
    let name = crate::config::TaskName(task.into());
    let mut c = crate::tasks::default_config(Some(&name)).map_err(Error::Invalid)?;
    c.experiment.seed = seed;
    if let Some(e) = evaluations {
        let population = c.neat.population_size as u64;
        c.experiment.generations = u32::try_from(e.div_ceil(population)).unwrap_or(u32::MAX);
    }
    c.run.threads = threads;
    Ok(c)
}

/// One run of `config`, its champion validated by its task.
pub(crate) fn one_run(config: Config) -> Result<Outcome> {
    let started = Instant::now();
    let task = config.experiment.task.name().to_string();
    let dir = ScratchDir::new();
    let mut run = prepare(config, true)?.create(&dir.0, true)?;
    run.run(&AtomicBool::new(false), |_| {})?;
    let champion = run.champion().ok_or(Error::NoChampion)?;
    let (validation, solved) = (run.task().validation(&champion.genome))
        .ok_or_else(|| Error::Invalid(format!("gym-classic: {task} has no validation")))?;
    let progress = run.target_progress().copied().unwrap_or_default();
    Ok(Outcome {
        evaluations: progress.solved_at.unwrap_or(progress.evaluations),
        stopped: progress.solved_at.is_some(),
        validated: validation.mean,
        solved,
        wall: started.elapsed().as_secs_f64(),
    })
}

/// One run of `config`, from `journal` when it finished before.
fn journaled(config: Config, journal: &mut Journal) -> Result<(Outcome, bool)> {
    if let Some(o) = journal.get(&config).and_then(Outcome::parse) {
        return Ok((o, true));
    }
    let what = format!(
        "gym-classic {} seed {}",
        config.experiment.task.name(),
        config.experiment.seed
    );
    let outcome = one_run(config.clone())?;
    journal.record(&config, &what, &outcome.text())?;
    Ok((outcome, false))
}

fn run_pack(o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let runs = o.runs.unwrap_or(if o.quick { QUICK.0 } else { RUNS });
    let budget = o.evaluations.or(o.quick.then_some(QUICK.1));
    let mut journal = Journal::open(o.journal.as_deref())?;
    let mut rows = Vec::new();
    let tasks = tasks();
    for entry in &tasks {
        let task = entry.name;
        if !o.methods.is_empty() && !o.methods.iter().any(|m| m == task) {
            continue;
        }
        let mut outcomes = Vec::new();
        for k in 0..runs {
            let seed = o.seed + k as u64;
            let (out, journaled) = journaled(config(task, seed, budget, o.threads)?, &mut journal)?;
            let from = if journaled { " (from the journal)" } else { "" };
            progress(&format!(
                "gym-classic {task} seed {seed}: {} after {} evaluations, validated mean {:.2}, {:.2} s{from}",
                if out.solved { "solved" } else { "not solved" },
                out.evaluations,
                out.validated,
                out.wall
            ));
            outcomes.push(out);
        }
        rows.push(row(entry, &outcomes));
    }
    let last = o.seed + runs as u64 - 1;
    // Each task's generations, the first's and those of any that differ.
    let mut generations = Vec::new();
    for t in &tasks {
        generations.push((
            t.name,
            config(t.name, o.seed, budget, o.threads)?
                .experiment
                .generations,
        ));
    }
    let first = generations.first().map_or(0, |g| g.1);
    let others: Vec<String> = (generations.iter())
        .filter(|(_, g)| *g != first)
        .map(|(t, g)| format!("{t} {g}"))
        .collect();
    let generations = if others.is_empty() {
        first.to_string()
    } else {
        format!("{first} ({})", others.join(", "))
    };
    Ok(Table::new(
        "Gymnasium's classic control, solved and validated",
        &[
            "task",
            "threshold",
            "ours: solved (validated)",
            "ours: stopped (held on the check)",
            "ours: evaluations to solve, median (range)",
            "ours: wall time to solve, median (range), s",
            "ours: validated return, mean (range)",
            "source",
        ],
        rows,
        vec![
            format!(
                "{runs} runs a task, seeds {}–{last}, each the task's default run (plain NEAT, population 150, at most {generations} generations), stopped at the first genome whose mean return over its 5 training episodes reaches the threshold and whose mean over {CHECK_EPISODES} check episodes (from the seed splitmix64(run seed XOR \"checking\"), a stream apart from training and validation), less {CHECK_STANDARD_ERRORS} standard errors of that mean, does too; that genome is the champion",
                o.seed,
            ),
            format!(
                "validation: the run's champion on {VALIDATION_EPISODES} fresh episodes, started as training episodes are but from the seed splitmix64(run seed XOR \"validate\"), a stream no training evaluation draws from; solved = the validated mean reaches the threshold (Gymnasium's reward_threshold; Pendulum-v1 has none: -200 here)"
            ),
            "evaluations to solve count each check as 20 evaluations (100 episodes, 5 an evaluation); evaluations and wall time to solve: over the solved runs (wall time: the run and its validation, on this machine)".into(),
            "each run: vivae evolve --task TASK --seed SEED; its summary line gives validated_mean= and validated=".into(),
        ],
    ))
}

/// The row of `task`'s `outcomes`.
fn row(task: &TaskEntry, outcomes: &[Outcome]) -> Vec<String> {
    let solved: Vec<&Outcome> = outcomes.iter().filter(|o| o.solved).collect();
    let threshold = task.reward_threshold;
    let source = threshold.map_or("", |t| t.source);
    let threshold = threshold.map_or("—".into(), |t| format!("{}", t.value));
    let spread = |xs: Vec<f64>, f: &dyn Fn(f64) -> String| -> String {
        if xs.is_empty() {
            return "—".into();
        }
        let mut xs = xs;
        xs.sort_by(f64::total_cmp);
        let mid = xs.len() / 2;
        let median = if xs.len().is_multiple_of(2) {
            (xs[mid - 1] + xs[mid]) / 2.0
        } else {
            xs[mid]
        };
        format!("{} ({}–{})", f(median), f(xs[0]), f(xs[xs.len() - 1]))
    };
    let validated: Vec<f64> = outcomes.iter().map(|o| o.validated).collect();
    let mean = validated.iter().sum::<f64>() / validated.len().max(1) as f64;
    let (lo, hi) = validated
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(*v), h.max(*v))
        });
    vec![
        task.name.into(),
        threshold,
        format!("{}/{}", solved.len(), outcomes.len()),
        format!(
            "{}/{}",
            outcomes.iter().filter(|o| o.stopped).count(),
            outcomes.len()
        ),
        spread(
            solved.iter().map(|o| o.evaluations as f64).collect(),
            &thousands,
        ),
        spread(solved.iter().map(|o| o.wall).collect(), &|s| {
            format!("{s:.2}")
        }),
        if outcomes.is_empty() {
            "—".into()
        } else {
            format!("{mean:.1} ({lo:.1} to {hi:.1})")
        },
        source.into(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outcome_survives_the_journal() {
        let o = Outcome {
            evaluations: 1234,
            stopped: true,
            validated: -98.25,
            solved: true,
            wall: 0.125,
        };
        assert_eq!(Outcome::parse(&o.text()), Some(o));
        assert_eq!(Outcome::parse("solved 12"), None);
    }

    #[test]
    fn the_pack_is_its_runs_validated_and_counts_only_validated_solves() {
        let options = Options {
            runs: Some(2),
            evaluations: Some(300),
            threads: 1,
            methods: vec!["cartpole".into()],
            ..Options::default()
        };
        let mut lines = Vec::new();
        let t = crate::reproduce::run("gym-classic", &options, &mut |l| lines.push(l.to_string()))
            .unwrap();
        assert_eq!((lines.len(), t.rows.len()), (2, 1), "{lines:?}");
        assert!(t.rows.iter().all(|r| r.len() == t.columns.len()));
        let runs: Vec<Outcome> = (1..=2)
            .map(|seed| one_run(config("cartpole", seed, Some(300), 1).unwrap()).unwrap())
            .collect();
        for o in &runs {
            assert_eq!(o.solved, o.validated >= 475.0, "{o:?}");
            assert!(o.evaluations <= 300 && o.evaluations > 0, "{o:?}");
        }
        let cartpole = crate::tasks::entry("cartpole").unwrap();
        let mut row_again = row(cartpole, &runs);
        // Wall times differ run to run; everything else is the runs'.
        let mut pack_row = t.rows[0].clone();
        row_again[5].clear();
        pack_row[5].clear();
        assert_eq!(pack_row, row_again);
        assert_eq!(t.rows[0][..2], ["cartpole".to_string(), "475".into()]);
        let stopped_unsolved = Outcome {
            stopped: true,
            solved: false,
            validated: 470.0,
            ..runs[0]
        };
        let r = row(cartpole, &[stopped_unsolved]);
        assert_eq!(r[2..5], ["0/1", "1/1", "—"]);
    }
}

//! The maze packs (`maze-medium`, `maze-hard`): Lehman & Stanley 2011's
//! medium and hard maze, novelty search against fitness-based NEAT (and
//! MAP-Elites, which the paper does not have), with Lehman's robot and
//! walls (docs/results.md, "The maze").

use super::{Journal, Options, Pack, Table, solved_at_journaled, stats, thousands};
use crate::config::Config;
use crate::error::Result;
use crate::search::StrategyConfig;

/// The paper's runs per method.
const PAPER_RUNS: usize = 40;
/// The paper's budget: 250,000 evaluations (Figs. 3 and 4's captions).
const PAPER_EVALUATIONS: u64 = 250_000;
/// `--quick`: runs per method and evaluations per run.
const QUICK: (usize, u64) = (5, 25_000);
/// Where the paper's numbers are.
const SOURCE: &str = "Lehman & Stanley 2011, Evol. Comput. 19(2):189–223, Sec. 6";

/// The methods, in the order a pack runs them (`--method`).
const METHODS: [&str; 3] = ["novelty", "neat", "map-elites"];

/// [`METHODS`] as a pack lists them.
fn methods() -> Vec<&'static str> {
    METHODS.to_vec()
}

/// `vivae reproduce maze-medium`.
pub const MEDIUM: Pack = Pack {
    name: "maze-medium",
    what: "Lehman & Stanley 2011's medium maze: novelty search vs fitness-based NEAT vs MAP-Elites",
    methods,
    run: |o, p| run("medium-maze", &MEDIUM_PAPER, o, p),
};

/// `vivae reproduce maze-hard`.
pub const HARD: Pack = Pack {
    name: "maze-hard",
    what: "Lehman & Stanley 2011's hard (deceptive) maze: novelty search vs fitness-based NEAT vs MAP-Elites",
    methods,
    run: |o, p| run("hard-maze", &HARD_PAPER, o, p),
};

/// A method and the paper's result for it: solved runs of 40, mean
/// evaluations (sd) when solved, the page.
struct Paper {
    label: &'static str,
    kind: &'static str,
    solved: Option<usize>,
    mean_sd: Option<(u64, u64)>,
    page: &'static str,
}

const MEDIUM_PAPER: [Paper; 3] = [
    Paper {
        label: "novelty search",
        kind: "novelty",
        solved: Some(40),
        mean_sd: Some((18_274, 20_447)),
        page: "p. 16",
    },
    Paper {
        label: "fitness-based NEAT",
        kind: "neat",
        solved: Some(40),
        mean_sd: Some((56_334, 48_705)),
        page: "p. 16",
    },
    MAP_ELITES,
];

const HARD_PAPER: [Paper; 3] = [
    Paper {
        label: "novelty search",
        kind: "novelty",
        solved: Some(39),
        mean_sd: Some((35_109, 30_236)),
        page: "pp. 16–17",
    },
    Paper {
        label: "fitness-based NEAT",
        kind: "neat",
        solved: Some(3),
        mean_sd: None,
        page: "pp. 16–17",
    },
    MAP_ELITES,
];

const MAP_ELITES: Paper = Paper {
    label: "MAP-Elites (10-unit grid)",
    kind: "map-elites",
    solved: None,
    mean_sd: None,
    page: "",
};

/// The config of one run: `vivae evolve --task maze --scenario MAZE
/// --strategy KIND --seed SEED --generations budget/250`.
pub fn config(maze: &str, kind: &str, seed: u64, evaluations: u64, threads: usize) -> Config {
    let mut c = Config::maze();
    c.experiment.scenario = maze.into();
    c.experiment.seed = seed;
    let population = c.neat.population_size as u64;
    c.experiment.generations = evaluations.div_ceil(population) as u32;
    StrategyConfig::update(&mut c, |s| s.kind = kind.into());
    c.run.threads = threads;
    c
}

fn run(
    maze: &str,
    paper: &[Paper; 3],
    o: &Options,
    progress: &mut dyn FnMut(&str),
) -> Result<Table> {
    let (quick_runs, quick_evals) = QUICK;
    let runs = o
        .runs
        .unwrap_or(if o.quick { quick_runs } else { PAPER_RUNS });
    let budget = (o.evaluations).unwrap_or(if o.quick {
        quick_evals
    } else {
        PAPER_EVALUATIONS
    });
    let mut journal = Journal::open(o.journal.as_deref())?;
    let mut rows = Vec::new();
    for p in paper {
        if !o.methods.is_empty() && !o.methods.iter().any(|m| m == p.kind) {
            rows.push(not_run(p));
            continue;
        }
        let mut solved = Vec::new();
        for k in 0..runs {
            let seed = o.seed + k as u64;
            let what = format!("{maze} {} seed {seed}", p.kind);
            let c = config(maze, p.kind, seed, budget, o.threads);
            let (at, journaled) = solved_at_journaled(c, &what, &mut journal)?;
            let said = at.map_or("unsolved".to_string(), |n| {
                format!("solved after {n} evaluations")
            });
            let from = if journaled { " (from the journal)" } else { "" };
            progress(&format!("{what}: {said}{from}"));
            solved.extend(at);
        }
        rows.push(row(p, &solved, runs));
    }
    let last = o.seed + runs as u64 - 1;
    Ok(Table::new(
        format!("The {} (Lehman & Stanley 2011), ours beside the paper's", maze.replace('-', " ")),
        &[
            "method",
            "ours: solved",
            "ours: mean evaluations (sd)",
            "ours: median",
            "paper: solved",
            "paper: mean evaluations (sd)",
            "source",
        ],
        rows,
        vec![
            format!(
                "ours: {runs} runs per method, seeds {}–{last}, population 250, at most {} evaluations a run; a run stops at its first solver, whose evaluation is counted; means over solved runs",
                o.seed,
                thousands(budget as f64)
            ),
            "ours: Lehman's robot and walls (maze.robot = \"lehman\", his code's quirks), plain NEAT with the parameters and the one-hidden-node start network of his code (tasks::maze::lehman_neat; generational, his is steady-state); novelty k = 15, threshold 6 in px, ×0.95 after 10 generations without additions, ×1.2 above 4 (his code; Euclidean distance, his mean absolute coordinate difference is strategy.novelty.metric = \"mean-absolute\")".into(),
            "the paper: 40 runs, 250,000 evaluations, steady-state rtNEAT (Novelty Search C++); page numbers of the authors' preprint".into(),
            format!("each run: vivae evolve --task maze --scenario {maze} --strategy KIND --seed SEED --generations {}", budget.div_ceil(250)),
        ],
    ))
}

/// The row of a method `--method` left out.
fn not_run(p: &Paper) -> Vec<String> {
    let mut r = row(p, &[], 0);
    r[1..4].fill("not run (--method)".into());
    r
}

fn row(p: &Paper, solved: &[u64], runs: usize) -> Vec<String> {
    let ours = stats(solved);
    let mean_sd = ours.map_or("—".into(), |(m, sd, _)| {
        format!("{} ({})", thousands(m), thousands(sd))
    });
    let median = ours.map_or("—".into(), |(_, _, med)| thousands(med));
    let paper_solved = p
        .solved
        .map_or("not in the paper".into(), |s| format!("{s}/{PAPER_RUNS}"));
    let paper_mean = match (p.solved, p.mean_sd) {
        (_, Some((m, sd))) => format!("{} ({})", thousands(m as f64), thousands(sd as f64)),
        (Some(_), None) => "not given".into(),
        (None, _) => "—".into(),
    };
    let source = if p.page.is_empty() {
        "—".into()
    } else {
        format!("{SOURCE}, {}", p.page)
    };
    vec![
        p.label.into(),
        format!("{}/{runs}", solved.len()),
        mean_sd,
        median,
        paper_solved,
        paper_mean,
        source,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pack_run_is_the_cli_runs_config_and_its_table_counts_solvers() {
        let c = config("hard-maze", "novelty", 7, 250_000, 1);
        assert_eq!(c.experiment.generations, 1000);
        assert_eq!(
            (c.experiment.seed, StrategyConfig::of(&c).kind.name()),
            (7, "novelty")
        );
        crate::tasks::check(&c).unwrap();
        let r = row(&HARD_PAPER[0], &[10_000, 30_000], 3);
        assert_eq!(r[1..4], ["2/3", "20,000 (14,142)", "20,000"]);
        assert_eq!(r[4..6], ["39/40", "35,109 (30,236)"]);
        assert!(r[6].contains("pp. 16–17"));
        let r = row(&MAP_ELITES, &[], 2);
        assert_eq!(r[1..6], ["0/2", "—", "—", "not in the paper", "—"]);
    }
}

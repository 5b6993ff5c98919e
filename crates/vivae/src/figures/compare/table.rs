//! The comparison as numbers: medians per generation and per wall-clock
//! second, and the table of them in Markdown and CSV.

use std::fmt::Write as _;

use vivae_neat::stats;

use super::runs::{Group, RunData};

/// Generations at which the table reports the median best fitness.
pub const AT_GENERATIONS: [u32; 5] = [10, 50, 100, 200, 400];
/// Wall-clock seconds at which the table reports the median best-so-far fitness.
pub const AT_SECONDS: [f64; 3] = [30.0, 120.0, 600.0];

/// A median over the runs that have a value, and how many did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Median {
    /// The median, `None` when no run has a value.
    pub value: Option<f64>,
    /// Runs that contributed.
    pub runs: usize,
}

impl Median {
    fn of(values: &[f64]) -> Median {
        Median {
            value: stats::median(values),
            runs: values.len(),
        }
    }
}

/// A group's numbers, as in the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Group name.
    pub name: String,
    /// Number of runs (seeds).
    pub seeds: usize,
    /// Fewest and most generations of its runs.
    pub generations: (usize, usize),
    /// Median best fitness at each of [`AT_GENERATIONS`], over the runs that reached it.
    pub at_generation: Vec<(u32, Median)>,
    /// Median over runs of each run's median wall seconds per generation.
    pub seconds_per_generation: f64,
    /// Median best-so-far fitness at each of [`AT_SECONDS`], over the runs that got that far.
    pub at_seconds: Vec<(f64, Median)>,
    /// Median over runs of the best fitness of the whole run.
    pub final_best: f64,
}

/// The numbers of one group (which has at least one run).
pub fn summarise(group: &Group) -> Summary {
    let runs = &group.runs;
    let lengths = runs.iter().map(RunData::generations);
    let at_generation = AT_GENERATIONS
        .iter()
        .map(|&g| {
            let values: Vec<f64> = runs
                .iter()
                .filter_map(|r| {
                    r.best
                        .get(g as usize - 1)
                        .filter(|_| r.generations() >= g as usize)
                })
                .copied()
                .collect();
            (g, Median::of(&values))
        })
        .collect();
    let per_generation: Vec<f64> = runs
        .iter()
        .filter_map(|r| stats::median(&r.seconds[..r.generations()]))
        .collect();
    let at_seconds = AT_SECONDS
        .iter()
        .map(|&t| {
            let values: Vec<f64> = runs.iter().filter_map(|r| r.best_at_seconds(t)).collect();
            (t, Median::of(&values))
        })
        .collect();
    let finals: Vec<f64> = runs
        .iter()
        .filter_map(|r| r.best_so_far().last().copied())
        .collect();
    Summary {
        name: group.name.clone(),
        seeds: runs.len(),
        generations: (
            lengths.clone().min().unwrap_or(0),
            lengths.max().unwrap_or(0),
        ),
        at_generation,
        seconds_per_generation: stats::median(&per_generation).unwrap_or(f64::NAN),
        at_seconds,
        final_best: stats::median(&finals).unwrap_or(f64::NAN),
    }
}

/// A table cell: the median to 3 decimals, `—` without one, and `(k/n)` when
/// only k of the group's n runs contributed.
fn cell(m: &Median, seeds: usize) -> String {
    match m.value {
        None => "—".into(),
        Some(v) if m.runs < seeds => format!("{v:.3} ({}/{seeds})", m.runs),
        Some(v) => format!("{v:.3}"),
    }
}

/// Seconds as a column heading: `30 s`, `2 min`.
fn seconds_heading(t: f64) -> String {
    if t >= 60.0 && t % 60.0 == 0.0 {
        format!("{} min", t / 60.0)
    } else {
        format!("{t} s")
    }
}

/// The Markdown table, a row per group; generation columns only for
/// generations some run reached.
pub fn markdown(summaries: &[Summary]) -> String {
    let reached: Vec<usize> = AT_GENERATIONS
        .iter()
        .enumerate()
        .filter(|&(_, &g)| summaries.iter().any(|s| s.generations.1 >= g as usize))
        .map(|(i, _)| i)
        .collect();
    let mut head = vec!["group".to_string(), "seeds".into(), "generations".into()];
    head.extend(
        reached
            .iter()
            .map(|&i| format!("best @ gen {}", AT_GENERATIONS[i])),
    );
    head.push("s/gen".into());
    head.extend(
        AT_SECONDS
            .iter()
            .map(|&t| format!("best-so-far @ {}", seconds_heading(t))),
    );
    head.push("final best".into());
    let mut out = format!("| {} |\n", head.join(" | "));
    let _ = writeln!(out, "|{}", " --- |".repeat(head.len()));
    for s in summaries {
        let (lo, hi) = s.generations;
        let mut row = vec![
            s.name.replace('|', "\\|"),
            s.seeds.to_string(),
            if lo == hi {
                lo.to_string()
            } else {
                format!("{lo}–{hi}")
            },
        ];
        row.extend(
            reached
                .iter()
                .map(|&i| cell(&s.at_generation[i].1, s.seeds)),
        );
        row.push(format!("{:.3}", s.seconds_per_generation));
        row.extend(s.at_seconds.iter().map(|(_, m)| cell(m, s.seeds)));
        row.push(format!("{:.3}", s.final_best));
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    out
}

/// The same numbers as CSV, every column always present (empty: no run
/// reached it); `*_runs` columns count the runs behind each median.
pub fn csv(summaries: &[Summary]) -> String {
    let mut head = vec![
        "group".to_string(),
        "seeds".into(),
        "min_generations".into(),
        "max_generations".into(),
    ];
    for g in AT_GENERATIONS {
        head.push(format!("best_gen_{g}"));
        head.push(format!("best_gen_{g}_runs"));
    }
    head.push("seconds_per_generation".into());
    for t in AT_SECONDS {
        head.push(format!("best_so_far_{t}s"));
        head.push(format!("best_so_far_{t}s_runs"));
    }
    head.push("final_best".into());
    let mut out = head.join(",") + "\n";
    let quote = |s: &str| vivae_lab::io::csv_field(s).into_owned();
    let num = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
    for s in summaries {
        let mut row = vec![
            quote(&s.name),
            s.seeds.to_string(),
            s.generations.0.to_string(),
            s.generations.1.to_string(),
        ];
        for (_, m) in &s.at_generation {
            row.push(num(m.value));
            row.push(m.runs.to_string());
        }
        row.push(s.seconds_per_generation.to_string());
        for (_, m) in &s.at_seconds {
            row.push(num(m.value));
            row.push(m.runs.to_string());
        }
        row.push(s.final_best.to_string());
        out += &(row.join(",") + "\n");
    }
    out
}

/// Median over the group's runs of the best fitness of each generation that
/// every run reached.
pub fn median_per_generation(group: &Group) -> Vec<f64> {
    let common = group
        .runs
        .iter()
        .map(RunData::generations)
        .min()
        .unwrap_or(0);
    (0..common)
        .filter_map(|g| stats::median(&group.runs.iter().map(|r| r.best[g]).collect::<Vec<_>>()))
        .collect()
}

/// Median over the group's runs of best-so-far fitness against wall seconds,
/// as (time, value) corners of a step line, from when every run had finished
/// a generation until the first run stopped.
pub fn median_per_second(group: &Group) -> Vec<(f64, f64)> {
    let cumulative: Vec<Vec<f64>> = group.runs.iter().map(RunData::cumulative_seconds).collect();
    if cumulative.iter().any(Vec::is_empty) {
        return Vec::new();
    }
    let start = cumulative.iter().map(|c| c[0]).fold(0.0, f64::max);
    let end = cumulative
        .iter()
        .map(|c| c[c.len() - 1])
        .fold(f64::INFINITY, f64::min);
    let mut times: Vec<f64> = cumulative
        .iter()
        .flatten()
        .copied()
        .filter(|&t| t >= start && t <= end)
        .collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    let mut points = Vec::with_capacity(2 * times.len());
    for &t in &times {
        let values: Vec<f64> = group
            .runs
            .iter()
            .filter_map(|r| r.best_at_seconds(t))
            .collect();
        if let Some(m) = stats::median(&values) {
            if let Some(&(_, last)) = points.last() {
                points.push((t, last));
            }
            points.push((t, m));
        }
    }
    points
}

/// One run's best-so-far fitness against cumulative seconds, as step-line corners.
pub(super) fn steps(run: &RunData) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    for (t, b) in run.cumulative_seconds().into_iter().zip(run.best_so_far()) {
        if let Some(&(_, last)) = points.last() {
            points.push((t, last));
        }
        points.push((t, b));
    }
    points
}

//! `vivae compare`: several runs side by side.
//!
//! Reads each run directory's `generations.csv` (best fitness per generation)
//! and `timing.csv` (wall seconds per generation), groups the runs (by
//! `--label`, else by their substrate from `config.toml`, e.g. `3x5→3x3`),
//! and draws one figure with two panels — best fitness per generation and
//! best-so-far fitness per cumulative wall-clock second — with a thin line per
//! run and a thick median line per group. The same comparison as numbers is
//! a Markdown table (stdout) and optionally a CSV file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use vivae_neat::stats;

use super::{FAMILY, Figure, FigureError, draw_err, register_font, svg_to_png};
use vivae_lab::config::Config;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::{bad_input, read_config, write_atomic};
use vivae_lab::rundir::{self, files};

/// Generations at which the table reports the median best fitness.
pub const AT_GENERATIONS: [u32; 5] = [10, 50, 100, 200, 400];
/// Wall-clock seconds at which the table reports the median best-so-far fitness.
pub const AT_SECONDS: [f64; 3] = [30.0, 120.0, 600.0];

/// A `--label NAME=GLOB` rule: runs whose path matches `GLOB` form group `NAME`.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelRule {
    /// The group's name.
    pub name: String,
    /// A glob (`*` any characters but `/`, `?` one character) or a directory.
    pub pattern: String,
}

impl FromStr for LabelRule {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s.split_once('=') {
            Some((name, pattern)) if !name.trim().is_empty() && !pattern.is_empty() => {
                Ok(LabelRule {
                    name: name.trim().to_string(),
                    pattern: pattern.to_string(),
                })
            }
            _ => Err(format!("expected NAME=GLOB, got {s:?}")),
        }
    }
}

impl LabelRule {
    /// Whether the run directory `dir` is one this rule names: the glob matches
    /// the path as given or its last component, or both name the same directory.
    pub fn matches(&self, dir: &Path) -> bool {
        let path = dir.to_string_lossy();
        let path = path.trim_end_matches('/');
        let pattern = self.pattern.trim_end_matches('/');
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        glob_match(pattern, path)
            || glob_match(pattern, &name)
            || matches!(
                (std::fs::canonicalize(pattern), std::fs::canonicalize(dir)),
                (Ok(a), Ok(b)) if a == b
            )
    }
}

/// Whether `text` matches the glob `pattern`: `*` is any run of characters
/// other than `/`, `?` any one character other than `/`, all else literal.
pub fn glob_match(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.chars().collect();
    let t: Vec<char> = text.chars().collect();
    // Iterative matcher with one backtrack point (the last `*`).
    let (mut pi, mut ti) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while ti < t.len() {
        if pi < p.len() && (p[pi] == t[ti] || (p[pi] == '?' && t[ti] != '/')) {
            pi += 1;
            ti += 1;
        } else if pi < p.len() && p[pi] == '*' {
            star = Some((pi, ti));
            pi += 1;
        } else if let Some((sp, st)) = star.filter(|&(_, st)| t[st] != '/') {
            // Let the star swallow one more character (never a `/`).
            star = Some((sp, st + 1));
            pi = sp + 1;
            ti = st + 1;
        } else {
            return false;
        }
    }
    p[pi..].iter().all(|&c| c == '*')
}

/// One run's progress: best fitness and wall seconds of each generation (1, 2, …).
#[derive(Debug, Clone, PartialEq)]
pub struct RunData {
    /// The run directory.
    pub dir: PathBuf,
    /// Best fitness of generation `i + 1`.
    pub best: Vec<f64>,
    /// Wall-clock seconds of generation `i + 1`.
    pub seconds: Vec<f64>,
}

impl RunData {
    /// Generations recorded.
    pub fn generations(&self) -> usize {
        self.best.len().min(self.seconds.len())
    }

    /// Best fitness seen up to and including each generation.
    pub fn best_so_far(&self) -> Vec<f64> {
        let mut max = f64::NEG_INFINITY;
        self.best[..self.generations()]
            .iter()
            .map(|&b| {
                max = max.max(b);
                max
            })
            .collect()
    }

    /// Wall-clock seconds from the start to the end of each generation.
    pub fn cumulative_seconds(&self) -> Vec<f64> {
        let mut sum = 0.0;
        self.seconds[..self.generations()]
            .iter()
            .map(|&s| {
                sum += s;
                sum
            })
            .collect()
    }

    /// Best-so-far fitness at `t` wall seconds, if the run got that far and had
    /// finished a generation by then.
    pub fn best_at_seconds(&self, t: f64) -> Option<f64> {
        let cumulative = self.cumulative_seconds();
        if cumulative.last().is_none_or(|&total| total < t) {
            return None;
        }
        let done = cumulative.iter().take_while(|&&c| c <= t).count();
        done.checked_sub(1).map(|i| self.best_so_far()[i])
    }
}

/// Reads a run directory's `generations.csv` and `timing.csv`.
pub fn read_run(dir: &Path) -> Result<RunData> {
    if !dir.is_dir() {
        return Err(Error::Read {
            path: dir.to_path_buf(),
            reason: if dir.exists() {
                "not a directory (expected a run directory)".into()
            } else {
                "no such run directory".into()
            },
        });
    }
    let generations = dir.join(files::GENERATIONS);
    let timing = dir.join(files::TIMING);
    let best = rundir::read_generations(&generations)?
        .iter()
        .map(|r| r.best)
        .collect();
    let seconds = rundir::read_timing(&timing)?
        .iter()
        .map(|r| r.seconds)
        .collect();
    let run = RunData {
        dir: dir.to_path_buf(),
        best,
        seconds,
    };
    if run.generations() == 0 {
        return Err(Error::Checkpoint {
            path: generations,
            reason: "no generation recorded (in it and timing.csv) yet".into(),
        });
    }
    Ok(run)
}

/// The group name of a run without a label: its substrate, e.g. `3x5→3x3`,
/// with distance rays and training resolutions when it has them.
pub fn substrate_label(config: &Config) -> String {
    let s = &config.surface_sensors;
    let mut label = format!("{}x{}", s.rings, s.angles);
    if config.distance_sensors.rays > 0 {
        let _ = write!(label, "+{}rays", config.distance_sensors.rays);
    }
    let _ = write!(label, "→{}", config.substrate.neurons);
    let sub = &config.substrate;
    if !sub.train_neurons.is_empty() || !sub.train_sensors.is_empty() {
        let list = |g: &[vivae_lab::substrate::PolarGrid]| {
            g.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(",")
        };
        let mut parts = Vec::new();
        if !sub.train_sensors.is_empty() {
            parts.push(list(&sub.train_sensors));
        }
        if !sub.train_neurons.is_empty() {
            parts.push(list(&sub.train_neurons));
        }
        let _ = write!(label, " (trained at {})", parts.join(" → "));
    }
    label
}

/// Runs compared together (several seeds of one setup).
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Name shown in the legend and table.
    pub name: String,
    /// The group's runs, in command-line order.
    pub runs: Vec<RunData>,
}

/// Puts each run into the group its name says (groups in order of first
/// appearance); `names[i]` is the group of `runs[i]`.
pub fn group(runs: Vec<RunData>, names: &[String]) -> Vec<Group> {
    let mut groups: Vec<Group> = Vec::new();
    for (run, name) in runs.into_iter().zip(names) {
        match groups.iter_mut().find(|g| &g.name == name) {
            Some(g) => g.runs.push(run),
            None => groups.push(Group {
                name: name.clone(),
                runs: vec![run],
            }),
        }
    }
    groups
}

/// Each run's label from the first matching rule (`None`: no rule matches);
/// a rule that matches no run is an error (a typo would otherwise go unnoticed).
pub fn assign_labels(dirs: &[PathBuf], rules: &[LabelRule]) -> Result<Vec<Option<String>>> {
    let labels: Vec<Option<String>> = dirs
        .iter()
        .map(|d| rules.iter().find(|r| r.matches(d)).map(|r| r.name.clone()))
        .collect();
    for rule in rules {
        if !dirs.iter().any(|d| rule.matches(d)) {
            return Err(bad_input(format!(
                "--label {}={}: matches none of the run directories given",
                rule.name, rule.pattern
            )));
        }
    }
    Ok(labels)
}

/// Reads the run directories and groups them (by `rules`, else by substrate).
pub fn load_groups(dirs: &[PathBuf], rules: &[LabelRule]) -> Result<Vec<Group>> {
    for (i, d) in dirs.iter().enumerate() {
        let same = |e: &PathBuf| match (std::fs::canonicalize(e), std::fs::canonicalize(d)) {
            (Ok(a), Ok(b)) => a == b,
            _ => e == d,
        };
        if dirs[..i].iter().any(same) {
            return Err(bad_input(format!(
                "{}: run directory given twice",
                d.display()
            )));
        }
    }
    let labels = assign_labels(dirs, rules)?;
    let mut runs = Vec::with_capacity(dirs.len());
    let mut names = Vec::with_capacity(dirs.len());
    for (dir, label) in dirs.iter().zip(labels) {
        runs.push(read_run(dir)?);
        names.push(match label {
            Some(l) => l,
            None => substrate_label(&read_config(&dir.join(files::CONFIG))?),
        });
    }
    Ok(group(runs, &names))
}

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
    let quote = |s: &str| {
        if s.contains([',', '"', '\n']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
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

/// Colour-blind safe group colours (Okabe & Ito), cycled.
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// Size and title of the comparison figure.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Figure title.
    pub title: String,
    /// Width in SVG units (the PNG is `PNG_SCALE` times larger).
    pub width: u32,
    /// Height in SVG units.
    pub height: u32,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            title: "Best fitness per generation and per wall-clock second".into(),
            width: 1300,
            height: 580,
        }
    }
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
fn steps(run: &RunData) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    for (t, b) in run.cumulative_seconds().into_iter().zip(run.best_so_far()) {
        if let Some(&(_, last)) = points.last() {
            points.push((t, last));
        }
        points.push((t, b));
    }
    points
}

/// Label of a seconds tick on the log axis.
fn seconds_label(t: &f64) -> String {
    if *t >= 1.0 {
        format!("{t:.0}")
    } else {
        let s = format!("{t:.3}");
        s.trim_end_matches('0').to_string()
    }
}

/// Renders the comparison figure (SVG and PNG).
pub fn render(groups: &[Group], opts: &CompareOptions) -> Result<Figure, FigureError> {
    let svg = draw(groups, opts)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

/// The left panel: fitness against generation.
type GenerationChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;
/// The right panel: fitness against seconds on a log scale.
type SecondsChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, RangedCoordf64>>;

/// The axes' ranges shared by the panels.
struct Ranges {
    /// Fitness, both panels.
    fitness: std::ops::Range<f64>,
    /// Generations, the left panel.
    generations: std::ops::Range<f64>,
    /// Seconds, the right panel.
    seconds: std::ops::Range<f64>,
}

impl Ranges {
    /// Ranges holding every run of `groups` (each with at least one generation).
    fn new(groups: &[Group]) -> Ranges {
        let runs = || groups.iter().flat_map(|g| &g.runs);
        let all_best = || runs().flat_map(|r| r.best[..r.generations()].iter().copied());
        let lo = all_best().fold(f64::INFINITY, f64::min);
        let hi = all_best().fold(f64::NEG_INFINITY, f64::max);
        let pad = ((hi - lo) * 0.06).max(1e-3);
        let max_gen = runs().map(RunData::generations).max().unwrap_or(1);
        let t_min = runs()
            .map(|r| r.cumulative_seconds()[0])
            .fold(f64::INFINITY, f64::min)
            .max(1e-3);
        let t_max = runs()
            .map(|r| r.cumulative_seconds()[r.generations() - 1])
            .fold(0.0, f64::max)
            .max(t_min * 10.0);
        Ranges {
            fitness: (lo - pad)..(hi + pad),
            generations: 0.5..(max_gen as f64 + 0.5),
            seconds: (t_min / 1.25)..(t_max * 1.25),
        }
    }
}

/// Checks that there is something to draw, every run has a generation, and the size is usable.
fn check(groups: &[Group], opts: &CompareOptions) -> Result<(), FigureError> {
    if groups.iter().all(|g| g.runs.is_empty()) {
        return Err(FigureError::NoData("no runs to compare"));
    }
    if let Some(r) = groups
        .iter()
        .flat_map(|g| &g.runs)
        .find(|r| r.generations() == 0)
    {
        return Err(FigureError::Invalid(format!(
            "{}: no generation recorded",
            r.dir.display()
        )));
    }
    if opts.width < 600 || opts.height < 300 {
        return Err(FigureError::Invalid(format!(
            "figure size {}x{} is too small (at least 600x300)",
            opts.width, opts.height
        )));
    }
    Ok(())
}

/// The font of axis descriptions.
fn label_font() -> FontDesc<'static> {
    (FAMILY, 18).into_font()
}

/// The font of axis labels and the legend.
fn axis_font() -> FontDesc<'static> {
    (FAMILY, 15).into_font()
}

/// The font of the panels' captions.
fn caption_font() -> FontDesc<'static> {
    (FAMILY, 17).into_font()
}

/// A run's line.
fn thin(c: RGBColor) -> ShapeStyle {
    c.mix(0.3).stroke_width(1)
}

/// A group's median line.
fn thick(c: RGBColor) -> ShapeStyle {
    c.stroke_width(3)
}

/// The left panel with its axes: best fitness of each generation.
fn generation_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    ranges: &Ranges,
) -> Result<GenerationChart<'a, 'b>, FigureError> {
    let mut chart = ChartBuilder::on(area)
        .caption("best of each generation", caption_font())
        .margin(10)
        .margin_right(20)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(ranges.generations.clone(), ranges.fitness.clone())
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc("generation")
        .y_desc("best fitness (px/step)")
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(&|x| {
            if (x - x.round()).abs() < 1e-6 {
                format!("{x:.0}")
            } else {
                String::new()
            }
        })
        .draw()
        .map_err(draw_err)?;
    Ok(chart)
}

/// The right panel with its axes: best-so-far fitness against wall-clock seconds.
fn seconds_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    ranges: &Ranges,
) -> Result<SecondsChart<'a, 'b>, FigureError> {
    let mut chart = ChartBuilder::on(area)
        .caption("best so far, against wall-clock time", caption_font())
        .margin(10)
        .margin_right(20)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(ranges.seconds.clone().log_scale(), ranges.fitness.clone())
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc("cumulative wall-clock seconds (log scale)")
        .y_desc("best-so-far fitness (px/step)")
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(&seconds_label)
        .draw()
        .map_err(draw_err)?;
    Ok(chart)
}

/// Every run's thin line in both panels.
fn draw_run_lines(
    groups: &[Group],
    per_gen: &mut GenerationChart<'_, '_>,
    per_second: &mut SecondsChart<'_, '_>,
) -> Result<(), FigureError> {
    for (gi, g) in groups.iter().enumerate() {
        let colour = COLOURS[gi % COLOURS.len()];
        for r in &g.runs {
            per_gen
                .draw_series(LineSeries::new(
                    r.best[..r.generations()]
                        .iter()
                        .enumerate()
                        .map(|(i, &b)| (i as f64 + 1.0, b)),
                    thin(colour),
                ))
                .map_err(draw_err)?;
            per_second
                .draw_series(LineSeries::new(steps(r), thin(colour)))
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

/// Every group's thick median line in both panels, labelled for the legend.
fn draw_median_lines(
    groups: &[Group],
    per_gen: &mut GenerationChart<'_, '_>,
    per_second: &mut SecondsChart<'_, '_>,
) -> Result<(), FigureError> {
    for (gi, g) in groups.iter().enumerate() {
        let colour = COLOURS[gi % COLOURS.len()];
        let n = g.runs.len();
        let label = if n == 1 {
            format!("{} (1 run)", g.name)
        } else {
            format!("{} ({n} runs, median)", g.name)
        };
        per_gen
            .draw_series(LineSeries::new(
                median_per_generation(g)
                    .into_iter()
                    .enumerate()
                    .map(|(i, b)| (i as f64 + 1.0, b)),
                thick(colour),
            ))
            .map_err(draw_err)?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], thick(colour)));
        per_second
            .draw_series(LineSeries::new(median_per_second(g), thick(colour)))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Draws the figure into an SVG string.
fn draw(groups: &[Group], opts: &CompareOptions) -> Result<String, FigureError> {
    register_font()?;
    check(groups, opts)?;
    let ranges = Ranges::new(groups);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (opts.width, opts.height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let root = root
            .titled(&opts.title, (FAMILY, 22).into_font().style(FontStyle::Bold))
            .map_err(draw_err)?;
        let (left, right) = root.split_horizontally(opts.width / 2);
        let mut per_gen = generation_chart(&left, &ranges)?;
        let mut per_second = seconds_chart(&right, &ranges)?;
        // Every run's thin line first, so that no median line is hidden under one.
        draw_run_lines(groups, &mut per_gen, &mut per_second)?;
        draw_median_lines(groups, &mut per_gen, &mut per_second)?;
        per_gen
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(180, 180, 180))
            .label_font(axis_font())
            .draw()
            .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// Runs `vivae compare` on the run directories `runs`, grouped by `rules`:
/// writes the figure to `out` (.png or .svg) and the table as CSV to `csv`,
/// and returns the table in Markdown.
pub fn run(
    runs: &[PathBuf],
    rules: &[LabelRule],
    out: &Path,
    csv_out: Option<&Path>,
    opts: &CompareOptions,
) -> Result<String> {
    let svg_out = match out.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") => true,
        Some(e) if e.eq_ignore_ascii_case("png") => false,
        _ => {
            return Err(bad_input(format!(
                "{}: the figure must be a .png or .svg file",
                out.display()
            )));
        }
    };
    let groups = load_groups(runs, rules)?;
    let summaries: Vec<Summary> = groups.iter().map(summarise).collect();
    let bytes = if svg_out {
        draw(&groups, opts)?.into_bytes()
    } else {
        render(&groups, opts)?.png
    };
    // Both outputs' folders are made first (as `evolve` and `replay` make
    // theirs), so that one is not written without the other.
    for path in std::iter::once(out).chain(csv_out) {
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            vivae_lab::io::create_dirs_for(parent, path)?;
        }
    }
    if let Some(path) = csv_out {
        write_atomic(path, csv(&summaries).as_bytes())?;
    }
    write_atomic(out, &bytes)?;
    Ok(markdown(&summaries))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};

    fn run(name: &str, best: &[f64], seconds: &[f64]) -> RunData {
        RunData {
            dir: PathBuf::from(name),
            best: best.to_vec(),
            seconds: seconds.to_vec(),
        }
    }

    #[test]
    fn globs_match_within_path_components() {
        assert!(glob_match("cam16-s*", "cam16-s1"));
        assert!(glob_match("runs/cam16-s?", "runs/cam16-s3"));
        assert!(glob_match("*", "x"));
        assert!(glob_match("a*b*c", "aXbYbc"));
        assert!(!glob_match("runs/*", "runs/a/b"), "* does not cross /");
        assert!(!glob_match("cam16-s?", "cam16-s12"));
        assert!(!glob_match("paper", "paper-seed-1"));
        assert!(glob_match("", ""));
    }

    #[test]
    fn label_rules_parse_and_match_path_or_folder_name() {
        let rule: LabelRule = "camera 16=/work/runs/cam16-s*".parse().unwrap();
        assert_eq!(rule.name, "camera 16");
        assert!(rule.matches(Path::new("/work/runs/cam16-s2/")));
        let by_name: LabelRule = "paper=paper-seed-*".parse().unwrap();
        assert!(by_name.matches(Path::new("../main/runs/paper-seed-4")));
        assert!(!by_name.matches(Path::new("runs/cam16-s1")));
        for bad in ["noequals", "=x", "x="] {
            assert!(bad.parse::<LabelRule>().is_err(), "{bad}");
        }
    }

    #[test]
    fn first_matching_label_wins_and_unused_labels_are_refused() {
        let dirs = [
            PathBuf::from("r/a-1"),
            PathBuf::from("r/a-2"),
            PathBuf::from("r/b"),
        ];
        let rules: Vec<LabelRule> = ["one=a-1", "rest=a-*"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let labels = assign_labels(&dirs, &rules).unwrap();
        assert_eq!(
            labels,
            [Some("one".to_string()), Some("rest".to_string()), None]
        );
        let typo = vec!["x=zzz*".parse().unwrap()];
        let err = assign_labels(&dirs, &typo).unwrap_err();
        assert!(err.is_bad_input());
        assert!(err.to_string().contains("matches none"), "{err}");
    }

    #[test]
    fn groups_keep_first_appearance_order() {
        let runs = vec![
            run("a", &[1.0], &[1.0]),
            run("b", &[2.0], &[1.0]),
            run("c", &[3.0], &[1.0]),
        ];
        let names = ["x".to_string(), "y".into(), "x".into()];
        let groups = group(runs, &names);
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0].name, "x");
        assert_eq!(groups[0].runs.len(), 2);
        assert_eq!(groups[0].runs[1].dir, PathBuf::from("c"));
        assert_eq!(groups[1].runs[0].dir, PathBuf::from("b"));
    }

    #[test]
    fn best_so_far_at_wall_seconds() {
        let r = run("a", &[1.0, 3.0, 2.0, 4.0], &[10.0, 10.0, 10.0, 10.0]);
        assert_eq!(r.best_so_far(), [1.0, 3.0, 3.0, 4.0]);
        assert_eq!(r.cumulative_seconds(), [10.0, 20.0, 30.0, 40.0]);
        assert_eq!(r.best_at_seconds(5.0), None, "no generation done yet");
        assert_eq!(r.best_at_seconds(10.0), Some(1.0));
        assert_eq!(r.best_at_seconds(35.0), Some(3.0));
        assert_eq!(r.best_at_seconds(40.0), Some(4.0));
        assert_eq!(r.best_at_seconds(41.0), None, "the run stopped before");
    }

    #[test]
    fn summary_medians_count_only_runs_that_got_there() {
        let g = Group {
            name: "g".into(),
            runs: vec![
                run("a", &[1.0; 10], &[1.0; 10]),
                run("b", &[2.0; 50], &[2.0; 50]),
                run("c", &[4.0; 60], &[3.0; 60]),
            ],
        };
        let s = summarise(&g);
        assert_eq!(s.seeds, 3);
        assert_eq!(s.generations, (10, 60));
        assert_eq!(
            s.at_generation[0],
            (
                10,
                Median {
                    value: Some(2.0),
                    runs: 3
                }
            )
        );
        assert_eq!(
            s.at_generation[1],
            (
                50,
                Median {
                    value: Some(3.0),
                    runs: 2
                }
            )
        );
        assert_eq!(
            s.at_generation[2],
            (
                100,
                Median {
                    value: None,
                    runs: 0
                }
            )
        );
        assert_eq!(s.seconds_per_generation, 2.0);
        // 30 s: a ran 10 s only; b (100 s) and c (180 s) did.
        assert_eq!(
            s.at_seconds[0].1,
            Median {
                value: Some(3.0),
                runs: 2
            }
        );
        assert_eq!(
            s.at_seconds[1].1,
            Median {
                value: Some(4.0),
                runs: 1
            }
        );
        assert_eq!(s.at_seconds[2].1.value, None);
        assert_eq!(s.final_best, 2.0);

        let table = markdown(std::slice::from_ref(&s));
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].contains("best @ gen 50") && !lines[0].contains("gen 100"));
        assert_eq!(
            lines[2],
            "| g | 3 | 10–60 | 2.000 | 3.000 (2/3) | 2.000 | 3.000 (2/3) | 4.000 (1/3) | — | 2.000 |"
        );
        let csv = csv(&[s]);
        let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
        assert_eq!(rows[0].len(), rows[1].len());
        let col = |name: &str| rows[1][rows[0].iter().position(|h| *h == name).unwrap()];
        assert_eq!(col("best_gen_50"), "3");
        assert_eq!(col("best_gen_50_runs"), "2");
        assert_eq!(col("best_gen_400"), "");
        assert_eq!(col("best_so_far_120s"), "4");
    }

    #[test]
    fn median_lines_span_what_every_run_reached() {
        let g = Group {
            name: "g".into(),
            runs: vec![
                run("a", &[1.0, 2.0, 3.0], &[1.0, 1.0, 1.0]),
                run("b", &[3.0, 4.0], &[2.0, 2.0]),
            ],
        };
        assert_eq!(median_per_generation(&g), [2.0, 3.0]);
        // From 2 s (b's first generation) to 3 s (a's end).
        assert_eq!(median_per_second(&g), [(2.0, 2.5), (3.0, 2.5), (3.0, 3.0)]);
    }

    #[test]
    fn renders_both_panels_with_legend() {
        let rising = |k: f64| {
            (1..=80)
                .map(|g| 4.0 * (1.0 - (-(g as f64) / k).exp()))
                .collect::<Vec<_>>()
        };
        let groups = vec![
            Group {
                name: "3x5→3x3".into(),
                runs: vec![
                    run("a", &rising(20.0), &[0.1; 80]),
                    run("b", &rising(25.0), &[0.12; 80]),
                ],
            },
            Group {
                name: "16x48→9x9".into(),
                runs: vec![run("c", &rising(10.0), &[2.0; 80])],
            },
        ];
        let fig = render(&groups, &CompareOptions::default()).unwrap();
        assert_eq!(png_size(&fig.png), (2600, 1160));
        assert!(distinct_colours(&fig.png) > 50);
        for text in [
            "generation",
            "wall-clock seconds",
            "best-so-far fitness",
            "3x5→3x3 (2 runs, median)",
            "16x48→9x9 (1 run)",
        ] {
            assert!(fig.svg.contains(text), "missing {text:?}");
        }
        assert!(matches!(
            render(&[], &CompareOptions::default()),
            Err(FigureError::NoData(_))
        ));
    }
}

//! The runs being compared: reading a run directory's progress, and grouping
//! runs by `--label` rules or by their substrate.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use vivae_lab::config::Config;
use vivae_lab::error::{Error, Result};
use vivae_lab::io::bad_input;
use vivae_lab::rundir::{self, files};
use vivae_lab::tasks::read_config;

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

/// The group name of a run without a label: the substrate of a task with one
/// ([`substrate_label`]), else its task and strategy, e.g. `cartpole (nsga2)`.
pub fn run_label(config: &Config) -> String {
    if vivae_lab::tasks::has_substrate(config) {
        substrate_label(config)
    } else {
        let strategy = vivae_lab::search::StrategyConfig::of(config).kind;
        let (task, strategy) = (&config.experiment.task, strategy.name());
        format!("{task} ({strategy})")
    }
}

/// The substrate of a run, e.g. `3x5→3x3`, with distance rays and training
/// resolutions when it has them.
pub fn substrate_label(config: &Config) -> String {
    let s = &config.surface_sensors;
    let mut label = format!("{}x{}", s.rings, s.angles);
    if config.distance_sensors.rays > 0 {
        let _ = write!(label, "+{}rays", config.distance_sensors.rays);
    }
    let _ = write!(label, "→{}", config.substrate.neurons);
    let sub = &config.substrate;
    if !sub.train_neurons.is_empty() || !sub.train_sensors.is_empty() {
        let list = |g: &[vivae_lab::controller::substrate::PolarGrid]| {
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
            None => run_label(&read_config(&dir.join(files::CONFIG))?),
        });
    }
    Ok(group(runs, &names))
}

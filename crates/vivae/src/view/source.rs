//! What `vivae view` shows: a run directory, a genome or a scenario, and the
//! run's history as it grows.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use serde::Serialize;

use crate::report_html::{GenerationRow, read_generation_rows};
use vivae_lab::config::Config;
use vivae_lab::io::{DEFAULT_SCENARIO, DEFAULT_SCENARIO_NAME, bad_input, read_config, read_text};
use vivae_lab::rundir::{self, Champion, GenerationBest, files, read_champion};

/// Most extra scenarios offered from `--scenarios`.
const MAX_SCENARIOS: usize = 200;
/// Largest scenario file offered from `--scenarios`, in bytes.
const MAX_SCENARIO_BYTES: u64 = 16 << 20;

/// What kind of thing the viewer was started on.
#[derive(Debug, Clone, PartialEq)]
pub enum SourceKind {
    /// A run directory (followed while it runs).
    Run(PathBuf),
    /// A champion genome file.
    Genome(PathBuf),
    /// A scenario file (robots driven by hand).
    Scenario(PathBuf),
    /// Nothing: the embedded scenario.
    Default,
}

/// The viewer's fixed inputs.
#[derive(Debug, Clone)]
pub struct Source {
    /// What was given.
    pub kind: SourceKind,
    /// The config controllers are built with (the run's, else the default).
    pub config: Config,
    /// Offered scenarios as (name, SVG text); the first is the source's own.
    pub scenarios: Vec<(String, String)>,
    /// The genome given as a file, if any.
    pub genome: Option<Champion>,
}

impl Source {
    /// Loads `path` (run directory, genome JSON or scenario SVG) and the extra scenario folder.
    pub fn load(path: Option<&Path>, extra: Option<&Path>) -> vivae_lab::Result<Source> {
        let default = (
            DEFAULT_SCENARIO_NAME.to_string(),
            DEFAULT_SCENARIO.to_string(),
        );
        let mut source = match path {
            None => Source {
                kind: SourceKind::Default,
                config: Config::default(),
                scenarios: vec![default.clone()],
                genome: None,
            },
            Some(p) if p.is_dir() => Source::from_run_dir(p)?,
            Some(p) => Source::from_file(p, &default)?,
        };
        if matches!(source.kind, SourceKind::Run(_)) {
            source.add_training_maps()?;
        }
        if source.scenarios[0].1 != default.1 {
            source.scenarios.push(default);
        }
        if let Some(dir) = extra {
            source.scenarios.extend(scenario_folder(dir)?);
        }
        Ok(source)
    }

    /// A run directory: its config and scenario.
    fn from_run_dir(p: &Path) -> vivae_lab::Result<Source> {
        let config = read_config(&p.join(files::CONFIG))?;
        let scenario = read_text(&p.join(files::SCENARIO))?;
        // A run that has not finished its first generation has no champion yet.
        Ok(Source {
            kind: SourceKind::Run(p.to_path_buf()),
            config,
            scenarios: vec![(format!("{} (the run's)", files::SCENARIO), scenario)],
            genome: None,
        })
    }

    /// A scenario SVG (with robots) or else a genome file, shown on `default`.
    fn from_file(p: &Path, default: &(String, String)) -> vivae_lab::Result<Source> {
        let ext = p
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if ext.as_deref() == Some("svg") {
            let loaded = vivae_lab::io::load_scenario(Some(p))?;
            loaded
                .scenario
                .require_robots()
                .map_err(|e| bad_input(vivae_lab::io::one_line(&e.to_string())))?;
            let text = loaded.text;
            Ok(Source {
                kind: SourceKind::Scenario(p.to_path_buf()),
                config: Config::default(),
                scenarios: vec![(file_name(p), text)],
                genome: None,
            })
        } else {
            // The champion's own recorded config rebuilds its controller
            // (substrate, sensors, physics), as `vivae replay` does.
            let (champion, config, _) = vivae_lab::rundir::load_genome_source(p)?;
            Ok(Source {
                kind: SourceKind::Genome(p.to_path_buf()),
                config,
                scenarios: vec![default.clone()],
                genome: Some(champion),
            })
        }
    }

    /// A multi-map run also offers its other training maps (the first is scenario.svg).
    fn add_training_maps(&mut self) -> vivae_lab::Result<()> {
        for (k, map) in self.config.experiment.scenarios.iter().enumerate().skip(1) {
            let text = read_text(Path::new(map))?;
            let name = Path::new(map)
                .file_name()
                .map_or_else(|| map.clone(), |n| n.to_string_lossy().into_owned());
            self.scenarios
                .push((format!("{name} (training map {})", k + 1), text));
        }
        Ok(())
    }

    /// One line saying what is shown.
    pub fn describe(&self) -> String {
        match &self.kind {
            SourceKind::Run(p) => format!("showing run {}", p.display()),
            SourceKind::Genome(p) => format!("showing genome {}", p.display()),
            SourceKind::Scenario(p) => format!("showing scenario {}", p.display()),
            SourceKind::Default => "showing the embedded road scenario".into(),
        }
    }

    /// The run directory, if the source is one.
    pub fn run_dir(&self) -> Option<&Path> {
        match &self.kind {
            SourceKind::Run(p) => Some(p),
            _ => None,
        }
    }

    /// The run's history now (an empty one for other sources).
    pub fn snapshot(&self) -> RunSnapshot {
        let mut snap = RunSnapshot::default();
        if let Some(g) = &self.genome {
            snap.champion = Some(g.clone());
        }
        if let Some(dir) = self.run_dir() {
            // A run being written may be read half-way; the next poll sees the rest.
            snap.champion = read_champion(&dir.join(files::CHAMPION)).ok();
            snap.best =
                rundir::read_best_genomes(&dir.join(files::BEST_GENOMES)).unwrap_or_default();
            snap.generations =
                read_generation_rows(&dir.join(files::GENERATIONS)).unwrap_or_default();
            snap.total = Some(self.config.experiment.generations);
            if let Ok(c) = read_config(&dir.join(files::CONFIG)) {
                snap.total = Some(c.experiment.generations);
            }
        }
        snap
    }

    /// What changes when a running evolution writes a generation (for polling).
    pub fn stamp(&self) -> Vec<(u64, Option<SystemTime>)> {
        let Some(dir) = self.run_dir() else {
            return Vec::new();
        };
        [files::GENERATIONS, files::BEST_GENOMES, files::CHAMPION]
            .iter()
            .map(|n| {
                std::fs::metadata(dir.join(n))
                    .map(|m| (m.len(), m.modified().ok()))
                    .unwrap_or((0, None))
            })
            .collect()
    }
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| p.display().to_string())
}

/// Every `.svg` file in `dir`, sorted by name (read now; parsed when chosen).
fn scenario_folder(dir: &Path) -> vivae_lab::Result<Vec<(String, String)>> {
    let entries = std::fs::read_dir(dir).map_err(|e| {
        bad_input(format!(
            "{}: {}",
            dir.display(),
            vivae_lab::io::io_reason(&e)
        ))
    })?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|e| e.eq_ignore_ascii_case("svg"))
                && p.metadata()
                    .is_ok_and(|m| m.is_file() && m.len() <= MAX_SCENARIO_BYTES)
        })
        .collect();
    paths.sort();
    paths.truncate(MAX_SCENARIOS);
    Ok(paths
        .iter()
        .filter_map(|p| read_text(p).ok().map(|t| (file_name(p), t)))
        .collect())
}

/// A run's history as last read.
#[derive(Debug, Clone, Default)]
pub struct RunSnapshot {
    /// The best genome so far.
    pub champion: Option<Champion>,
    /// Each generation's best genome and species.
    pub best: Vec<GenerationBest>,
    /// Rows of `generations.csv`.
    pub generations: Vec<GenerationRow>,
    /// Generations the run will have.
    pub total: Option<u32>,
}

/// What a page is told about the run's history (no genomes).
#[derive(Debug, Serialize)]
pub struct ProgressMsg<'a> {
    /// Always `progress`.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// Rows of `generations.csv`.
    pub generations: &'a [GenerationRow],
    /// Per generation, `[species id, members]`.
    pub species: Vec<&'a [(u32, usize)]>,
    /// Generations whose best genome can be watched.
    pub genomes: Vec<u32>,
    /// The champion's generation and fitness.
    pub champion: Option<(u32, f64)>,
    /// Generations the run will have.
    pub total: Option<u32>,
}

impl RunSnapshot {
    /// The page's view of this history.
    pub fn progress(&self) -> ProgressMsg<'_> {
        ProgressMsg {
            kind: "progress",
            generations: &self.generations,
            species: self.best.iter().map(|b| b.species.as_slice()).collect(),
            genomes: self.best.iter().map(|b| b.generation).collect(),
            champion: self.champion.as_ref().map(|c| (c.generation, c.fitness)),
            total: self.total,
        }
    }
}

/// A shared, cheaply cloned history.
pub type SharedSnapshot = Arc<RunSnapshot>;

//! What `vivae view` shows: a run directory, a genome or a scenario, and the
//! run's history as it grows.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use serde::Serialize;

use vivae_lab::config::Config;
use vivae_lab::io::{DEFAULT_SCENARIO, DEFAULT_SCENARIO_NAME, bad_input, read_text};
use vivae_lab::rundir::GenerationRow;
use vivae_lab::rundir::{self, Champion, GenerationBest, files};
use vivae_lab::search::files::{self as strategy_files, ArchiveLine, FrontLine, Member};
use vivae_lab::tasks::read_champion;
use vivae_lab::tasks::read_config;

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
    /// Per offered scenario, why it cannot be driven (no robots, not a
    /// scenario), or `None`: the page lists these greyed out with the reason.
    pub unusable: Vec<Option<String>>,
    /// The genome given as a file, if any.
    pub genome: Option<Champion>,
    /// The archive or front member that drives when a page opens
    /// (`--elite`, `--front`), instead of the champion.
    pub start: Option<Member>,
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
                unusable: Vec::new(),
                genome: None,
                start: None,
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
        source.unusable = source
            .scenarios
            .iter()
            .map(|(name, text)| unusable(name, text))
            .collect();
        Ok(source)
    }

    /// A note for the terminal when some offered scenarios cannot be driven.
    pub fn unusable_note(&self) -> Option<String> {
        let names: Vec<&str> = self
            .scenarios
            .iter()
            .zip(&self.unusable)
            .filter(|(_, u)| u.is_some())
            .map(|((n, _), _)| n.as_str())
            .collect();
        (!names.is_empty()).then(|| {
            format!(
                "note: {} of {} scenarios cannot be driven (no robots, or not a scenario) and are listed greyed out: {}",
                names.len(),
                self.scenarios.len(),
                names.join(", ")
            )
        })
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
            unusable: Vec::new(),
            genome: None,
            start: None,
        })
    }

    /// A scenario SVG (with robots) or else a genome file, shown on `default`.
    fn from_file(p: &Path, default: &(String, String)) -> vivae_lab::Result<Source> {
        let ext = p
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if ext.as_deref() == Some("svg") {
            let loaded = vivae_lab::tasks::scenarios::load_scenario(Some(p))?;
            loaded
                .scenario
                .require_robots()
                .map_err(|e| bad_input(vivae_lab::io::one_line(&e.to_string())))?;
            let text = loaded.text;
            Ok(Source {
                kind: SourceKind::Scenario(p.to_path_buf()),
                config: Config::default(),
                scenarios: vec![(file_name(p), text)],
                unusable: Vec::new(),
                genome: None,
                start: None,
            })
        } else {
            // The champion's own recorded config rebuilds its controller
            // (substrate, sensors, physics), as `vivae replay` does.
            let (champion, config, _) = vivae_lab::tasks::load_genome_source(p)?;
            Ok(Source {
                kind: SourceKind::Genome(p.to_path_buf()),
                config,
                scenarios: vec![default.clone()],
                unusable: Vec::new(),
                genome: Some(champion),
                start: None,
            })
        }
    }

    /// A multi-map run offers each of its training maps, named as such (the
    /// first is the run's `scenario.svg`).
    fn add_training_maps(&mut self) -> vivae_lab::Result<()> {
        let maps = &self.config.experiment.scenarios;
        for (k, map) in maps.iter().enumerate() {
            let name = Path::new(map)
                .file_name()
                .map_or_else(|| map.clone(), |n| n.to_string_lossy().into_owned());
            let label = format!("{name} (training map {} of {})", k + 1, maps.len());
            if k == 0 {
                self.scenarios[0].0 = label;
            } else {
                self.scenarios.push((label, read_text(Path::new(map))?));
            }
        }
        Ok(())
    }

    /// Makes `member` (of the run's archive or front) drive when a page
    /// opens; refused, naming the file, unless the run has it.
    pub fn start_with(&mut self, member: Member) -> vivae_lab::Result<()> {
        let flag = match member {
            Member::Elite(c) => format!("--elite {c}"),
            Member::Front(n) => format!("--front {n}"),
        };
        let Some(dir) = self.run_dir() else {
            return Err(bad_input(format!(
                "{flag}: needs a run directory ({})",
                self.describe()
            )));
        };
        strategy_files::read_member(dir, member)?;
        self.start = Some(member);
        Ok(())
    }

    /// Names of the behaviour coordinates of the archive's elites in `snap`.
    pub fn behaviour_names(&self, snap: &RunSnapshot) -> Vec<String> {
        let dims = snap.elites.first().map_or(0, |e| e.behaviour.len());
        vivae_lab::tasks::behaviours::coordinate_names(&self.config, dims)
    }

    /// Names of the objectives of the run's Pareto front (a minimised one without its `-`).
    pub fn objective_names(&self) -> Vec<String> {
        vivae_lab::search::front_objective_names(&self.config)
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
            snap.generations = vivae_lab::rundir::read_generations(&dir.join(files::GENERATIONS))
                .unwrap_or_default();
            snap.total = Some(self.config.experiment.generations);
            if let Ok(c) = read_config(&dir.join(files::CONFIG)) {
                snap.total = Some(c.experiment.generations);
            }
            snap.elites = strategy_files::read_archive(dir)
                .ok()
                .flatten()
                .unwrap_or_default();
            snap.front = strategy_files::read_front(dir)
                .ok()
                .flatten()
                .unwrap_or_default();
        }
        snap
    }

    /// What changes when a running evolution writes a generation (for polling).
    pub fn stamp(&self) -> Vec<(u64, Option<SystemTime>)> {
        let Some(dir) = self.run_dir() else {
            return Vec::new();
        };
        // The strategies' own files (an archive, a front) from their entries.
        let strategies = vivae_lab::search::entries();
        let own = strategies.iter().flat_map(|e| e.files.iter().copied());
        [files::GENERATIONS, files::BEST_GENOMES, files::CHAMPION]
            .into_iter()
            .chain(own)
            .map(|n| {
                std::fs::metadata(dir.join(n))
                    .map(|m| (m.len(), m.modified().ok()))
                    .unwrap_or((0, None))
            })
            .collect()
    }
}

/// Why scenario `name` cannot be driven in the viewer, if it cannot.
pub(crate) fn unusable(name: &str, text: &str) -> Option<String> {
    let reason = |e: &dyn std::fmt::Display| vivae_lab::io::one_line(&e.to_string());
    match vivae_sim::Scenario::from_svg(text, name, &vivae_sim::LoadOptions::default()) {
        Ok(s) if s.robots.is_empty() => Some("no robots".into()),
        Ok(_) => None,
        Err(e) => Some(reason(&e)),
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
    /// A map-elites run's archive, cell by cell.
    pub elites: Vec<ArchiveLine>,
    /// An nsga2 run's Pareto front, fittest first.
    pub front: Vec<FrontLine>,
}

/// An archive's elite as a page lists it (no genome).
#[derive(Debug, Serialize)]
pub struct EliteMsg<'a> {
    /// Its cell.
    pub cell: usize,
    /// Its fitness.
    pub fitness: f64,
    /// Generation it was evaluated in.
    pub generation: u32,
    /// Its behaviour descriptor.
    pub behaviour: &'a [f64],
}

/// A front member as a page lists it (no genome).
#[derive(Debug, Serialize)]
pub struct FrontMsg<'a> {
    /// Its index in the front (0 = the fittest).
    pub member: usize,
    /// Its fitness.
    pub fitness: f64,
    /// Its objectives as measured.
    pub objectives: &'a [f64],
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
    /// The archive's elites (map-elites runs).
    pub elites: Vec<EliteMsg<'a>>,
    /// The Pareto front (nsga2 runs).
    pub front: Vec<FrontMsg<'a>>,
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
            elites: (self.elites.iter())
                .map(|e| EliteMsg {
                    cell: e.cell,
                    fitness: e.fitness,
                    generation: e.generation,
                    behaviour: &e.behaviour,
                })
                .collect(),
            front: (self.front.iter())
                .map(|f| FrontMsg {
                    member: f.member,
                    fitness: f.fitness,
                    objectives: &f.objectives,
                })
                .collect(),
        }
    }
}

/// A shared, cheaply cloned history.
pub type SharedSnapshot = Arc<RunSnapshot>;

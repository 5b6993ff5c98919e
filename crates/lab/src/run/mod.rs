//! The evolution driver: run directories, per-generation records, checkpoints.
//!
//! A run directory holds `config.toml`, `scenario.svg`, `generations.csv`,
//! `population.csv`, `timing.csv`, `champion.json`, `checkpoints/` and, at the
//! end, `figures/`. CSV files are appended once per generation; a checkpoint
//! records their lengths, so resuming truncates whatever a crash left after
//! the last checkpoint and the finished files are byte-identical to an
//! uninterrupted run's. Wall-clock times live only in `timing.csv`, the one
//! file that is allowed to differ between two runs of the same config.

mod background;
mod checkpoint;
pub mod prepare;
mod solver;

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use crate::search::Search;
use crate::search::StrategyConfig;
use crate::search::files::{extra_fields, write_outputs};
use vivae_neat::driver::{
    CheckpointState, Checkpointer, DriverError, Evaluator, Evolution, GenerationReport, HookError,
    Observer, ParallelEvaluator, Reusing, StopCriteria, StopReason,
};
use vivae_neat::driver::{Evaluation, Strategy};
use vivae_neat::{Genome, Population, Precision, stats};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{bad_input, fnv1a, write_atomic};
use crate::rundir::{
    BestLine, Champion, GenerationRecord, GenerationRow, POPULATION_HEADER, RunLock, TIMING_HEADER,
    append, copy_maps, files, latest_checkpoint, population_rows, read_best_genomes,
    remove_abandoned_builds, remove_stale_temporaries, truncate, truncate_lines,
};
use crate::tasks::maps::{TrainingMap, load_run};
use crate::tasks::{RunTask, StoredTarget, TargetProgress, config_text};
use background::CheckpointWriter;
use checkpoint::*;
pub use checkpoint::{population_from_checkpoint, population_from_checkpoint_text};
use solver::champion;

/// Generations whose best individual gets a trajectory figure (besides the champion).
pub const FIGURE_GENERATIONS: [u32; 2] = [1, 10];

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// All generations done.
    Finished,
    /// Stopped by the user after a generation; a checkpoint was written.
    Interrupted,
}

/// A run in a run directory.
pub struct Run {
    dir: PathBuf,
    /// Held while the run exists: one writer per run directory.
    _lock: RunLock,
    config: Config,
    task: Box<dyn RunTask>,
    search: Search,
    progress: Progress,
    pool: Arc<rayon::ThreadPool>,
}

impl Run {
    /// Creates a new run directory of `task` and the initial checkpoint.
    ///
    /// `scenario_text` (the first map's) is copied to `scenario.svg` and
    /// `config.experiment.scenario` rewritten to point at that copy, so that
    /// `config.toml` alone re-runs it; `None` for a task without maps (no
    /// `scenario.svg`). With several training maps (`maps`, from
    /// [`crate::tasks::maps::load`]; empty for a single-scenario run) every
    /// map is copied to `scenarios/` with a manifest of their hashes and
    /// `experiment.scenarios` is rewritten to name the copies. `init` is a
    /// population to start from (retrain) instead of a fresh one, for a
    /// task whose controller is a substrate network re-sampled
    /// ([`crate::tasks::TaskEntry::substrate`]).
    pub fn create_task(
        dir: &Path,
        mut config: Config,
        task: Box<dyn RunTask>,
        scenario_text: Option<&str>,
        maps: &[TrainingMap],
        init: Option<Population>,
        force: bool,
    ) -> Result<Run> {
        crate::tasks::check(&config).map_err(|e| bad_input(format!("config: {e}")))?;
        let retrains = task.entry().substrate;
        if task.entry().name != config.experiment.task.name() || (!retrains && init.is_some()) {
            return Err(bad_input(format!(
                "experiment.task = {}: the run was given another task{}",
                config.experiment.task.name(),
                if init.is_some() {
                    " or a starting population"
                } else {
                    ""
                }
            )));
        }
        let space = task.behaviour_space(&config);
        let metrics = task.entry().metric_names;
        let search = Search::new(&config, task.genome_spec(), &space, init.as_ref(), metrics)?;
        // The run is built in a temporary sibling and renamed into place once its
        // first checkpoint exists: a kill or an error before that leaves no
        // directory that could neither be resumed nor re-run without --force.
        let old = crate::rundir::replace::check_target(dir, force, &strategy_files())?;
        let (tmp, lock) = temporary_sibling(dir)?;
        let progress = Progress {
            scenario_fnv: scenario_text.map(|t| fnv1a(t.as_bytes())),
            maps_fnv: (!maps.is_empty()).then(|| {
                maps.iter()
                    .map(|m| fnv1a(m.loaded.text.as_bytes()))
                    .collect()
            }),
            generations_len: generations_header(&config).len() as u64,
            target: StoredTarget::start(task.as_ref()),
            ..Progress::start(search.generation())
        };
        let filled = copy_maps(&tmp, &mut config, maps)
            .and_then(|()| fill_new_run(&tmp, &mut config, scenario_text, &search, &progress));
        let placed = filled.and_then(|()| crate::rundir::replace::swap_in(&tmp, dir, old));
        if let Err(e) = placed {
            let _ = fs::remove_dir_all(&tmp);
            return Err(e);
        }
        Ok(Run {
            dir: dir.to_path_buf(),
            _lock: lock,
            pool: thread_pool(config.run.threads)?,
            config,
            task,
            search,
            progress,
        })
    }

    /// Opens an existing run at its newest checkpoint; `generations` extends (or
    /// shortens, if not yet reached) the total. Files written after that
    /// checkpoint are truncated back to it.
    pub fn resume(dir: &Path, generations: Option<u32>, threads: Option<usize>) -> Result<Run> {
        Run::resume_in(dir, generations, threads, None)
    }

    /// [`Run::resume`], refused (nothing changed) when `precision` is given
    /// and is not the one the run's checkpoint records: a run's bits depend
    /// on it, so a run resumes in the precision it started with.
    pub fn resume_in(
        dir: &Path,
        generations: Option<u32>,
        threads: Option<usize>,
        precision: Option<Precision>,
    ) -> Result<Run> {
        let path = latest_checkpoint(dir)?;
        // Locked before anything is read: another writer may be mid-generation.
        let lock = RunLock::acquire(dir)?;
        let mut cp = decode_checkpoint(&path)?;
        let recorded = cp.config.experiment.precision;
        if let Some(p) = precision.filter(|&p| p != recorded) {
            return Err(bad_input(format!(
                "precision {p}: {} computes in {recorded} precision (its checkpoint records it); \
                 a run resumes in the precision it started with: drop the setting, or start a new run",
                dir.display()
            )));
        }
        check_config_unchanged(dir, &path, &cp.config)?;
        extend_generations(&mut cp, &path, generations)?;
        let maps = load_run(dir, &cp.config, cp.progress.maps_fnv.as_deref())?;
        // A task without maps has no scenario.svg.
        let scenario = (crate::tasks::maps::uses_maps(&cp.config))
            .then(|| crate::tasks::scenarios::load_scenario(Some(&dir.join(files::SCENARIO))))
            .transpose()?;
        let task = crate::tasks::build(&cp.config, &maps)?;
        // Everything is validated before anything in the directory changes.
        let search = validate_progress(&path, &cp, task.as_ref())?;
        if let Some(h) = cp.progress.scenario_fnv
            && scenario.is_none_or(|s| h != fnv1a(s.text.as_bytes()))
        {
            return Err(Error::Checkpoint {
                path: dir.join(files::SCENARIO),
                reason: format!(
                    "changed since the run started (it does not match {})",
                    path.display()
                ),
            });
        }
        check_csv_prefixes(dir, &path, &cp.progress)?;
        remove_stale_temporaries(dir);
        for (name, len) in [
            (files::GENERATIONS, cp.progress.generations_len),
            (files::POPULATION, cp.progress.population_len),
            (files::TIMING, cp.progress.timing_len),
        ] {
            truncate(&dir.join(name), len)?;
        }
        truncate_lines(&dir.join(files::BEST_GENOMES), cp.progress.done)?;
        // The resolved config records the (possibly extended) total.
        write_atomic(&dir.join(files::CONFIG), config_text(&cp.config).as_bytes())?;
        Ok(Run {
            dir: dir.to_path_buf(),
            _lock: lock,
            // A thread count given at resume changes speed, not results: not recorded.
            pool: thread_pool(threads.unwrap_or(cp.config.run.threads))?,
            config: cp.config,
            task,
            search,
            progress: cp.progress,
        })
    }

    /// The run directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The resolved configuration.
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// What the run's genomes are evaluated on, whichever the task.
    pub fn task(&self) -> &dyn RunTask {
        self.task.as_ref()
    }

    /// The run's progress towards its task's target (evaluations, when
    /// first reached); none for a task without one.
    pub fn target_progress(&self) -> Option<&TargetProgress> {
        self.progress.target.get()
    }

    /// Whether the run has nothing left to do: every generation done, or
    /// its task's target reached.
    pub fn finished(&self) -> bool {
        self.done() >= self.config.experiment.generations
            || self
                .target_progress()
                .is_some_and(|m| m.solved_at.is_some())
    }

    /// Generations done so far.
    pub fn done(&self) -> u32 {
        self.progress.done
    }

    /// The search strategy (ready for the next generation).
    pub fn search(&self) -> &Search {
        &self.search
    }

    /// The NEAT population (ready for the next generation) of a strategy that breeds one.
    pub fn population(&self) -> Option<&Population> {
        self.search.population()
    }

    /// Evolves until the configured number of generations or until `stop` is set
    /// (checked after each generation, which is finished first).
    pub fn run(
        &mut self,
        stop: &AtomicBool,
        on_generation: impl FnMut(&GenerationRecord),
    ) -> Result<Outcome> {
        let pool = Arc::clone(&self.pool);
        let evaluator = ParallelEvaluator::with_pool(self.task.clone(), &pool);
        self.run_on(evaluator, stop, on_generation)
    }

    /// The worker threads this run evaluates on (for an evaluator of the program's own).
    pub fn pool(&self) -> Arc<rayon::ThreadPool> {
        Arc::clone(&self.pool)
    }

    /// [`Run::run`] on a given evaluator (e.g. one that spreads each
    /// generation over the processes of an MPI job).
    pub fn run_on<E: Evaluator>(
        &mut self,
        evaluator: E,
        stop: &AtomicBool,
        on_generation: impl FnMut(&GenerationRecord),
    ) -> Result<Outcome> {
        let total = self.config.experiment.generations;
        if self.finished() {
            return Ok(Outcome::Finished);
        }
        // A task whose evaluations depend on the genome alone runs each
        // distinct genome once: the same bits, less work.
        let evaluator = Reusing::new(evaluator, self.task.context_free());
        let mut evolution = Evolution::resume(self.search.clone(), evaluator, self.progress.done);
        // A run with a target also stops once it is reached: the recorder raises `halt` then,
        // or when `stop` is set.
        let halt = AtomicBool::new(false);
        let mut recorder = Recorder {
            dir: &self.dir,
            config: &self.config,
            task: self.task.as_ref(),
            progress: &mut self.progress,
            total,
            started: Instant::now(),
            last_best: read_best_genomes(&self.dir.join(files::BEST_GENOMES))?
                .pop()
                .map(|b| (b.generation, b.genome)),
            halt: (stop, &halt),
            on_generation,
            writer: CheckpointWriter::default(),
            champion_text: None,
        };
        let flag = if self.task.has_target() { &halt } else { stop };
        let criteria = StopCriteria::generations(total).or_interrupt(flag);
        let result = evolution.run_with(&criteria, &mut recorder);
        // A run that stops writes its last checkpoint itself; one that
        // fails may leave one under way, which must land (or say why not).
        let written = recorder.writer.wait();
        self.search = evolution.into_strategy();
        let reason = result.map_err(driver_error)?;
        written?;
        match reason {
            StopReason::Interrupted if stop.load(Ordering::SeqCst) => Ok(Outcome::Interrupted),
            _ => Ok(Outcome::Finished),
        }
    }

    /// The best individual of each figure generation reached.
    pub fn figure_genomes(&self) -> impl Iterator<Item = (u32, f64, &Genome)> {
        self.progress
            .figure_genomes
            .iter()
            .map(|(g, f, genome)| (*g, *f, genome))
    }

    /// The champion (best ever) with its run-relative generation.
    pub fn champion(&self) -> Option<Champion> {
        champion(&self.search, &self.progress, &self.config)
    }
}

/// A fresh, locked temporary sibling of `dir` to build a new run in (the
/// lock is on the directory itself, so it survives the rename into place).
fn temporary_sibling(dir: &Path) -> Result<(PathBuf, RunLock)> {
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    crate::io::create_dirs_for(&parent, dir)?;
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into());
    remove_abandoned_builds(&parent, &name);
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    if tmp.exists() {
        fs::remove_dir_all(&tmp).map_err(Error::io("clear", &tmp))?;
    }
    fs::create_dir(&tmp).map_err(Error::io("create", dir))?;
    match RunLock::acquire(&tmp) {
        Ok(lock) => Ok((tmp, lock)),
        Err(e) => {
            let _ = fs::remove_dir_all(&tmp);
            Err(e)
        }
    }
}

/// The driver's error as ours; an error of our own observer comes back unchanged.
fn driver_error(e: DriverError) -> Error {
    match e {
        DriverError::Hook(hook) => match hook.downcast::<Error>() {
            Ok(ours) => *ours,
            Err(other) => Error::Evolution(other.to_string()),
        },
        other => Error::Evolution(other.to_string()),
    }
}

/// Writes a run directory's per-generation files and its checkpoints: the
/// observer and checkpointer of a run.
struct Recorder<'a, F> {
    dir: &'a Path,
    config: &'a Config,
    task: &'a dyn RunTask,
    progress: &'a mut Progress,
    total: u32,
    /// When the generation under way started.
    started: Instant,
    /// The last line written to `best-genomes.jsonl`: (generation, genome).
    last_best: Option<(u32, Genome)>,
    /// The user's stop flag, and the flag that stops a run with a target (raised by
    /// either the user's or the target being reached).
    halt: (&'a AtomicBool, &'a AtomicBool),
    on_generation: F,
    /// Writes the checkpoints of generations that do not stop the run.
    writer: CheckpointWriter,
    /// What this recorder last wrote to `champion.json`.
    champion_text: Option<String>,
}

impl<F: FnMut(&GenerationRecord)> Recorder<'_, F> {
    /// Appends one generation's rows and rewrites the champion.
    fn record(&mut self, report: &GenerationReport<'_, Search>) -> Result<()> {
        let seconds = self.started.elapsed().as_secs_f64();
        let search = report.strategy;
        let generation = report.generation;
        let fitnesses = search.fitnesses(report.evaluations);
        let sorted = stats::sorted_descending(&fitnesses);
        let (best_genome, best) = search
            .champion()
            .map(|(g, f)| (g.clone(), f))
            .expect("an evaluated population has a champion");
        let record = self.measure(report, &fitnesses, &sorted, (&best_genome, best), seconds)?;
        self.append_best_line(search, generation, best, best_genome)?;
        let own = self.tell_task(search, generation, report.evaluations);
        let p = &mut *self.progress;
        let row = record.generations_row();
        let row = format!(
            "{}{}{own}\n",
            row.trim_end_matches('\n'),
            extra_fields(search)
        );
        p.generations_len = append(&self.dir.join(files::GENERATIONS), &row)?;
        p.population_len = append(
            &self.dir.join(files::POPULATION),
            &population_rows(generation, &sorted),
        )?;
        p.timing_len = append(&self.dir.join(files::TIMING), &record.timing_row())?;
        if let Some(champion) = champion(search, self.progress, self.config) {
            let text = serde_json::to_string_pretty(&champion).map_err(|e| Error::Serialize {
                what: "champion",
                reason: e.to_string(),
            })? + "\n";
            // Most generations keep the champion: its file is synced only when it changes.
            if self.champion_text.as_ref() != Some(&text) {
                write_atomic(&self.dir.join(files::CHAMPION), text.as_bytes())?;
                self.champion_text = Some(text);
            }
        }
        self.progress.done = generation;
        (self.on_generation)(&record);
        Ok(())
    }

    /// The generation's record: fitness statistics of `sorted` (best first),
    /// the best genome's substrate, and the time it took.
    fn measure(
        &self,
        report: &GenerationReport<'_, Search>,
        fitnesses: &[f64],
        sorted: &[f64],
        (best_genome, best): (&Genome, f64),
        seconds: f64,
    ) -> Result<GenerationRecord> {
        let search = report.strategy;
        let stats = report.stats;
        let (best_links, possible_links) = self.task.links(best_genome)?;
        let n = sorted.len();
        let (mean, median) = stats::mean(fitnesses)
            .zip(stats::median_of_sorted(sorted))
            .expect("an evaluated population has fitnesses");
        // Only the evaluations run simulated anything; reused ones were copied.
        let run: Vec<Evaluation> = (report.evaluations.iter().enumerate())
            .filter(|(i, _)| report.reused.binary_search(i).is_err())
            .map(|(_, e)| e.clone())
            .collect();
        let robot_steps = self.task.robot_steps_of(&run);
        let row = GenerationRow {
            generation: report.generation,
            best,
            mean,
            median,
            worst: sorted[n - 1],
            species: stats.species,
            mean_cppn_nodes: stats.mean_nodes,
            mean_cppn_links: stats.mean_links,
            best_substrate_links: best_links,
            possible_substrate_links: possible_links,
        };
        Ok(GenerationRecord {
            row,
            total: self.total,
            seconds,
            robot_steps_per_second: robot_steps / seconds.max(1e-9),
            reused: report.reused.len(),
            best_ever: search.best_ever().map_or(best, |b| b.fitness),
        })
    }

    /// The task's own fields of `generations.csv` for `generation` (none
    /// for a task without a target); raises the halt flag once the target is
    /// reached or the user asked to stop.
    fn tell_task(
        &mut self,
        search: &Search,
        generation: u32,
        evaluations: &[Evaluation],
    ) -> String {
        solver::tell_target(self.progress, self.task, search, generation, evaluations);
        let Some(target) = self.progress.target.get_mut() else {
            return String::new();
        };
        let (stop, halt) = self.halt;
        if target.solved_at.is_some() || stop.load(Ordering::SeqCst) {
            halt.store(true, Ordering::SeqCst);
        }
        self.task.generation_fields(target, evaluations)
    }

    /// Appends the generation's line to `best-genomes.jsonl` (a genome equal
    /// to the previous line's is stored as a reference to it).
    fn append_best_line(
        &mut self,
        search: &Search,
        generation: u32,
        best: f64,
        best_genome: Genome,
    ) -> Result<()> {
        let same_as = self
            .last_best
            .as_ref()
            .filter(|(_, g)| *g == best_genome)
            .map(|(k, _)| *k);
        let line = BestLine {
            generation,
            fitness: best,
            species: search.species(),
            genome: same_as.is_none().then(|| best_genome.clone()),
            same_as,
        };
        append(
            &self.dir.join(files::BEST_GENOMES),
            &(serde_json::to_string(&line).map_err(|e| Error::Serialize {
                what: "a best-genomes line",
                reason: e.to_string(),
            })? + "\n"),
        )?;
        // Referring to the previous line only keeps a resumed run's file identical.
        self.last_best = Some((generation, best_genome.clone()));
        if FIGURE_GENERATIONS.contains(&generation) {
            self.progress
                .figure_genomes
                .push((generation, best, best_genome));
        }
        Ok(())
    }
}

impl<F: FnMut(&GenerationRecord)> Observer<Search> for Recorder<'_, F> {
    fn on_generation(&mut self, report: &GenerationReport<'_, Search>) -> Result<(), HookError> {
        self.record(report).map_err(Into::into)
    }
}

impl<F> Checkpointer<Search> for Recorder<'_, F> {
    fn after_generation(&mut self, state: &CheckpointState<'_, Search>) -> Result<(), HookError> {
        // A stopping run (finished or interrupted) always leaves a checkpoint.
        if state.stopping.is_some()
            || state
                .generations_done
                .is_multiple_of(self.config.run.checkpoint_interval)
        {
            if state.stopping.is_some() {
                // The last checkpoint is on disk before the run returns.
                self.writer.wait()?;
                write_checkpoint(self.dir, self.config, self.progress, state.strategy)?;
            } else {
                let cp = Checkpoint::new(self.config, self.progress, state.strategy);
                let keep = self.config.run.checkpoint_keep;
                self.writer.start(self.dir.to_path_buf(), keep, cp)?;
            }
            let space = self.task.behaviour_space(self.config);
            write_outputs(self.dir, self.config, &space, state.strategy)?;
        }
        self.started = Instant::now();
        Ok(())
    }
}

fn thread_pool(threads: usize) -> Result<Arc<rayon::ThreadPool>> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map(Arc::new)
        .map_err(|e| Error::Threads(e.to_string()))
}

/// Checks a decoded checkpoint against itself and the run's experiment: the
/// genomes fit the substrate (a wrong CPPN would fail in every later
/// generation), the recorded file lengths are possible and the strategy is
/// the config's; returns the search it holds.
fn validate_progress(path: &Path, cp: &Checkpoint, task: &dyn RunTask) -> Result<Search> {
    let bad = |reason: String| Error::Checkpoint {
        path: path.to_path_buf(),
        reason,
    };
    let p = &cp.progress;
    let search = cp.search().map_err(|why| bad(why.into()))?;
    let kind = StrategyConfig::of(&cp.config).kind;
    if search.kind() != kind.name() {
        return Err(bad(format!(
            "holds {} search, its config says strategy.kind = {}",
            crate::error::a(search.kind()),
            kind.name()
        )));
    }
    if !p.target.fits(task) {
        return Err(bad(format!(
            "its progress does not fit experiment.task = {}",
            cp.config.experiment.task.name()
        )));
    }
    let generations = generations_header(&cp.config);
    for (name, len, header) in [
        (files::GENERATIONS, p.generations_len, generations.as_str()),
        (files::POPULATION, p.population_len, POPULATION_HEADER),
        (files::TIMING, p.timing_len, TIMING_HEADER),
    ] {
        if len < header.len() as u64 {
            return Err(bad(format!(
                "{name} length {len} is shorter than its header"
            )));
        }
    }
    let batch = search.batch();
    if batch.is_empty() {
        return Err(bad("the population has no genomes".into()));
    }
    let named = |what: String| move |e: String| bad(format!("{what} does not fit the run: {e}"));
    for (i, g) in batch.iter().enumerate() {
        task.check_genome(g)
            .map_err(named(format!("genome {i} of the population")))?;
    }
    for (generation, _, g) in &p.figure_genomes {
        (task.check_genome(g))
            .map_err(named(format!("the best genome of generation {generation}")))?;
    }
    Ok(search)
}

/// Sets the checkpoint's total to `generations` when given, refusing a
/// checkpoint that has done more than its own total or a total below what
/// is done.
fn extend_generations(cp: &mut Checkpoint, path: &Path, generations: Option<u32>) -> Result<()> {
    // Against the checkpoint's own total, before a new one replaces it.
    if cp.progress.done > cp.config.experiment.generations {
        return Err(Error::Checkpoint {
            path: path.to_path_buf(),
            reason: format!(
                "{} generations done, more than the run's {}",
                cp.progress.done, cp.config.experiment.generations
            ),
        });
    }
    if let Some(n) = generations {
        if n < cp.progress.done {
            return Err(bad_input(format!(
                "experiment.generations = {n}: the run already has {} generations",
                cp.progress.done
            )));
        }
        cp.config.experiment.generations = n;
    }
    Ok(())
}

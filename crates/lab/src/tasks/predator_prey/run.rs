//! A predator–prey run (`experiment.task = "predator-prey"`): its
//! registration and its run directory, on a driver of its own (two
//! populations do not fit [`crate::run::Run`]'s one strategy).
//!
//! The run directory holds `config.toml`, `scenario.svg`, `hunters.csv` and
//! `prey.csv` (one row per generation of each population), `ciao.csv` (the
//! CIAO matrix, one row per pair of generations), `hall-of-fame.jsonl`
//! (each generation's best hunter and prey genomes), `checkpoint.json` (both
//! populations and halls of fame, and the lengths of the files above: a
//! resume truncates what a crash left after it, so a resumed run's files
//! are the bytes of an uninterrupted one's) and, when it stops,
//! `champions.json` (the master tournament's winners).

use std::fs;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use vivae_neat::Genome;

use crate::config::Config;
use crate::error::{Error, Refusal, Result};
use crate::io::{bad_input, create_dirs, read_text, write_atomic};
use crate::shipped::Shipped;
use crate::tasks::maps::TrainingMap;
pub use crate::tasks::predator_prey::coevo::{ChampionEntry, Champions};
use crate::tasks::predator_prey::coevo::{
    CiaoCell, Coevolution, GenerationRecord, SideRecord, master_tournament,
};
use crate::tasks::predator_prey::meetings::{self, OnThreads};
use crate::tasks::predator_prey::section::{CoevolutionConfig, SideController};
use crate::tasks::predator_prey::{Arena, NAME, Side, present};
use crate::tasks::scenarios::load_scenario;
use crate::tasks::{OwnDriver, RunTask, Session, Stopped, TaskEntry};

/// The predator–prey task's registration.
pub static TASK: TaskEntry = TaskEntry {
    name: NAME,
    default_config: Config::predator_prey,
    validate: crate::tasks::predator_prey::config::validate,
    metric_names: &[],
    generation_columns: "",
    behaviours: &[],
    build,
    own_driver: Some(OwnDriver { evolve, resume }),
    refuse_when_other: crate::tasks::nothing_to_refuse,
    set_robot: None,
    sections: &[super::section::SECTION],
    reads: &crate::config::SharedSection::ALL,
    scenarios: &SCENARIOS,
    maps: true,
    check_map: |s| Arena::teams(s).map(|_| ()).map_err(|e| e.to_string()),
    substrate: false,
    substrate_episode: None,
    stepped: None,
    reward_threshold: None,
    host: None,
};

/// The predator–prey arenas as shipped scenarios (`--scenario predator-prey`).
pub const SCENARIOS: [Shipped; 2] = [
    Shipped {
        name: "predator-prey",
        what: "an open 300 x 300 arena, for the predator-prey task (a hunter and a prey)",
        svg: include_str!("../../../../../scenarios/predator-prey.svg"),
        task: NAME,
    },
    Shipped {
        name: "predator-prey-obstacles",
        what: "the predator-prey arena with four blocks to hide behind (a hunter and a prey)",
        svg: include_str!("../../../../../scenarios/predator-prey-obstacles.svg"),
        task: NAME,
    },
];

/// The files of a predator–prey run directory.
pub use super::files;

/// Header of `hunters.csv` and `prey.csv`.
pub const SIDE_HEADER: &str =
    "generation,best_fitness,mean_fitness,catch_rate,species,mean_links,opponents\n";
/// Header of `ciao.csv`.
pub const CIAO_HEADER: &str = "hunter_generation,prey_generation,hunter_fitness,caught\n";

/// A predator–prey run is not built as a one-population task.
fn build(_: &Config, _: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    Err(bad_input(
        "experiment.task = \"predator-prey\" co-evolves two populations on its own driver: run it with `vivae evolve --task predator-prey` or Python's vivae.coevolve",
    ))
}

/// Lengths of the appended files at a checkpoint, bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
struct Lengths {
    hunters: u64,
    prey: u64,
    ciao: u64,
    hall: u64,
}

impl Lengths {
    /// Each appended file with the length recorded for it.
    fn of_files(self) -> [(&'static str, u64); 4] {
        [
            (files::HUNTERS, self.hunters),
            (files::PREY, self.prey),
            (files::CIAO, self.ciao),
            (files::HALL, self.hall),
        ]
    }
}

/// What `checkpoint.json` holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Checkpoint {
    config: Config,
    state: Coevolution,
    lengths: Lengths,
}

/// One line of `hall-of-fame.jsonl`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct HallEntry {
    /// `hunter` or `prey`.
    pub side: String,
    /// Its generation.
    pub generation: u32,
    /// Its fitness in that generation (against that generation's opponents).
    pub fitness: f64,
    /// The genome.
    pub genome: Genome,
}

/// A predator–prey run in its directory.
struct PpRun {
    dir: PathBuf,
    config: Config,
    arena: Arena,
    state: Coevolution,
    lengths: Lengths,
}

/// The arena of `config` in the scenario at `path` (a file or a shipped
/// name), and the scenario's text.
pub fn arena_of(config: &Config, path: &Path) -> Result<(Arena, String)> {
    let loaded = load_scenario(Some(path))?;
    let arena = Arena::of_config(&loaded.scenario, config).map_err(|e| bad_input(e.to_string()))?;
    Ok((arena, loaded.text))
}

/// The fixed prey named by `from`: the prey champion of the predator-prey
/// run in the directory `from` or in the champions.json file `from` (or the
/// prey of a fixed-prey run's `fixed-prey.json`), and
/// its entry as JSON (for the new run's `fixed-prey.json`).
pub fn fixed_prey(from: &Path, kind: SideController) -> Result<(Genome, String)> {
    let path = if from.is_dir() {
        from.join(files::CHAMPIONS)
    } else {
        from.to_path_buf()
    };
    let text = read_text(&path)?;
    let bad = |why: String| {
        bad_input(format!(
            "coevolution.fixed_prey = {}: {why}",
            from.display()
        ))
    };
    // A run's champions.json, or a run's fixed-prey.json (one entry).
    let entry: ChampionEntry = match serde_json::from_str::<Champions>(&text) {
        Ok(champions) => champions.prey,
        Err(e) => serde_json::from_str(&text).map_err(|_| {
            bad(format!(
                "neither a predator-prey run's champions.json nor its fixed-prey.json ({e})"
            ))
        })?,
    };
    let genome = entry.genome.clone();
    let spec = Arena::spec_of(kind);
    if genome.check().is_err()
        || (genome.num_inputs(), genome.num_outputs()) != (spec.inputs, spec.outputs)
    {
        return Err(bad(format!(
            "its prey is not a genome of {} inputs and {} outputs, as coevolution.prey = \"{}\" has",
            spec.inputs,
            spec.outputs,
            kind.name()
        )));
    }
    let entry = serde_json::to_string_pretty(&entry).map_err(|e| Error::Serialize {
        what: "fixed prey",
        reason: e.to_string(),
    })?;
    Ok((genome, entry))
}

/// Makes `dir` ready for a new run: refused when it holds anything, unless
/// `force` and it is a run directory (it holds a `config.toml`), which is removed.
fn clear_dir(dir: &Path, force: bool) -> Result<()> {
    let occupied = fs::read_dir(dir).is_ok_and(|mut d| d.next().is_some());
    if occupied {
        let is_run = dir.join(crate::rundir::files::CONFIG).is_file();
        if !force || !is_run {
            let said = Refusal::text(format!("{}: exists and is not empty", dir.display()));
            return Err(Error::Refused(if is_run {
                said.then("; ").on("force").then(" replaces the run in it")
            } else {
                said.then(" and holds no run: choose another ").key("out")
            }));
        }
        fs::remove_dir_all(dir).map_err(Error::io("remove", dir))?;
    }
    create_dirs(dir)
}

/// Creates a run of `config` in `dir` and runs it.
fn evolve(dir: &Path, mut config: Config, force: bool, session: &Session<'_>) -> Result<Stopped> {
    crate::tasks::check(&config).map_err(|e| bad_input(format!("config: {e}")))?;
    let scenario = PathBuf::from(&config.experiment.scenario);
    let (arena, text) = arena_of(&config, &scenario)?;
    let mut state = Coevolution::new(&config).map_err(|e| Error::Evolution(e.to_string()))?;
    let fixed = match CoevolutionConfig::of(&config).fixed_prey.as_str() {
        "" => None,
        from => Some(fixed_prey(
            Path::new(from),
            CoevolutionConfig::of(&config).prey,
        )?),
    };
    clear_dir(dir, force)?;
    if let Some(prey) = fixed {
        write_atomic(&dir.join(files::FIXED_PREY), prey.1.as_bytes())?;
        (config.owned).update(|c: &mut CoevolutionConfig| c.fixed_prey = files::FIXED_PREY.into());
        state.fixed_prey = Some(prey.0);
    }
    config.experiment.scenario = crate::rundir::files::SCENARIO.into();
    write_atomic(&dir.join(crate::rundir::files::SCENARIO), text.as_bytes())?;
    write_atomic(
        &dir.join(crate::rundir::files::CONFIG),
        config.to_toml().as_bytes(),
    )?;
    for (name, header) in [
        (files::HUNTERS, SIDE_HEADER),
        (files::PREY, SIDE_HEADER),
        (files::CIAO, CIAO_HEADER),
        (files::HALL, ""),
    ] {
        write_atomic(&dir.join(name), header.as_bytes())?;
    }
    let side = SIDE_HEADER.len() as u64;
    let lengths = Lengths {
        hunters: side,
        prey: side,
        ciao: CIAO_HEADER.len() as u64,
        hall: 0,
    };
    let mut run = PpRun {
        dir: dir.to_path_buf(),
        config,
        arena,
        state,
        lengths,
    };
    run.checkpoint()?;
    (session.say)(&present::header(
        &run.config,
        "evolve",
        &scenario.display().to_string(),
        dir,
    ));
    run.run(session)
}

/// The arena a new run of `config` plays in (its scenario's text too),
/// after checking `config`: what every rank of an MPI job builds.
pub fn arena_for(config: &Config) -> Result<(Arena, String)> {
    crate::tasks::check(config).map_err(|e| bad_input(format!("config: {e}")))?;
    arena_of(config, Path::new(&config.experiment.scenario))
}

/// The config of the run in `dir` (its last checkpoint's) and its arena
/// (and the scenario's text): what every rank of an MPI job resuming it builds.
pub fn arena_of_run(dir: &Path) -> Result<(Config, Arena, String)> {
    let cp = read_checkpoint(dir)?;
    let (arena, text) = arena_of(&cp.config, &dir.join(crate::rundir::files::SCENARIO))?;
    Ok((cp.config, arena, text))
}

/// The checkpoint of the run in `dir`.
fn read_checkpoint(dir: &Path) -> Result<Checkpoint> {
    let path = dir.join(files::CHECKPOINT);
    let text = read_text(&path)?;
    serde_json::from_str(&text).map_err(|e| Error::Checkpoint {
        path,
        reason: e.to_string(),
    })
}

/// Resumes the run in `dir`. Everything is checked before any file
/// changes ([`check_resumable`]): a refused resume leaves the run as it was.
fn resume(dir: &Path, generations: Option<u32>, session: &Session<'_>) -> Result<Stopped> {
    let mut cp = read_checkpoint(dir)?;
    check_resumable(dir, &cp)?;
    let done = cp.state.done();
    let recorded = cp.config.experiment.generations;
    if let Some(n) = generations {
        if n < done {
            return Err(bad_input(format!(
                "experiment.generations = {n}: the run already has {done} generations"
            )));
        }
        cp.config.experiment.generations = n;
    }
    let (arena, _) = arena_of(&cp.config, &dir.join(crate::rundir::files::SCENARIO))?;
    let total = cp.config.experiment.generations;
    // Checked; from here on the run's files change.
    if total != recorded || generations.is_some() {
        let config = dir.join(crate::rundir::files::CONFIG);
        write_atomic(&config, cp.config.to_toml().as_bytes())?;
    }
    for (name, len) in cp.lengths.of_files() {
        let p = dir.join(name);
        let file = fs::OpenOptions::new()
            .write(true)
            .open(&p)
            .map_err(Error::io("open", &p))?;
        file.set_len(len).map_err(Error::io("truncate", &p))?;
    }
    let mut run = PpRun {
        dir: dir.to_path_buf(),
        config: cp.config,
        arena,
        state: cp.state,
        lengths: cp.lengths,
    };
    if done >= total {
        // Killed between its last checkpoint and its champions, or ended
        // at another total: its champions are written now.
        let champions = if total != recorded || !dir.join(files::CHAMPIONS).is_file() {
            run.write_champions()?
        } else {
            run.champions()?
        };
        let (_, line) = present::summary(&champions, dir);
        return Ok(Stopped::AlreadyFinished {
            generations: total,
            line,
        });
    }
    let from = format!(" (resuming after generation {done})");
    let header = present::header(
        &run.config,
        "resume",
        &(dir.display().to_string() + &from),
        dir,
    );
    (session.say)(&header);
    run.run(session)
}

/// Why the run in `dir` cannot resume from its checkpoint `cp`, checked
/// without changing anything: its config must be the run's `config.toml`
/// (but for the total of generations, which `--generations` changes), its
/// genomes of the shapes its sides evolve, and its files at least as long
/// as it recorded, the hall of fame holding its generations' best (so
/// another run's `checkpoint.json` copied in is refused).
fn check_resumable(dir: &Path, cp: &Checkpoint) -> Result<()> {
    let path = dir.join(files::CHECKPOINT);
    let bad = |reason: String| Error::Checkpoint {
        path: path.clone(),
        reason,
    };
    let config_path = dir.join(crate::rundir::files::CONFIG);
    let text = read_text(&config_path)?;
    let mut on_disk = crate::tasks::config_from_toml(&text).map_err(|error| Error::Config {
        path: config_path.clone(),
        error,
    })?;
    on_disk.experiment.generations = cp.config.experiment.generations;
    if on_disk.to_toml() != cp.config.to_toml() {
        return Err(bad(format!(
            "its config is not the run's {} (is it another run's checkpoint?)",
            crate::rundir::files::CONFIG
        )));
    }
    crate::tasks::check(&cp.config).map_err(|e| bad(format!("its config: {e}")))?;
    let st = &cp.state;
    let done = st.done() as usize;
    if st.hall_prey.len() != done {
        return Err(bad(format!(
            "its halls of fame differ in length ({} hunters, {} prey)",
            done,
            st.hall_prey.len()
        )));
    }
    let c = &CoevolutionConfig::of(&cp.config);
    for (side, kind, population, hall) in [
        (Side::Hunter, c.hunter, &st.hunters, &st.hall_hunters),
        (Side::Prey, c.prey, &st.prey, &st.hall_prey),
    ] {
        let spec = Arena::spec_of(kind);
        let fits = |g: &Genome| {
            g.check().is_ok() && (g.num_inputs(), g.num_outputs()) == (spec.inputs, spec.outputs)
        };
        let what = side.name();
        if (population.spec().inputs, population.spec().outputs) != (spec.inputs, spec.outputs)
            || !population.genomes().iter().all(fits)
        {
            return Err(bad(format!(
                "its {what} population is not of genomes of {} inputs and {} outputs, as coevolution.{what} = \"{}\" evolves",
                spec.inputs,
                spec.outputs,
                kind.name()
            )));
        }
        if let Some(k) = hall.iter().position(|g| !fits(g)) {
            return Err(bad(format!(
                "its {what} hall of fame's generation {k} is not a genome of {} inputs and {} outputs",
                spec.inputs, spec.outputs
            )));
        }
    }
    if let Some(g) = &st.fixed_prey {
        let spec = Arena::spec_of(c.prey);
        if g.check().is_err() || (g.num_inputs(), g.num_outputs()) != (spec.inputs, spec.outputs) {
            return Err(bad(format!(
                "its fixed prey is not a genome of {} inputs and {} outputs",
                spec.inputs, spec.outputs
            )));
        }
    }
    check_lengths(dir, cp, &bad)?;
    check_hall(dir, cp).map_err(bad)
}

/// Whether the run's files in `dir` are at least as long as `cp` recorded.
fn check_lengths(dir: &Path, cp: &Checkpoint, bad: &dyn Fn(String) -> Error) -> Result<()> {
    for (name, len) in cp.lengths.of_files() {
        let p = dir.join(name);
        let (_, meta) = crate::io::open_regular(&p)
            .map_err(|e| bad_input(format!("{}: {}", p.display(), crate::io::io_reason(&e))))?;
        if meta.len() < len {
            return Err(bad(format!(
                "{name} is shorter ({} bytes) than it recorded ({len})",
                meta.len()
            )));
        }
    }
    Ok(())
}

/// Whether `hall-of-fame.jsonl`, up to the length `cp` recorded, holds two
/// lines a generation and ends with the last generation's best of `cp`.
fn check_hall(dir: &Path, cp: &Checkpoint) -> std::result::Result<(), String> {
    let p = dir.join(files::HALL);
    let len = cp.lengths.hall;
    let bytes = crate::io::read_regular(&p, crate::rundir::MAX_RUN_FILE_BYTES)
        .map_err(|e| format!("{}: {}", files::HALL, crate::io::io_reason(&e)))?;
    let prefix = bytes.get(..len as usize).unwrap_or(&bytes);
    let done = cp.state.done() as usize;
    let lines: Vec<&[u8]> = prefix
        .split(|&b| b == b'\n')
        .filter(|l| !l.is_empty())
        .collect();
    let whole = prefix.is_empty() || prefix.ends_with(b"\n");
    if !whole || lines.len() != 2 * done {
        return Err(format!(
            "it records {done} generations, but {} holds {} lines of them (is it another run's checkpoint?)",
            files::HALL,
            lines.len()
        ));
    }
    for (line, side, genome) in [
        (
            lines.len().checked_sub(2),
            Side::Hunter,
            cp.state.hall_hunters.last(),
        ),
        (
            lines.len().checked_sub(1),
            Side::Prey,
            cp.state.hall_prey.last(),
        ),
    ] {
        let (Some(k), Some(genome)) = (line, genome) else {
            continue;
        };
        let entry: Option<HallEntry> = serde_json::from_slice(lines[k]).ok();
        let same = entry.is_some_and(|e| {
            e.side == side.name() && e.generation as usize == done - 1 && e.genome == *genome
        });
        if !same {
            return Err(format!(
                "its last {} is not the one on line {} of {} (is it another run's checkpoint?)",
                side.name(),
                k + 1,
                files::HALL
            ));
        }
    }
    Ok(())
}

impl PpRun {
    /// Runs generations until the total or an interruption (each one
    /// checkpointed); writes the champions (once a generation is done); says
    /// how it stopped.
    fn run(&mut self, session: &Session<'_>) -> Result<Stopped> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.config.run.threads)
            .build()
            .map_err(|e| Error::Threads(e.to_string()))?;
        let total = self.config.experiment.generations;
        let mut interrupted = false;
        while self.state.done() < total {
            if session
                .interrupted
                .load(std::sync::atomic::Ordering::SeqCst)
            {
                interrupted = true;
                break;
            }
            let (state, arena, config) = (&mut self.state, &self.arena, &self.config);
            // Meetings played elsewhere (across an MPI job's ranks) are handed
            // out from this thread; else this process's threads play them.
            let record = match meetings::played_by(session) {
                Some(meetings) => state.generation(arena, config, meetings)?,
                None => pool.install(|| state.generation(arena, config, &OnThreads))?,
            };
            self.append(&record)?;
            self.checkpoint()?;
            (session.say)(&present::generation_line(&record, total));
        }
        if interrupted {
            // The champions so far (none before a first generation): the
            // resumed run writes them again at its end.
            if self.state.done() > 0 {
                self.write_champions()?;
            }
            return Ok(Stopped::Interrupted(self.state.done()));
        }
        let champions = self.write_champions()?;
        let (person, line) = present::summary(&champions, &self.dir);
        (session.say)(&person);
        Ok(Stopped::Finished(line))
    }

    /// Writes `champions.json`: the master tournament's winners so far.
    fn write_champions(&self) -> Result<Champions> {
        let champions = self.champions()?;
        let text = serde_json::to_string_pretty(&champions).map_err(|e| Error::Serialize {
            what: "champions",
            reason: e.to_string(),
        })?;
        write_atomic(&self.dir.join(files::CHAMPIONS), text.as_bytes())?;
        Ok(champions)
    }

    /// Appends generation `r`'s rows to the run's files.
    fn append(&mut self, r: &GenerationRecord) -> Result<()> {
        let g = r.generation;
        let hunters = side_row(g, &r.hunters);
        let prey = side_row(g, &r.prey);
        let ciao: String = r.ciao.iter().map(ciao_row).collect();
        let hall = [Side::Hunter, Side::Prey]
            .iter()
            .map(|&side| {
                let (rec, genome) = match side {
                    Side::Hunter => (&r.hunters, &self.state.hall_hunters[g as usize]),
                    Side::Prey => (&r.prey, &self.state.hall_prey[g as usize]),
                };
                let entry = HallEntry {
                    side: side.name().into(),
                    generation: g,
                    fitness: rec.stats.best_fitness.unwrap_or_default(),
                    genome: genome.clone(),
                };
                serde_json::to_string(&entry).map(|s| s + "\n")
            })
            .collect::<std::result::Result<String, _>>()
            .map_err(|e| Error::Serialize {
                what: "hall of fame",
                reason: e.to_string(),
            })?;
        let l = &mut self.lengths;
        for (name, text, len) in [
            (files::HUNTERS, hunters, &mut l.hunters),
            (files::PREY, prey, &mut l.prey),
            (files::CIAO, ciao, &mut l.ciao),
            (files::HALL, hall, &mut l.hall),
        ] {
            let p = self.dir.join(name);
            crate::rundir::append(&p, &text)?;
            *len += text.len() as u64;
        }
        Ok(())
    }

    /// Writes `checkpoint.json` (atomically).
    fn checkpoint(&self) -> Result<()> {
        #[derive(Serialize)]
        struct Out<'a> {
            config: &'a Config,
            state: &'a Coevolution,
            lengths: Lengths,
        }
        let out = Out {
            config: &self.config,
            state: &self.state,
            lengths: self.lengths,
        };
        let text = serde_json::to_string(&out).map_err(|e| Error::Serialize {
            what: "checkpoint",
            reason: e.to_string(),
        })?;
        write_atomic(&self.dir.join(files::CHECKPOINT), text.as_bytes())
    }

    /// The master tournament's winners over the CIAO matrix in `ciao.csv`.
    fn champions(&self) -> Result<Champions> {
        let n = self.state.done();
        let cells = read_ciao(&self.dir.join(files::CIAO))?;
        let pick = |side: Side| -> Result<ChampionEntry> {
            let scores = master_tournament(&cells, n, side);
            // The first of the best (the earliest generation on ties).
            let best = (0..scores.len())
                .reduce(|b, i| if scores[i] > scores[b] { i } else { b })
                .ok_or(Error::NoChampion)?;
            Ok(ChampionEntry {
                generation: best as u32,
                master_fitness: scores[best],
                genome: self.state.hall(side)[best].clone(),
            })
        };
        Ok(Champions {
            generations: n,
            hunter: pick(Side::Hunter)?,
            prey: pick(Side::Prey)?,
        })
    }
}

/// A row of `hunters.csv` or `prey.csv`.
fn side_row(g: u32, r: &SideRecord) -> String {
    let s = &r.stats;
    let opponents: Vec<String> = r.opponents.iter().map(u32::to_string).collect();
    format!(
        "{g},{},{},{},{},{},{}\n",
        s.best_fitness.unwrap_or_default(),
        s.mean_fitness.unwrap_or_default(),
        r.catch_rate,
        s.species,
        s.mean_links,
        opponents.join(";"),
    )
}

/// A row of `ciao.csv`.
fn ciao_row(c: &CiaoCell) -> String {
    format!(
        "{},{},{},{}\n",
        c.hunter,
        c.prey,
        c.hunter_fitness,
        u8::from(c.caught)
    )
}

/// Reads `ciao.csv` back.
pub fn read_ciao(path: &Path) -> Result<Vec<CiaoCell>> {
    let text = read_text(path)?;
    let bad = |line: usize| Error::RunFile {
        path: path.to_path_buf(),
        reason: format!("line {}: not a CIAO row", line + 1),
    };
    (text.lines().enumerate().skip(1))
        .map(|(i, line)| {
            let f: Vec<&str> = line.split(',').collect();
            let [h, p, fit, caught] = f.as_slice() else {
                return Err(bad(i));
            };
            Ok(CiaoCell {
                hunter: h.parse().map_err(|_| bad(i))?,
                prey: p.parse().map_err(|_| bad(i))?,
                hunter_fitness: fit.parse().map_err(|_| bad(i))?,
                caught: *caught == "1",
            })
        })
        .collect()
}

/// Reads `champions.json` of the run in `dir`.
pub fn read_champions(dir: &Path) -> Result<Champions> {
    let path = dir.join(files::CHAMPIONS);
    let text = read_text(&path)?;
    serde_json::from_str(&text).map_err(|e| Error::RunFile {
        path,
        reason: e.to_string(),
    })
}

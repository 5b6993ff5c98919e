//! One predator–prey run's champions against another's (`vivae tournament
//! RUN_A RUN_B`): A's hunters against B's prey and B's hunters against A's
//! prey, each side as its champion (the master tournament's winner,
//! `champions.json`) and as its whole hall of fame (each generation's best,
//! `hall-of-fame.jsonl`). Tells how hunters hold up against prey they never
//! met (a held-out seed's) and how fast they catch a fixed prey. Every game
//! is one deterministic episode in run A's arena; both runs must have the
//! same arena, episode length and robot.

use std::fmt::Write as _;
use std::path::Path;

use vivae_neat::Genome;
use vivae_neat::hyperneat::HyperParams;

use crate::tasks::predator_prey::section::{CoevolutionConfig, SideController};

use crate::error::{Error, Result};
use crate::io::{bad_input, csv_field, read_text};
use crate::tasks::predator_prey::run::{HallEntry, arena_of, files, read_champions};
use crate::tasks::predator_prey::{Arena, NAME, Outcome, Side};

/// The header of the tournament's CSV.
pub const CSV_HEADER: &str = "hunters_run,prey_run,hunters,prey,games,catches,catch_rate,mean_hunter_fitness,mean_catch_step\n";

/// The CSV file `vivae tournament --csv` writes: an existing file is an
/// earlier one when it opens with [`CSV_HEADER`] (`crate::output_path`).
pub const CSV_KIND: crate::io::OutputKind = crate::io::OutputKind {
    what: "vivae tournament CSV",
    earlier: |b| b.starts_with(CSV_HEADER.as_bytes()),
};

/// One line of the tournament: a set of one run's hunters against a set of
/// another's prey, every hunter against every prey once.
#[derive(Debug, Clone, PartialEq)]
pub struct TournamentRow {
    /// The hunters' run directory.
    pub hunters_run: String,
    /// The prey's run directory.
    pub prey_run: String,
    /// `champion` or `hall` (every generation's best).
    pub hunters: &'static str,
    /// `champion` or `hall`.
    pub prey: &'static str,
    /// Games played.
    pub games: usize,
    /// Games that ended in a catch.
    pub catches: usize,
    /// `catches / games`.
    pub catch_rate: f64,
    /// The hunters' mean fitness (≥ 1 a catch, `2 − t/T`; below 1 a miss, `1 − d̄`).
    pub mean_hunter_fitness: f64,
    /// The mean step of the catches (none without a catch).
    pub mean_catch_step: Option<f64>,
}

/// A run's champions: each side's master-tournament winner and hall of fame.
struct Entrant {
    name: String,
    controllers: [SideController; 2],
    hyper: HyperParams,
    champion: [Genome; 2],
    hall: [Vec<Genome>; 2],
}

impl Entrant {
    fn side(side: Side) -> usize {
        match side {
            Side::Hunter => 0,
            Side::Prey => 1,
        }
    }

    /// The genomes of `side` in set `set` (`champion` or `hall`).
    fn set(&self, side: Side, set: &str) -> &[Genome] {
        let k = Entrant::side(side);
        match set {
            "champion" => std::slice::from_ref(&self.champion[k]),
            _ => &self.hall[k],
        }
    }
}

/// Reads the champions and the hall of fame of the finished run in `dir`.
fn entrant(dir: &Path) -> Result<Entrant> {
    let config = crate::tasks::read_config(&dir.join(crate::rundir::files::CONFIG))?;
    let champions = read_champions(dir)?;
    let path = dir.join(files::HALL);
    let text = read_text(&path)?;
    let sides = CoevolutionConfig::of(&config);
    let controllers = [sides.hunter, sides.prey];
    // Genomes of another shape (another kind of controller, another run's)
    // are refused here, by file and line: a meeting would not be able to
    // build their networks.
    let misfit = |side: Side, genome: &Genome| {
        let spec = Arena::spec_of(controllers[Entrant::side(side)]);
        let fits = genome.check().is_ok()
            && (genome.num_inputs(), genome.num_outputs()) == (spec.inputs, spec.outputs);
        (!fits).then(|| {
            format!(
                "its {} is not a genome of {} inputs and {} outputs, as the run's config (coevolution.{} = \"{}\") has",
                side.name(),
                spec.inputs,
                spec.outputs,
                side.name(),
                controllers[Entrant::side(side)].name()
            )
        })
    };
    let mut hall = [Vec::new(), Vec::new()];
    for (i, line) in text.lines().enumerate() {
        let bad = |reason: String| Error::RunFile {
            path: path.clone(),
            reason: format!("line {}: {reason}", i + 1),
        };
        let e: HallEntry = serde_json::from_str(line).map_err(|e| bad(e.to_string()))?;
        let side = [Side::Hunter, Side::Prey]
            .into_iter()
            .find(|s| e.side == s.name())
            .ok_or_else(|| {
                bad(format!(
                    "side {:?}: expected \"{}\" or \"{}\"",
                    e.side,
                    Side::Hunter.name(),
                    Side::Prey.name()
                ))
            })?;
        if let Some(why) = misfit(side, &e.genome) {
            return Err(bad(why));
        }
        hall[Entrant::side(side)].push(e.genome);
    }
    if let Some(side) = [Side::Hunter, Side::Prey]
        .into_iter()
        .find(|&s| hall[Entrant::side(s)].is_empty())
    {
        return Err(Error::RunFile {
            path,
            reason: format!(
                "holds no {}: a tournament needs a finished run",
                side.name()
            ),
        });
    }
    for (side, genome) in [
        (Side::Hunter, &champions.hunter.genome),
        (Side::Prey, &champions.prey.genome),
    ] {
        if let Some(why) = misfit(side, genome) {
            return Err(Error::RunFile {
                path: dir.join(files::CHAMPIONS),
                reason: why.replacen("its ", "its champion ", 1),
            });
        }
    }
    Ok(Entrant {
        name: dir.display().to_string(),
        controllers,
        hyper: config.hyperneat,
        champion: [champions.hunter.genome, champions.prey.genome],
        hall,
    })
}

/// The arena of the run in `dir` and what must match between two runs.
fn arena_and_terms(dir: &Path) -> Result<(Arena, String)> {
    let config = crate::tasks::read_config(&dir.join(crate::rundir::files::CONFIG))?;
    if config.experiment.task.0 != NAME {
        return Err(bad_input(format!(
            "{}: {} run, not a predator-prey run",
            dir.display(),
            crate::error::a(&config.experiment.task.0)
        )));
    }
    let (arena, text) = arena_of(&config, &dir.join(crate::rundir::files::SCENARIO))?;
    let terms = format!("{text}\n{}\n{:?}", config.experiment.steps, config.physics);
    Ok((arena, terms))
}

/// Plays `a`'s champions against `b`'s (either may be the same run) on
/// `threads` threads (0 = one per core; the results do not depend on it):
/// A's hunters against B's prey, then B's hunters against A's prey, each as
/// champion × champion, champion × hall, hall × champion, hall × hall.
pub fn tournament(a: &Path, b: &Path, threads: usize) -> Result<Vec<TournamentRow>> {
    let (arena, terms) = arena_and_terms(a)?;
    if arena_and_terms(b)?.1 != terms {
        return Err(bad_input(format!(
            "{}: played in another arena than {} (scenario.svg, experiment.steps or [physics] differ): a tournament needs the same game",
            b.display(),
            a.display()
        )));
    }
    let runs = [entrant(a)?, entrant(b)?];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Threads(e.to_string()))?;
    let mut rows = Vec::new();
    for (h, p) in [(0, 1), (1, 0)] {
        for hunters in ["champion", "hall"] {
            for prey in ["champion", "hall"] {
                let (hs, ps) = (
                    runs[h].set(Side::Hunter, hunters),
                    runs[p].set(Side::Prey, prey),
                );
                // Each side plays with its own run's kind of controller.
                let (hr, pr) = (&runs[h], &runs[p]);
                let arena =
                    arena
                        .clone()
                        .with_controllers(hr.controllers[0], pr.controllers[1], hr.hyper);
                let arena = arena.with_prey_params(pr.hyper);
                let outcomes = pool.install(|| play_all(&arena, hs, ps));
                rows.push(row(&runs[h].name, &runs[p].name, hunters, prey, &outcomes));
            }
        }
    }
    Ok(rows)
}

/// Every hunter of `hunters` against every prey of `prey`, in order.
fn play_all(arena: &Arena, hunters: &[Genome], prey: &[Genome]) -> Vec<Outcome> {
    use rayon::prelude::*;
    let pairs: Vec<(usize, usize)> = (0..hunters.len())
        .flat_map(|h| (0..prey.len()).map(move |p| (h, p)))
        .collect();
    pairs
        .par_iter()
        .map(|&(h, p)| arena.play_genomes(&hunters[h], &prey[p]))
        .collect()
}

/// The row of `outcomes`.
fn row(
    hunters_run: &str,
    prey_run: &str,
    hunters: &'static str,
    prey: &'static str,
    outcomes: &[Outcome],
) -> TournamentRow {
    let games = outcomes.len();
    let caught: Vec<&Outcome> = outcomes.iter().filter(|o| o.caught).collect();
    let fitness: f64 = outcomes.iter().map(Outcome::hunter_fitness).sum();
    let steps: f64 = caught.iter().map(|o| f64::from(o.steps)).sum();
    TournamentRow {
        hunters_run: hunters_run.into(),
        prey_run: prey_run.into(),
        hunters,
        prey,
        games,
        catches: caught.len(),
        catch_rate: caught.len() as f64 / games.max(1) as f64,
        mean_hunter_fitness: fitness / games.max(1) as f64,
        mean_catch_step: (!caught.is_empty()).then(|| steps / caught.len() as f64),
    }
}

/// The rows as CSV (with [`CSV_HEADER`]); run names quoted as RFC 4180 asks.
pub fn csv(rows: &[TournamentRow]) -> String {
    let mut out = CSV_HEADER.to_string();
    for r in rows {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            csv_field(&r.hunters_run),
            csv_field(&r.prey_run),
            r.hunters,
            r.prey,
            r.games,
            r.catches,
            r.catch_rate,
            r.mean_hunter_fitness,
            r.mean_catch_step.map(|s| s.to_string()).unwrap_or_default(),
        );
    }
    out
}

/// The rows as a table for a person.
pub fn table(rows: &[TournamentRow]) -> String {
    let mut out = format!(
        "{:<30} {:<30} {:<17} {:>6} {:>7} {:>8} {:>10}\n",
        "hunters", "prey", "sets", "games", "caught", "fitness", "catch step"
    );
    for r in rows {
        let step = r.mean_catch_step.map_or("-".into(), |s| format!("{s:.1}"));
        let _ = writeln!(
            out,
            "{:<30} {:<30} {:<17} {:>6} {:>7.3} {:>8.3} {:>10}",
            r.hunters_run,
            r.prey_run,
            format!("{} x {}", r.hunters, r.prey),
            r.games,
            r.catch_rate,
            r.mean_hunter_fitness,
            step,
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_names_with_commas_quotes_or_line_breaks_are_quoted_as_rfc_4180_asks() {
        let row = |hunters_run: &str, prey_run: &str| TournamentRow {
            hunters_run: hunters_run.into(),
            prey_run: prey_run.into(),
            hunters: "champion",
            prey: "hall",
            games: 4,
            catches: 2,
            catch_rate: 0.5,
            mean_hunter_fitness: 1.25,
            mean_catch_step: None,
        };
        let text = csv(&[
            row("runs/a,b", "say \"hi\""),
            row("two\nlines", "plain"),
            row("cr\rhere", "plain"),
        ]);
        let rows = text.strip_prefix(CSV_HEADER).unwrap();
        assert_eq!(
            rows,
            "\"runs/a,b\",\"say \"\"hi\"\"\",champion,hall,4,2,0.5,1.25,\n\
             \"two\nlines\",plain,champion,hall,4,2,0.5,1.25,\n\
             \"cr\rhere\",plain,champion,hall,4,2,0.5,1.25,\n"
        );
    }
}

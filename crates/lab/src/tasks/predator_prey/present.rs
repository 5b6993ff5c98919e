//! A predator–prey run for a person: its header, a line per generation and
//! its closing lines and summary line.

use std::path::Path;

use crate::config::Config;
use crate::tasks::predator_prey::coevo::{Champions, GenerationRecord};
use crate::tasks::predator_prey::section::{CoevolutionConfig, Opponents, SideController};

/// The header of a predator–prey run.
pub(super) fn header(config: &Config, command: &str, scenario: &str, dir: &Path) -> String {
    let c = config;
    let opponents = match CoevolutionConfig::of(c).opponents {
        Opponents::Best => "the other population's best of the previous generation".to_string(),
        Opponents::HallOfFame => format!(
            "{} of the other population's earlier champions (hall of fame)",
            CoevolutionConfig::of(c).sample
        ),
        Opponents::Fixed => format!(
            "a fixed prey ({}; only the hunters evolve)",
            CoevolutionConfig::of(c).fixed_prey
        ),
    };
    let kinds = match (
        CoevolutionConfig::of(c).hunter,
        CoevolutionConfig::of(c).prey,
    ) {
        (SideController::Neat, SideController::Neat) => {
            "plain NEAT networks (11 inputs, 2 outputs)".to_string()
        }
        (h, p) => format!(
            "genomes (hunters {}, prey {}; hyperneat = CPPNs on a 3x3 substrate at the sensors' angles)",
            h.name(),
            p.name()
        ),
    };
    format!(
        "vivae {command}: predators and prey in {scenario}\n\
         \x20 two populations of {} {kinds}, {} steps per episode, \
         {} generations, seed {}\n\
         \x20 each genome meets {opponents}\n\
         \x20 hunter fitness = 2 - t/T after a catch at step t, else 1 - the mean distance / the arena's diagonal; prey = 2 - hunter\n\
         \x20 output: {}",
        c.neat.population_size,
        c.experiment.steps,
        c.experiment.generations,
        c.experiment.seed,
        dir.display(),
    )
}

/// The line of one generation.
pub(super) fn generation_line(r: &GenerationRecord, total: u32) -> String {
    let best = |s: &crate::tasks::predator_prey::coevo::SideRecord| {
        s.stats.best_fitness.unwrap_or_default()
    };
    let caught = r.ciao.iter().filter(|c| c.caught).count();
    format!(
        "gen {:>4}/{total}  hunters best {:.3} (catch rate {:.2})  prey best {:.3}  CIAO: {caught} of {} new pairs caught",
        r.generation + 1,
        best(&r.hunters),
        r.hunters.catch_rate,
        best(&r.prey),
        r.ciao.len(),
    )
}

/// The closing lines and the summary line.
pub(super) fn summary(c: &Champions, dir: &Path) -> (String, String) {
    let dir = dir.display();
    let how = format!("done: {} generations", c.generations);
    let person = format!(
        "{how}\n\
         hunter champion: generation {} (master tournament fitness {:.3} against every prey champion)\n\
         prey champion: generation {} (master tournament fitness {:.3} against every hunter champion)\n\
         run directory: {dir}/ (config.toml, hunters.csv, prey.csv, ciao.csv, hall-of-fame.jsonl, champions.json, checkpoint.json)",
        c.hunter.generation, c.hunter.master_fitness, c.prey.generation, c.prey.master_fitness,
    );
    let line = format!(
        "evolve: task=predator-prey generations={} hunter_champion_generation={} hunter_master_fitness={} prey_champion_generation={} prey_master_fitness={} out={dir}",
        c.generations,
        c.hunter.generation,
        c.hunter.master_fitness,
        c.prey.generation,
        c.prey.master_fitness,
    );
    (person, line)
}

//! Which genome drives a page's robots: the page's choice (`controller`
//! message) parsed, and the genome it names found in the followed run.

use serde_json::Value;

use crate::view::source::RunSnapshot;
use vivae_lab::config::Config;
use vivae_lab::io::one_line;

/// Which genome drives the robots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Choice {
    /// Nobody: robots stand still unless driven by hand.
    None,
    /// The best genome so far.
    Champion,
    /// The best genome of one generation.
    Generation(u32),
    /// The elite of this cell of a map-elites run's archive.
    Elite(usize),
    /// This member of an nsga2 run's Pareto front (0 = the fittest).
    Front(usize),
}

impl Choice {
    /// What a page's controller list calls it: `none`, `champion`, a
    /// generation, `elite:CELL` or `front:N`.
    pub(super) fn page_value(self) -> String {
        match self {
            Choice::None => "none".into(),
            Choice::Champion => "champion".into(),
            Choice::Generation(g) => g.to_string(),
            Choice::Elite(c) => format!("elite:{c}"),
            Choice::Front(n) => format!("front:{n}"),
        }
    }
}

/// A chosen genome, its label for the page and its generation (if recorded).
type Chosen<'a> = (&'a vivae_neat::Genome, String, Option<u32>);

/// The genome `choice` names in `snap`, with its label for the page and its
/// generation (if recorded); `None` for nobody; `Err` if the run has no such genome.
pub(super) fn chosen_genome<'a>(
    choice: Choice,
    snap: &'a RunSnapshot,
    config: &Config,
) -> Result<Option<Chosen<'a>>, String> {
    let two = |v: &f64| format!("{v:.2}");
    Ok(Some(match choice {
        Choice::None => return Ok(None),
        Choice::Champion => snap
            .champion
            .as_ref()
            .map(|c| {
                let label = format!(
                    "champion (generation {}, fitness {:.3})",
                    c.generation, c.fitness
                );
                (&c.genome, label, Some(c.generation))
            })
            .ok_or("there is no champion yet")?,
        Choice::Generation(g) => snap
            .best
            .iter()
            .find(|b| b.generation == g)
            .map(|b| {
                let label = format!("best of generation {g} (fitness {:.3})", b.fitness);
                (&b.genome, label, Some(g))
            })
            .ok_or_else(|| format!("generation {g} has no recorded best genome"))?,
        Choice::Elite(cell) => {
            let e = (snap.elites.iter().find(|e| e.cell == cell))
                .ok_or_else(|| missing("elite in cell", cell, snap.elites.len(), "elites"))?;
            let names = vivae_lab::tasks::behaviours::coordinate_names(config, e.behaviour.len());
            let label = format!(
                "elite of cell {cell} (generation {}, fitness {:.3}; {})",
                e.generation,
                e.fitness,
                named(&names, e.behaviour.iter().map(two))
            );
            (&e.genome, label, Some(e.generation))
        }
        Choice::Front(n) => {
            let f = (snap.front.iter().find(|f| f.member == n))
                .ok_or_else(|| missing("front member", n, snap.front.len(), "members"))?;
            let names = vivae_lab::search::front_objective_names(config);
            let label = format!(
                "front member {n} (fitness {:.3}; {})",
                f.fitness,
                named(&names, f.objectives.iter().map(two))
            );
            (&f.genome, label, None)
        }
    }))
}

/// Why `what` `index` is not there, where the run holds `held` `things`.
fn missing(what: &str, index: usize, held: usize, things: &str) -> String {
    match held {
        0 => {
            format!("no {what} {index}: this run has none (its strategy keeps no archive or front)")
        }
        n => format!("no {what} {index} (the run has {n} {things})"),
    }
}

/// `name value, …` for each name and value.
fn named(names: &[String], values: impl Iterator<Item = String>) -> String {
    let pairs = names.iter().zip(values).map(|(n, v)| format!("{n} {v}"));
    pairs.collect::<Vec<_>>().join(", ")
}

/// The controller a `controller` message chooses: `"champion"`, `"none"`, a
/// generation, `{"elite": CELL}` or `{"front": N}`.
pub(super) fn parse_choice(which: &Value) -> Result<Choice, String> {
    let index = |v: &Value| v.as_u64().and_then(|i| u32::try_from(i).ok());
    match which {
        Value::String(s) if s == "champion" => Ok(Choice::Champion),
        Value::String(s) if s == "none" => Ok(Choice::None),
        Value::Number(n) => {
            Ok(Choice::Generation(index(which).ok_or_else(|| {
                format!("controller {n}: not a generation")
            })?))
        }
        Value::Object(o) if o.len() == 1 => {
            let (key, v) = o.iter().next().expect("one entry");
            let quoted = truncated(&which.to_string());
            let i = index(v)
                .ok_or_else(|| format!("controller {quoted}: not a cell or member number"))?;
            match key.as_str() {
                "elite" => Ok(Choice::Elite(i as usize)),
                "front" => Ok(Choice::Front(i as usize)),
                _ => Err(format!(
                    "controller {quoted}: expected {{\"elite\": CELL}} or {{\"front\": N}}"
                )),
            }
        }
        other => Err(format!(
            "controller {}: expected \"champion\", \"none\", a generation, {{\"elite\": CELL}} or {{\"front\": N}}",
            one_line(&truncated(&other.to_string()))
        )),
    }
}

/// `text`, cut to 80 characters (an error quoting a hostile message stays short).
fn truncated(text: &str) -> String {
    match text.char_indices().nth(80) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}

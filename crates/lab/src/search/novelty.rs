//! Novelty search (Lehman & Stanley 2011) over a NEAT population: it adds the
//! archive's size and the novelty threshold to `generations.csv`.

use vivae_neat::strategies::{NoveltyParams, NoveltySearch};
use vivae_neat::{Genome, NeatError, Population};

use crate::search::StrategyConfig;
use crate::error::Result;
use crate::io::bad_input;
use crate::search::{
    Needs, RunStrategy, Search, Start, StrategyEntry, StrategyReport, TaskFacts, bad_setting, behaviour_line,
    starting_population, state_of,
};

/// Novelty search's registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "novelty",
    needs: Needs {
        behaviour: true,
        metrics: false,
    },
    takes_population: true,
    variant: "Novelty",
    from_state: state_of::<NoveltySearch>,
    extra_columns: ",archive_size,novelty_threshold",
    build,
    header_line: behaviour_line,
    report: |_, _, _| {
        Ok(Some(StrategyReport {
            kind: STRATEGY.kind,
            heading: "Novelty search".into(),
            note: "The archive of novel behaviours and its admission threshold, per generation."
                .into(),
            ..StrategyReport::default()
        }))
    },
    files: &[],
    settings: None,
};

/// Novelty search's settings in a run: the library's, with ρ_min and its
/// floor on the scale of the descriptors of runs (arena sizes, shares), not
/// the library's default of 1.
pub fn novelty_defaults() -> NoveltyParams {
    NoveltyParams {
        threshold: 0.05,
        threshold_floor: 0.005,
        ..NoveltyParams::default()
    }
}

/// Checks `[strategy.novelty]`; the error names the key.
pub(super) fn validate(p: &NoveltyParams) -> std::result::Result<(), String> {
    match p.validate() {
        Err(NeatError::InvalidParam {
            field,
            value,
            reason,
        }) => Err(bad_setting(&format!("novelty.{field}"), &value, reason)),
        _ => Ok(()),
    }
}

/// A task's distance between distinct behaviours is ρ_min, and its floor
/// the floor ρ_min adapts down to.
pub(super) fn fit_to(p: &mut NoveltyParams, task: &TaskFacts<'_>) {
    if let Some(distinct) = task.distinct {
        p.threshold = distinct;
    }
    if let Some(floor) = task.distinct_floor {
        p.threshold_floor = floor;
    }
}

fn build(start: Start<'_>) -> Result<Search> {
    let config = start.config;
    let population = starting_population(start)?;
    let refused = |e: NeatError| bad_input(format!("strategy.novelty: {e}"));
    let params = StrategyConfig::of(config).novelty;
    Ok(Search::of(
        NoveltySearch::new(population, params).map_err(refused)?,
    ))
}

impl RunStrategy for NoveltySearch {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn population(&self) -> Option<&Population> {
        Some(NoveltySearch::population(self))
    }

    fn batch(&self) -> Vec<Genome> {
        NoveltySearch::population(self).genomes().to_vec()
    }

    fn extra_fields(&self) -> String {
        format!(",{},{}", self.archive().len(), self.threshold())
    }

    fn summary_fields(&self) -> String {
        format!(" archive_size={}", self.archive().len())
    }
}

//! NEAT (the paper's): a speciated population selecting on fitness. Its run
//! files are NEAT's own; it adds no columns and no files.

use vivae_neat::driver::Evaluation;
use vivae_neat::{Genome, GenomeSpec, Population};

use crate::config::Config;
use crate::config::strategy::StrategyKind;
use crate::error::Result;
use crate::search::{Bounds, RunStrategy, Search, StrategyEntry, starting_population};

/// NEAT's registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: StrategyKind::Neat,
    variant: "Neat",
    from_state: |state| Ok(Search::of(serde_json::from_str::<Population>(state)?)),
    extra_columns: "",
    build,
    header_line: |_| String::new(),
    report: |_, _, _| Ok(None),
};

fn build(
    config: &Config,
    spec: GenomeSpec,
    _: Bounds,
    init: Option<&Population>,
) -> Result<Search> {
    Ok(Search::of(starting_population(config, spec, init)?))
}

impl RunStrategy for Population {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn population(&self) -> Option<&Population> {
        Some(self)
    }

    fn batch(&self) -> Vec<Genome> {
        self.genomes().to_vec()
    }

    /// As the population holds them.
    fn fitnesses(&self, _evaluations: &[Evaluation]) -> Vec<f64> {
        Population::fitnesses(self)
    }
}

//! NEAT (the paper's): a speciated population selecting on fitness. Its run
//! files are NEAT's own; it adds no columns and no files.

use vivae_neat::driver::Evaluation;
use vivae_neat::{Genome, Population};

use crate::error::Result;
use crate::search::{
    Needs, RunStrategy, Search, Start, StrategyEntry, starting_population, state_of,
};

/// NEAT's registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "neat",
    needs: Needs {
        behaviour: false,
        metrics: false,
    },
    takes_population: true,
    variant: "Neat",
    from_state: state_of::<Population>,
    extra_columns: "",
    build,
    header_line: |_| String::new(),
    report: |_, _, _| Ok(None),
    files: &[],
    settings: None,
};

fn build(start: Start<'_>) -> Result<Search> {
    Ok(Search::of(starting_population(start)?))
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

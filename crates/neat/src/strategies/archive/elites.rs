//! MAP-Elites' archive: per cell, the fittest genome whose behaviour fell
//! in it (an [`Elite`]), and the archive's coverage and QD-score.

use serde::{Deserialize, Serialize};

use super::grid::Cells;
use crate::error::NeatError;
use crate::genome::Genome;
use crate::strategies::invalid;

/// The best genome found for one cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Elite {
    /// The genome.
    pub genome: Genome,
    /// Its fitness.
    pub fitness: f64,
    /// Its behaviour (non-finite coordinates as 0).
    pub behaviour: Vec<f64>,
    /// The generation in which it was evaluated.
    pub generation: u32,
}

/// The archive at a glance (for `generations.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapElitesStats {
    /// Cells holding an elite.
    pub filled: usize,
    /// Filled cells over all cells.
    pub coverage: f64,
    /// Σ (fitness − qd_offset) over the elites.
    pub qd_score: f64,
    /// Fitness of the best elite.
    pub best: Option<f64>,
}

/// Places a genome in its cell if the cell is empty or it is strictly
/// fitter than the cell's elite; says whether it did.
pub fn insert(archive: &mut [Option<Elite>], cell: usize, candidate: Elite) -> bool {
    let slot = &mut archive[cell];
    if slot.as_ref().is_none_or(|e| candidate.fitness > e.fitness) {
        *slot = Some(candidate);
        true
    } else {
        false
    }
}

/// Coverage, QD-score (Σ fitness − `qd_offset`) and best fitness of `archive`.
pub fn archive_stats(archive: &[Option<Elite>], qd_offset: f64) -> MapElitesStats {
    let (mut filled, mut qd_score, mut best) = (0, 0.0, None::<f64>);
    for e in archive.iter().flatten() {
        filled += 1;
        qd_score += e.fitness - qd_offset;
        best = Some(best.map_or(e.fitness, |b| b.max(e.fitness)));
    }
    MapElitesStats {
        filled,
        coverage: filled as f64 / archive.len() as f64,
        qd_score,
        best,
    }
}

/// Checks a restored archive against its cells: one entry per cell, each
/// elite finite, of the cells' dimension and not from after `generation`.
pub(crate) fn check_archive(
    archive: &[Option<Elite>],
    cells: &Cells,
    generation: u32,
) -> Result<(), NeatError> {
    if archive.len() != cells.len() {
        return Err(invalid("archive", archive.len(), "one entry per cell"));
    }
    let dims = cells.dims();
    let elite_ok = |e: &Elite| {
        e.fitness.is_finite() && e.behaviour.len() == dims && e.generation <= generation
    };
    if !archive.iter().flatten().all(elite_ok) {
        return Err(invalid(
            "archive",
            "an elite",
            "inconsistent with the cells",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use crate::params::NeatParams;
    use proptest::prelude::{prop, prop_assert_eq, proptest};
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    fn elite(fitness: f64) -> Elite {
        let spec = GenomeSpec::plain(1, 1);
        let mut rng = Pcg64::seed_from_u64(0);
        let mut tracker = InnovationTracker::new(2);
        let genome = Genome::minimal(&spec, &NeatParams::plain_neat(), &mut tracker, &mut rng);
        Elite {
            genome,
            fitness,
            behaviour: vec![fitness],
            generation: 0,
        }
    }

    proptest! {
        #[test]
        fn insertion_keeps_the_first_best_per_cell(
            offers in prop::collection::vec((0usize..6, -3i32..3), 0..60),
        ) {
            let mut archive = vec![None; 6];
            // Each offer marked by its position (as its generation).
            for (k, &(cell, f)) in offers.iter().enumerate() {
                insert(&mut archive, cell, Elite { generation: k as u32, ..elite(f64::from(f)) });
            }
            for (cell, slot) in archive.iter().enumerate() {
                let here = || offers.iter().enumerate().filter(|(_, o)| o.0 == cell);
                let best = here().map(|(_, o)| o.1).max();
                let first = here().find(|(_, o)| Some(o.1) == best).map(|(k, _)| k as u32);
                let kept = slot.as_ref().map(|e| (e.fitness, e.generation));
                prop_assert_eq!(kept, best.map(f64::from).zip(first));
            }
        }
    }
}

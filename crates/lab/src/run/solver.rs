//! A run with a target stops on a genome that holds it: one whose
//! evaluation reached the target and that passes its task's check
//! ([`RunTask::holds_target`]), which then is the run's champion.

use vivae_neat::Population;
use vivae_neat::driver::{Evaluation, Strategy};

use super::checkpoint::Progress;
use crate::config::Config;
use crate::rundir::Champion;
use crate::search::Search;
use crate::tasks::RunTask;

/// Tells the run's target progress `generation`'s `evaluations`, checking
/// the genomes that reached the target in batch order; the first that holds
/// is kept as the solver. A strategy without a population (MAP-Elites,
/// NSGA-II) exposes only its batch's best genome once told: that one is
/// checked, for the first evaluation that reached the target.
pub(super) fn tell_target(
    progress: &mut Progress,
    task: &dyn RunTask,
    search: &Search,
    generation: u32,
    evaluations: &[Evaluation],
) {
    let Some(target) = progress.target.get_mut() else {
        return;
    };
    let genomes = search.population().map(Population::genomes);
    let best = search.champion();
    let (mut best_checked, mut checked) = (false, false);
    let held = target.tell_checked(task, generation, evaluations, |i| {
        let verdict = match genomes {
            Some(g) => task.holds_target(&g[i]),
            // The batch's best is checked once: later solvers of the batch are the same genome.
            None if best_checked => Some((false, 0)),
            None => {
                best_checked = true;
                best.and_then(|(g, _)| task.holds_target(g))
            }
        };
        checked = verdict.is_some();
        verdict
    });
    // A task without a check keeps its champion: the best ever.
    if let Some(i) = held.filter(|_| checked) {
        let (genome, fitness) = match (genomes, best) {
            (Some(g), _) => (g[i].clone(), evaluations[i].fitness),
            (None, Some((g, f))) => (g.clone(), f),
            (None, None) => return,
        };
        progress.solver = Some((generation, fitness, genome));
    }
}

/// The champion with its run-relative generation: the genome that held the
/// task's target on its check, else the best ever of `search`.
pub(super) fn champion(search: &Search, progress: &Progress, config: &Config) -> Option<Champion> {
    let best = search.best_ever().map(|b| {
        (
            b.generation - progress.start_generation + 1,
            b.fitness,
            &b.genome,
        )
    });
    let (generation, fitness, genome) = progress
        .solver
        .as_ref()
        .map(|(g, f, x)| (*g, *f, x))
        .or(best)?;
    Some(Champion {
        format: "vivae-champion".into(),
        generation,
        fitness,
        config: Some(Champion::recorded_config(config)),
        genome: genome.clone(),
    })
}

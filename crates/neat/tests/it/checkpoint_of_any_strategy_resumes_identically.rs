//! Any strategy, NEAT's population or the (1+λ)-ES, serialised mid-run with
//! serde_json, restored and continued, gives the uninterrupted run bit for bit.

use serde::Serialize;
use vivae_neat::driver::{
    CheckpointState, Checkpointer, Evolution, GenerationReport, HookError, NoCheckpoints, Observer,
    ParallelEvaluator, StopCriteria, Strategy,
};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams, Population};

use crate::common::OnePlusLambda;

/// Depends on weights, structure and the evaluation seed.
fn task(g: &Genome, ctx: &EvalContext) -> f64 {
    g.links()
        .iter()
        .map(|l| (l.weight * 1.7).cos())
        .sum::<f64>()
        + 0.3 * g.num_hidden() as f64
        + (ctx.seed % 7) as f64 * 0.1
}

/// Every fitness of every generation, as bits.
#[derive(Default)]
struct History(Vec<Vec<u64>>);

impl<S: Strategy> Observer<S> for History {
    fn on_generation(&mut self, report: &GenerationReport<'_, S>) -> Result<(), HookError> {
        assert_eq!(report.stats.generation, report.strategy.generation());
        let bits = report.evaluations.iter().map(|e| e.fitness.to_bits());
        self.0.push(bits.collect());
        Ok(())
    }
}

/// The JSON of the strategy after generation `at`.
struct Snapshot {
    at: u32,
    json: Option<String>,
}

impl<S: Strategy> Checkpointer<S> for Snapshot {
    fn after_generation(&mut self, state: &CheckpointState<'_, S>) -> Result<(), HookError> {
        if state.generations_done == self.at {
            self.json = Some(serde_json::to_string(state.strategy)?);
        }
        Ok(())
    }
}

fn json<S: Serialize>(s: &S) -> String {
    serde_json::to_string(s).unwrap()
}

/// Runs `total` generations straight and `k` + restore + the rest; compares.
fn resumes_identically<S: Strategy>(make: impl Fn() -> S, k: u32, total: u32) {
    let mut straight = Evolution::new(make(), ParallelEvaluator::new(task));
    let (mut full, mut snapshot) = (History::default(), Snapshot { at: k, json: None });
    straight
        .run(&StopCriteria::generations(total), &mut full, &mut snapshot)
        .unwrap();

    let mut first = Evolution::new(make(), ParallelEvaluator::new(task));
    let mut history = History::default();
    first
        .run(
            &StopCriteria::generations(k),
            &mut history,
            &mut NoCheckpoints,
        )
        .unwrap();
    let saved = json(first.strategy());
    assert_eq!(Some(&saved), snapshot.json.as_ref(), "checkpoint at {k}");
    let restored: S = serde_json::from_str(&saved).unwrap();
    let mut resumed = Evolution::resume(restored, ParallelEvaluator::new(task), k);
    resumed
        .run(
            &StopCriteria::generations(total),
            &mut history,
            &mut NoCheckpoints,
        )
        .unwrap();

    assert_eq!(history.0.len(), total as usize);
    assert_eq!(history.0, full.0);
    assert_eq!(json(resumed.strategy()), json(straight.strategy()));
}

#[test]
fn neat_population_resumes_identically() {
    let params = NeatParams {
        population_size: 40,
        target_species: Some(4),
        add_node_probability: 0.2,
        ..NeatParams::default()
    };
    let make = || Population::new(params.clone(), GenomeSpec::cppn(), 2024).unwrap();
    resumes_identically(make, 5, 12);
}

#[test]
fn evolution_strategy_resumes_identically() {
    resumes_identically(|| OnePlusLambda::new(GenomeSpec::plain(3, 2), 6, 77), 9, 25);
}

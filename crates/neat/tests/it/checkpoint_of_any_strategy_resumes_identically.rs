//! Any strategy (NEAT's population, the (1+λ)-ES, novelty search,
//! MAP-Elites on a grid and on a CVT, NSGA-II), serialised mid-run with
//! serde_json, restored and continued, gives the uninterrupted run bit for bit.

use serde::Serialize;
use vivae_neat::driver::{
    CheckpointState, Checkpointer, Evaluation, Evolution, GenerationReport, HookError,
    NoCheckpoints, Observer, ParallelEvaluator, StopCriteria, Strategy, Task,
};
use vivae_neat::strategies::{
    Cells, MapElites, MapElitesParams, Measure, NoveltyParams, NoveltySearch, Nsga2, Nsga2Params,
    Objective,
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

/// [`task`] as fitness, with two metrics and a two-dimensional behaviour
/// that also depend on the genome and the seed.
struct Measured;

impl Task for Measured {
    fn evaluate(&self, g: &Genome, ctx: &EvalContext) -> Evaluation {
        let weights: f64 = g.links().iter().map(|l| l.weight).sum();
        Evaluation {
            fitness: task(g, ctx),
            metrics: vec![g.num_enabled_links() as f64, (weights * 0.7).sin()],
            behaviour: vec![weights.tanh(), (ctx.seed % 11) as f64 * 0.1 - 0.5],
        }
    }
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
    let mut straight = Evolution::new(make(), ParallelEvaluator::new(Measured));
    let (mut full, mut snapshot) = (History::default(), Snapshot { at: k, json: None });
    straight
        .run(&StopCriteria::generations(total), &mut full, &mut snapshot)
        .unwrap();

    let mut first = Evolution::new(make(), ParallelEvaluator::new(Measured));
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
    let mut resumed = Evolution::resume(restored, ParallelEvaluator::new(Measured), k);
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

fn neat_params(population_size: usize) -> NeatParams {
    NeatParams {
        population_size,
        ..NeatParams::plain_neat()
    }
}

#[test]
fn novelty_search_resumes_identically() {
    let novelty = NoveltyParams {
        k: 5,
        threshold: 0.05,
        threshold_floor: 0.01,
        lower_after: 2,
        fitness_weight: 0.3,
        ..NoveltyParams::default()
    };
    let make = || {
        let population = Population::new(neat_params(30), GenomeSpec::plain(3, 2), 31).unwrap();
        NoveltySearch::new(population, novelty.clone()).unwrap()
    };
    resumes_identically(make, 6, 14);
    // The run did what novelty search does: it archived behaviours.
    let mut run = Evolution::new(make(), ParallelEvaluator::new(Measured));
    run.run(&StopCriteria::generations(14), &mut (), &mut NoCheckpoints)
        .unwrap();
    assert!(run.strategy().archive().len() > 5);
}

#[test]
fn map_elites_resumes_identically_on_a_grid_and_a_cvt() {
    let map = MapElitesParams {
        batch_size: 12,
        crossover_probability: 0.3,
        qd_offset: -10.0,
    };
    let grid = Cells::grid(vec![-1.0, -0.5], vec![1.0, 0.5], vec![8, 4]).unwrap();
    let cvt = Cells::cvt(&[-1.0, -0.5], &[1.0, 0.5], 20, 500, 5, 3).unwrap();
    for cells in [grid, cvt] {
        let make = || {
            let (params, spec) = (neat_params(1), GenomeSpec::plain(3, 2));
            MapElites::new(params, spec, map.clone(), cells.clone(), 8).unwrap()
        };
        resumes_identically(make, 7, 16);
    }
}

#[test]
fn nsga2_resumes_identically() {
    let objectives = vec![
        Objective {
            measure: Measure::Fitness,
            maximise: true,
        },
        Objective {
            measure: Measure::Metric(0),
            maximise: false,
        },
        Objective {
            measure: Measure::Metric(1),
            maximise: true,
        },
    ];
    let nsga = Nsga2Params {
        population_size: 16,
        objectives,
        crossover_probability: 0.5,
    };
    let make = || {
        let (params, spec) = (neat_params(1), GenomeSpec::plain(3, 2));
        Nsga2::new(params, spec, nsga.clone(), 12).unwrap()
    };
    resumes_identically(make, 5, 13);
}

//! Each strategy beyond NEAT does its job on a toy problem over the sum of a
//! genome's link weights: novelty search keeps a generation spread out
//! where fitness gathers it, MAP-Elites fills its map, NSGA-II spreads along a Pareto front.

use vivae_neat::driver::{
    Evaluation, Evolution, GenerationReport, HookError, NoCheckpoints, Observer, ParallelEvaluator,
    StopCriteria, Strategy, Task,
};
use vivae_neat::strategies::{
    Cells, MapElites, MapElitesParams, Measure, NoveltyParams, NoveltySearch, Nsga2, Nsga2Params,
    Objective,
};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams, Population};

fn weight_sum(g: &Genome) -> f64 {
    g.links()
        .iter()
        .filter(|l| l.enabled)
        .map(|l| l.weight)
        .sum()
}

fn params(population_size: usize) -> NeatParams {
    NeatParams {
        population_size,
        ..NeatParams::plain_neat()
    }
}

/// A task given as a function returning a whole evaluation.
struct Eval(fn(&Genome, &EvalContext) -> Evaluation);

impl Task for Eval {
    fn evaluate(&self, g: &Genome, ctx: &EvalContext) -> Evaluation {
        (self.0)(g, ctx)
    }
}

fn run<S: Strategy>(strategy: S, task: fn(&Genome, &EvalContext) -> Evaluation, n: u32) -> S {
    let mut evolution = Evolution::new(strategy, ParallelEvaluator::new(Eval(task)));
    let stop = StopCriteria::generations(n);
    evolution.run(&stop, &mut (), &mut NoCheckpoints).unwrap();
    evolution.into_strategy()
}

/// Spread (standard deviation) of the behaviours of a generation.
fn spread(genomes: &[Genome]) -> f64 {
    let b: Vec<f64> = genomes.iter().map(behaviour).collect();
    let mean = b.iter().sum::<f64>() / b.len() as f64;
    (b.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / b.len() as f64).sqrt()
}

/// The squashed weight sum.
fn behaviour(g: &Genome) -> f64 {
    (weight_sum(g) / 4.0).tanh()
}

#[test]
fn novelty_search_keeps_spreading_where_fitness_converges() {
    // Fitness pulls the behaviour to 0; novelty search ignores it. Mutation
    // is gentle, so that what selection does shows in the generation.
    let task = |g: &Genome, _: &EvalContext| Evaluation {
        fitness: -behaviour(g).abs(),
        metrics: vec![],
        behaviour: vec![behaviour(g)],
    };
    let novelty = NoveltyParams {
        threshold: 0.05,
        threshold_floor: 0.01,
        ..NoveltyParams::default()
    };
    let gentle = NeatParams {
        weight_perturb_power: 0.3,
        weight_replace_probability: 0.0,
        ..params(50)
    };
    let population = || Population::new(gentle.clone(), GenomeSpec::plain(3, 1), 4).unwrap();
    let novelty_run = run(NoveltySearch::new(population(), novelty).unwrap(), task, 60);
    let neat = run(population(), task, 60);
    let (ns, neat) = (novelty_run.population().genomes(), neat.genomes());
    let (ns_spread, neat_spread) = (spread(ns), spread(neat));
    assert!(
        ns_spread > 1.5 * neat_spread,
        "spread: novelty {ns_spread}, fitness {neat_spread}"
    );
    let far = |g: &[Genome]| g.iter().filter(|g| behaviour(g).abs() > 0.5).count();
    assert!(
        far(ns) > 3 * far(neat),
        "far: novelty {}, fitness {}",
        far(ns),
        far(neat)
    );
    let archived: Vec<f64> = novelty_run.archive().map(|b| b[0]).collect();
    let (lo, hi) = archived
        .iter()
        .fold((1.0f64, -1.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!(lo < -0.9 && hi > 0.9, "archive spans {lo}..{hi}");
}

/// Counts the elites of each generation.
struct Filled(Vec<usize>);

impl Observer<MapElites> for Filled {
    fn on_generation(&mut self, r: &GenerationReport<'_, MapElites>) -> Result<(), HookError> {
        let stats = r.strategy.archive_stats();
        assert_eq!(stats.filled, r.strategy.elites().count());
        assert_eq!(stats.coverage, stats.filled as f64 / 100.0);
        self.0.push(stats.filled);
        Ok(())
    }
}

#[test]
fn map_elites_fills_its_map_and_keeps_the_best_per_cell() {
    // Cells over (squashed weight sum, squashed number of links); fitness
    // prefers fewer links, so an elite is only replaced by a fitter genome.
    let task = |g: &Genome, _: &EvalContext| Evaluation {
        fitness: -(g.num_enabled_links() as f64),
        metrics: vec![],
        behaviour: vec![(weight_sum(g) / 4.0).tanh(), g.links().len() as f64],
    };
    let cells = Cells::grid(vec![-1.0, 0.0], vec![1.0, 10.0], vec![10, 10]).unwrap();
    let map = MapElitesParams {
        batch_size: 40,
        ..MapElitesParams::default()
    };
    let me = MapElites::new(params(1), GenomeSpec::plain(3, 1), map, cells, 5).unwrap();
    let mut evolution = Evolution::new(me, ParallelEvaluator::new(Eval(task)));
    let mut filled = Filled(Vec::new());
    let stop = StopCriteria::generations(50);
    evolution
        .run(&stop, &mut filled, &mut NoCheckpoints)
        .unwrap();
    assert!(
        filled.0.windows(2).all(|w| w[0] <= w[1]),
        "never loses a cell"
    );
    assert!(filled.0[49] >= 3 * filled.0[0], "{:?}", filled.0);
    for (cell, elite) in evolution.strategy().elites() {
        assert_eq!(evolution.strategy().cells().cell_of(&elite.behaviour), cell);
    }
}

#[test]
fn nsga2_spreads_along_the_front_of_two_conflicting_objectives() {
    // Weight sum w: one objective wants w = 2, the other w = −2; the
    // Pareto set is −2 ≤ w ≤ 2.
    let task = |g: &Genome, _: &EvalContext| {
        let w = weight_sum(g);
        Evaluation {
            fitness: -(w - 2.0).powi(2),
            metrics: vec![(w + 2.0).powi(2), w],
            behaviour: vec![],
        }
    };
    let objectives = vec![
        Objective {
            measure: Measure::Fitness,
            maximise: true,
        },
        Objective {
            measure: Measure::Metric(0),
            maximise: false,
        },
    ];
    let nsga = Nsga2Params {
        population_size: 40,
        objectives,
        crossover_probability: 0.3,
    };
    let es = Nsga2::new(params(1), GenomeSpec::plain(3, 1), nsga, 6).unwrap();
    let es = run(es, task, 60);
    let front = es.pareto_front();
    // On the front w ≤ 2, so the first objective −(w − 2)² gives w back.
    let ws: Vec<f64> = front.iter().map(|(_, o, _)| 2.0 - (-o[0]).sqrt()).collect();
    for (_, o, f) in &front {
        assert_eq!(o[0], *f, "the first objective is the fitness, as measured");
        assert!(
            o[1] >= 0.0,
            "the second as measured (minimised), not negated"
        );
    }
    let (lo, hi) = ws
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), &w| (lo.min(w), hi.max(w)));
    assert!(front.len() >= 20, "{} on the front", front.len());
    assert!(lo < -1.5 && hi > 1.5, "front spans w = {lo}..{hi}");
}

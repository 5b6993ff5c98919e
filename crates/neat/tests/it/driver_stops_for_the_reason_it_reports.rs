//! The evolution driver stops on each criterion, reports it, tells its hooks
//! in order, and evolves exactly as the population's own loop does.

use std::sync::atomic::AtomicBool;

use vivae_neat::driver::{
    CheckpointState, Checkpointer, Evolution, GenerationReport, HookError, NoCheckpoints, Observer,
    ParallelEvaluator, StopCriteria, StopReason,
};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatParams, Population};

fn links(g: &Genome, _: &EvalContext) -> f64 {
    g.links().iter().map(|l| l.weight.abs()).sum::<f64>() / (1 + g.links().len()) as f64
}

fn population(seed: u64) -> Population {
    let params = NeatParams {
        population_size: 20,
        ..NeatParams::plain_neat()
    };
    Population::new(params, GenomeSpec::plain(3, 1), seed).unwrap()
}

#[derive(Default)]
struct Log(Vec<String>);

impl Observer for Log {
    fn on_generation(&mut self, r: &GenerationReport<'_>) -> Result<(), HookError> {
        assert_eq!(r.evaluations.len(), r.strategy.genomes().len());
        assert_eq!(r.strategy.fitnesses().len(), r.evaluations.len());
        self.0.push(format!("eval {}", r.generation));
        Ok(())
    }
}

impl Checkpointer for Log {
    fn after_generation(&mut self, s: &CheckpointState<'_>) -> Result<(), HookError> {
        assert!(
            !s.strategy.is_evaluated(),
            "checkpoints hold a bred population"
        );
        self.0
            .push(format!("ckpt {} {:?}", s.generations_done, s.stopping));
        Ok(())
    }
}

#[test]
fn stops_after_the_requested_generations_and_tells_hooks_in_order() {
    let mut evo = Evolution::new(population(1), ParallelEvaluator::new(links));
    let (mut obs, mut ckpt) = (Log::default(), Log::default());
    let reason = evo
        .run(&StopCriteria::generations(3), &mut obs, &mut ckpt)
        .unwrap();
    assert_eq!(reason, StopReason::Generations(3));
    assert_eq!(obs.0, ["eval 1", "eval 2", "eval 3"]);
    assert_eq!(
        ckpt.0,
        ["ckpt 1 None", "ckpt 2 None", "ckpt 3 Some(Generations(3))"]
    );
    // Running again with the same criteria does nothing: the run is finished.
    let again = evo
        .run(&StopCriteria::generations(3), &mut obs, &mut NoCheckpoints)
        .unwrap();
    assert_eq!(again, StopReason::Generations(3));
    assert_eq!(obs.0.len(), 3);
}

#[test]
fn stops_at_target_fitness_interrupt_and_stagnation() {
    let mut evo = Evolution::new(population(2), ParallelEvaluator::new(links));
    let reason = evo
        .run(
            &StopCriteria::generations(50).or_target(0.0),
            &mut (),
            &mut NoCheckpoints,
        )
        .unwrap();
    assert!(matches!(
        reason,
        StopReason::TargetFitness { generation: 1, .. }
    ));

    let flag = AtomicBool::new(true);
    let mut evo = Evolution::new(population(3), ParallelEvaluator::new(links));
    let reason = evo
        .run(
            &StopCriteria::generations(50).or_interrupt(&flag),
            &mut (),
            &mut NoCheckpoints,
        )
        .unwrap();
    assert_eq!(reason, StopReason::Interrupted);
    assert_eq!(
        evo.generations_done(),
        1,
        "the generation under way is finished"
    );

    // A constant fitness never improves after generation 1.
    let mut evo = Evolution::new(
        population(4),
        ParallelEvaluator::new(|_: &Genome, _: &EvalContext| 1.0),
    );
    let reason = evo
        .run(
            &StopCriteria::generations(50).or_stagnation(5),
            &mut (),
            &mut NoCheckpoints,
        )
        .unwrap();
    assert_eq!(reason, StopReason::Stagnation(5));
    assert_eq!(evo.generations_done(), 6);
}

#[test]
fn driver_evolves_exactly_as_the_population_loop() {
    let mut by_hand = population(5);
    for _ in 0..6 {
        by_hand.evaluate(|g, ctx| links(g, &ctx));
        by_hand.next_generation();
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let mut evo = Evolution::new(population(5), ParallelEvaluator::with_pool(links, &pool));
    evo.run(&StopCriteria::generations(6), &mut (), &mut NoCheckpoints)
        .unwrap();
    assert_eq!(evo.population(), &by_hand);
}

//! The driver runs a strategy that is not NEAT: every stop criterion holds
//! for it, generic observers see it, and bad evaluations are refused.

use std::sync::atomic::AtomicBool;

use vivae_neat::driver::{
    Evaluation, Evolution, GenerationReport, HookError, NoCheckpoints, Observer, ParallelEvaluator,
    StopCriteria, StopReason, Strategy,
};
use vivae_neat::{EvalContext, Genome, GenomeSpec, NeatError, NeatParams, Population};

use crate::common::OnePlusLambda;

/// Drives the sum of the link weights to 3 (fitness 0 is perfect).
fn weights_to_three(g: &Genome, _: &EvalContext) -> f64 {
    -(g.links().iter().map(|l| l.weight).sum::<f64>() - 3.0).abs()
}

fn es(seed: u64) -> OnePlusLambda {
    OnePlusLambda::new(GenomeSpec::plain(2, 1), 4, seed)
}

/// A progress line per generation, written once for every strategy.
#[derive(Default)]
struct Progress(Vec<String>);

impl<S: Strategy> Observer<S> for Progress {
    fn on_generation(&mut self, r: &GenerationReport<'_, S>) -> Result<(), HookError> {
        let (_, best) = r.strategy.champion().ok_or("a told batch has a champion")?;
        assert_eq!(r.stats.best_fitness, Some(best));
        assert_eq!(r.stats.population, r.evaluations.len());
        let ever = r.strategy.best_ever().ok_or("a told strategy has a best")?;
        assert!(ever.fitness >= best);
        self.0
            .push(format!("{} {}", r.generation, r.stats.population));
        Ok(())
    }
}

#[test]
fn stops_after_the_requested_generations() {
    let mut evo = Evolution::new(es(1), ParallelEvaluator::new(weights_to_three));
    let mut progress = Progress::default();
    let reason = evo
        .run(
            &StopCriteria::generations(5),
            &mut progress,
            &mut NoCheckpoints,
        )
        .unwrap();
    assert_eq!(reason, StopReason::Generations(5));
    assert_eq!(progress.0, ["1 4", "2 4", "3 4", "4 4", "5 4"]);
    assert_eq!(evo.generations_done(), 5);
    assert_eq!(evo.strategy().generation(), 5, "prepared for generation 5");
}

#[test]
fn stops_at_the_target_fitness() {
    let mut evo = Evolution::new(es(2), ParallelEvaluator::new(weights_to_three));
    let stop = StopCriteria::generations(3000).or_target(-0.01);
    let reason = evo.run(&stop, &mut (), &mut NoCheckpoints).unwrap();
    let StopReason::TargetFitness {
        fitness,
        generation,
    } = reason
    else {
        panic!("target not reached: {reason:?}");
    };
    assert!(fitness >= -0.01);
    assert!(generation > 1, "the first generation is not already there");
    assert_eq!(generation, evo.generations_done());
    assert_eq!(evo.strategy().best_ever().unwrap().fitness, fitness);
}

#[test]
fn stops_on_stagnation_and_interrupt() {
    // A constant fitness never improves on generation 0's.
    let constant = |_: &Genome, _: &EvalContext| 1.0;
    let mut evo = Evolution::new(es(3), ParallelEvaluator::new(constant));
    let stop = StopCriteria::generations(50).or_stagnation(5);
    let reason = evo.run(&stop, &mut (), &mut NoCheckpoints).unwrap();
    assert_eq!(reason, StopReason::Stagnation(5));
    assert_eq!(evo.generations_done(), 6);

    let flag = AtomicBool::new(true);
    let mut evo = Evolution::new(es(4), ParallelEvaluator::new(constant));
    let stop = StopCriteria::generations(50).or_interrupt(&flag);
    let reason = evo.run(&stop, &mut (), &mut NoCheckpoints).unwrap();
    assert_eq!(reason, StopReason::Interrupted);
    assert_eq!(evo.generations_done(), 1);
}

#[test]
fn tell_refuses_a_wrong_count_and_zeroes_non_finite_fitness() {
    let population = Population::new(NeatParams::plain_neat(), GenomeSpec::plain(2, 1), 5);
    refuses_and_zeroes(population.unwrap());
    refuses_and_zeroes(es(5));
}

fn refuses_and_zeroes<S: Strategy>(mut strategy: S) {
    let n = strategy.ask().genomes.len();
    assert_eq!(
        strategy.tell(&[]),
        Err(NeatError::FitnessCount {
            given: 0,
            genomes: n
        })
    );
    assert_eq!(strategy.champion(), None, "nothing was told");
    let mut evaluations = vec![Evaluation::fitness(f64::NAN); n];
    evaluations[n - 1] = Evaluation::fitness(-1.0);
    strategy.tell(&evaluations).unwrap();
    assert_eq!(strategy.champion().map(|(_, f)| f), Some(0.0));
    assert_eq!(strategy.stats().mean_fitness, Some(-1.0 / n as f64));
}

#[test]
fn ask_gives_every_genome_its_own_seeded_context() {
    let mut strategy = es(6);
    for generation in 0..3 {
        let batch = strategy.ask();
        assert_eq!(batch.contexts.len(), batch.genomes.len());
        for (i, ctx) in batch.contexts.iter().enumerate() {
            assert_eq!(ctx.index, i);
            assert_eq!(ctx.generation, generation);
            assert_eq!(ctx.seed, vivae_neat::eval_seed(6, generation, i));
        }
        let n = batch.genomes.len();
        strategy.tell(&vec![Evaluation::fitness(1.0); n]).unwrap();
    }
}

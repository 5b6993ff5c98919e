//! What the measuring strategies read from an episode (behaviour
//! descriptors and metrics) and that measuring keeps the fitness: tests of
//! `descriptors` that need an [`Episode`], which that module does not import.

use vivae_neat::Population;
use vivae_neat::driver::Task;

use super::Episode;
use crate::config::Config;
use crate::tasks::driving::descriptors::*;
use crate::tasks::scenarios::load_scenario;

/// A registered strategy that selects on a behaviour (`behaviour`) or
/// on the task's metrics (`!behaviour`).
fn needing(behaviour: bool) -> &'static str {
    let fits = |e: &&crate::search::StrategyEntry| {
        (e.needs.behaviour, e.needs.metrics) == (behaviour, !behaviour)
    };
    let found = crate::search::entries().into_iter().find(fits);
    found.expect("a registered strategy needs it").kind
}

fn experiment(kind: &str, behaviour: BehaviourKind) -> (Config, Episode) {
    let mut config = Config::default();
    config.experiment.steps = 150;
    crate::search::StrategyConfig::update(&mut config, |s| {
        s.kind = kind.into();
        s.behaviour = behaviour.name().into();
    });
    let e = Episode::new(&config, &load_scenario(None).unwrap().scenario).unwrap();
    (config, e)
}

#[test]
fn measuring_keeps_the_fitness_bit_for_bit() {
    let (config, plain) = experiment("neat", BehaviourKind::EndPosition);
    let pop = Population::new(config.neat.clone(), plain.cppn_spec(), 5).unwrap();
    let ctx = vivae_neat::EvalContext {
        generation: 0,
        index: 0,
        seed: 0,
    };
    for (kind, behaviour) in [
        (needing(true), BehaviourKind::SideSpeed),
        (needing(true), BehaviourKind::EndPositions),
        (needing(false), BehaviourKind::EndPosition),
        (needing(true), BehaviourKind::Trajectory),
    ] {
        let (_, measured) = experiment(kind, behaviour);
        for g in pop.genomes().iter().take(4) {
            let a = plain.evaluate(g, &ctx);
            let b = measured.evaluate(g, &ctx);
            assert!(a.behaviour.is_empty() && a.metrics.is_empty());
            assert_eq!(a.fitness.to_bits(), b.fitness.to_bits());
            let (lower, upper) = behaviour.bounds(measured.robots());
            if kind == needing(false) {
                assert!(b.behaviour.is_empty());
                assert_eq!(b.metrics.len(), METRICS.len());
                assert!(b.metrics[0] >= 0.0 && (0.0..=1.0).contains(&b.metrics[1]));
            } else {
                assert!(b.metrics.is_empty());
                assert_eq!(b.behaviour.len(), behaviour.dims(measured.robots()));
                for ((x, lo), hi) in b.behaviour.iter().zip(&lower).zip(&upper) {
                    assert!((lo..=hi).contains(&x), "{behaviour:?}: {x} outside");
                }
            }
        }
    }
}

#[test]
fn metrics_agree_with_the_recorded_episode() {
    let (config, e) = experiment(needing(false), BehaviourKind::EndPosition);
    let pop = Population::new(config.neat.clone(), e.cppn_spec(), 9).unwrap();
    for g in pop.genomes().iter().take(4) {
        let c = e.controller(g).unwrap();
        let m = measured_episode(
            e.setup(),
            e.rollout(&c),
            &c,
            Measures::of(&crate::search::StrategyConfig::of(&config)).unwrap(),
        );
        let recorded = e.run(&c, true);
        assert_eq!(m.metrics[0], recorded.behaviour.unwrap().collisions);
        assert_eq!(m.metrics[1], recorded.on_road.unwrap());
    }
}

#[test]
fn end_position_is_the_mean_of_end_positions() {
    let (config, e) = experiment(needing(true), BehaviourKind::EndPosition);
    let pop = Population::new(config.neat.clone(), e.cppn_spec(), 2).unwrap();
    let c = e.controller(&pop.genomes()[0]).unwrap();
    let each = |kind| {
        let m = Measures {
            behaviour: Some(kind),
            metrics: false,
        };
        measured_episode(e.setup(), e.rollout(&c), &c, m).behaviour
    };
    let (mean, all) = (
        each(BehaviourKind::EndPosition),
        each(BehaviourKind::EndPositions),
    );
    let n = e.robots() as f64;
    let x: f64 = all.iter().step_by(2).sum::<f64>() / n;
    let y: f64 = all.iter().skip(1).step_by(2).sum::<f64>() / n;
    assert!((mean[0] - x).abs() < 1e-12 && (mean[1] - y).abs() < 1e-12);
}

#[test]
fn a_trajectory_samples_the_path_and_ends_at_the_end_position() {
    let (config, e) = experiment(needing(true), BehaviourKind::Trajectory);
    let pop = Population::new(config.neat.clone(), e.cppn_spec(), 3).unwrap();
    let m = |kind| Measures {
        behaviour: Some(kind),
        metrics: false,
    };
    let mut moved = false;
    for g in pop.genomes().iter().take(6) {
        let c = e.controller(g).unwrap();
        let path = measured_episode(e.setup(), e.rollout(&c), &c, m(BehaviourKind::Trajectory));
        let end = measured_episode(e.setup(), e.rollout(&c), &c, m(BehaviourKind::EndPosition));
        assert_eq!(path.behaviour.len(), 2 * TRAJECTORY_SAMPLES);
        assert_eq!(
            path.behaviour[2 * TRAJECTORY_SAMPLES - 2..],
            end.behaviour[..]
        );
        moved |= path.behaviour[..2] != path.behaviour[2..4];
    }
    assert!(moved, "no robot moved between the first two samples");
}

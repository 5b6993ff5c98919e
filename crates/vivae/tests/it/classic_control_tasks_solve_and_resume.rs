//! Gymnasium's classic-control tasks besides CartPole (Acrobot-v1,
//! MountainCar-v0, MountainCarContinuous-v0, Pendulum-v1: `crates/lab/src/
//! tasks/`, each a plain task on the shared episode loop of `classic.rs`) run
//! with every strategy and resume bit-identically, as CartPole does, and each
//! reaches its threshold on a fixed seed within 40 generations of its
//! default run, its champion replayed.

use vivae_lab::tasks::acrobot::Acrobot;
use vivae_lab::tasks::mountain_car::MountainCar;
use vivae_lab::tasks::mountain_car_continuous::MountainCarContinuous;
use vivae_lab::tasks::pendulum::Pendulum;
use vivae_lab::tasks::plain::{Described, Plain};

use crate::a_plain_task_runs_reports_exports_and_resumes::{
    every_strategy_runs_and_resumes_bit_identical, plain,
};
use crate::common::*;

/// The tasks, each with the fitness it counts as solved at.
fn tasks() -> [(&'static str, f64); 4] {
    [
        (Acrobot::NAME, Acrobot::TARGET.unwrap()),
        (MountainCar::NAME, MountainCar::TARGET.unwrap()),
        (
            MountainCarContinuous::NAME,
            MountainCarContinuous::TARGET.unwrap(),
        ),
        (Pendulum::NAME, Pendulum::TARGET.unwrap()),
    ]
}

#[test]
fn every_classic_control_task_runs_every_strategy_and_resumes_bit_identical() {
    // Populations and seeds that leave 4 generations unsolved (Acrobot
    // solves in its first generation at 30).
    let runs = [("10", "8"), ("30", "5"), ("30", "9"), ("30", "5")];
    for ((task, _), (population, seed)) in tasks().into_iter().zip(runs) {
        every_strategy_runs_and_resumes_bit_identical(task, population, seed);
    }
}

#[test]
fn every_classic_control_task_reaches_its_threshold_on_seed_1_and_stops_if_it_holds() {
    let dir = scratch("classic-solved");
    for (task, target) in tasks() {
        let out = dir.join(task);
        // MountainCar's seed 1 holds its check (by three standard errors) in
        // generation 36.
        let line = plain(task, &out, &["--seed", "1", "--generations", "40"]);
        assert!(number(&line, "best") >= target, "{task}: {line}");
        if task == Pendulum::NAME {
            // Its genomes reach −200 on their 5 training episodes but none
            // holds it on the 100 check episodes: the run does not stop.
            assert_eq!(field(&line, "solved"), "no", "{task}: {line}");
            assert_eq!(number(&line, "generations"), 40.0, "{task}: {line}");
            assert!(
                number(&line, "evaluations") > 40.0 * 150.0,
                "checks count: {line}"
            );
        } else {
            assert_eq!(field(&line, "solved"), "yes", "{task}: {line}");
            assert!(
                number(&line, "generations") < 40.0,
                "{task}: a solved run stops: {line}"
            );
        }
        // Its champion validated on 100 fresh episodes, solved by that alone.
        let validated = number(&line, "validated_mean");
        assert!(
            number(&line, "validated_worst") <= validated,
            "{task}: {line}"
        );
        let verdict = if validated >= target { "yes" } else { "no" };
        assert_eq!(field(&line, "validated"), verdict, "{task}: {line}");
        let replayed = ok(vivae().arg("replay").arg(&out));
        assert!(replayed.contains("fitness="), "{task}: {replayed}");
        let episode = String::from_utf8(read(&out, "replay/episode.csv")).unwrap();
        assert!(
            episode.starts_with("episode,step,in0,"),
            "{task}: {episode}"
        );
    }
}

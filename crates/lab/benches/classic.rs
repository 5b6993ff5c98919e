//! Evaluations of Gymnasium's classic-control tasks as a run makes them (a
//! feed-forward network compiled, then 5 episodes), one episode after the
//! other and with the episodes side by side in lanes
//! (`classic::evaluate_lanes`, the same bits): the genomes of the 10th
//! generation of a real run of each task (population 150, seed 1).

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use vivae_lab::tasks::acrobot::Acrobot;
use vivae_lab::tasks::cartpole::CartPole;
use vivae_lab::tasks::classic::{self, Classic};
use vivae_lab::tasks::mountain_car::MountainCar;
use vivae_lab::tasks::mountain_car_continuous::MountainCarContinuous;
use vivae_lab::tasks::pendulum::Pendulum;
use vivae_lab::tasks::plain::spec;
use vivae_neat::{FeedForwardNetwork, Genome, NeatParams, Population};

fn main() {
    divan::main();
}

/// The 10th generation of a run of `T` (plain NEAT, population 150, seed 1).
fn population<T: Classic>() -> Vec<Genome> {
    let mut pop = Population::new(NeatParams::plain_neat(), spec::<T>(), 1).unwrap();
    for _ in 0..9 {
        pop.evaluate(|g, ctx| {
            classic::evaluate::<T>(&mut FeedForwardNetwork::from_genome(g), ctx.seed, None).fitness
        });
        pop.next_generation();
    }
    pop.genomes().to_vec()
}

/// The population's evaluations, one episode after the other.
fn one_by_one<T: Classic>(bencher: Bencher) {
    let genomes = population::<T>();
    bencher.counter(ItemsCount::new(genomes.len())).bench(|| {
        for (k, g) in genomes.iter().enumerate() {
            let mut net = FeedForwardNetwork::from_genome(g);
            black_box(classic::evaluate::<T>(&mut net, k as u64, None));
        }
    });
}

/// The population's evaluations, each genome's episodes side by side.
fn in_lanes<T: Classic>(bencher: Bencher) {
    let genomes = population::<T>();
    bencher.counter(ItemsCount::new(genomes.len())).bench(|| {
        for (k, g) in genomes.iter().enumerate() {
            let net = FeedForwardNetwork::from_genome(g);
            black_box(classic::evaluate_lanes::<T>(&net, k as u64));
        }
    });
}

#[divan::bench]
fn cartpole_one_by_one(b: Bencher) {
    one_by_one::<CartPole>(b);
}

#[divan::bench]
fn cartpole_in_lanes(b: Bencher) {
    in_lanes::<CartPole>(b);
}

#[divan::bench]
fn acrobot_one_by_one(b: Bencher) {
    one_by_one::<Acrobot>(b);
}

#[divan::bench]
fn acrobot_in_lanes(b: Bencher) {
    in_lanes::<Acrobot>(b);
}

#[divan::bench]
fn mountain_car_one_by_one(b: Bencher) {
    one_by_one::<MountainCar>(b);
}

#[divan::bench]
fn mountain_car_in_lanes(b: Bencher) {
    in_lanes::<MountainCar>(b);
}

#[divan::bench]
fn pendulum_one_by_one(b: Bencher) {
    one_by_one::<Pendulum>(b);
}

#[divan::bench]
fn pendulum_in_lanes(b: Bencher) {
    in_lanes::<Pendulum>(b);
}

#[divan::bench]
fn mountain_car_continuous_one_by_one(b: Bencher) {
    one_by_one::<MountainCarContinuous>(b);
}

#[divan::bench]
fn mountain_car_continuous_in_lanes(b: Bencher) {
    in_lanes::<MountainCarContinuous>(b);
}

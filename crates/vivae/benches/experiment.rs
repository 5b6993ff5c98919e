//! Speed of the experiment: one full evaluation (5 robots × 1000 steps, decode
//! included) at the paper's, a re-sampled and a camera resolution, of the
//! default run's champion, and decoding a CPPN onto the paper's substrate.
//!
//! Throughput is reported in robot-steps (one robot, one simulation step with its
//! sensor reading and controller update) and in evaluations.

use divan::counter::ItemsCount;
use vivae_lab::config::Config;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_neat::{Genome, NeatParams, Population, Precision};

fn main() {
    divan::main();
}

/// An evolved-looking CPPN: a few generations of the real experiment's mutations.
fn genome(experiment: &Episode) -> Genome {
    let params = NeatParams {
        population_size: 20,
        ..NeatParams::default()
    };
    let mut pop = Population::new(params, experiment.cppn_spec(), 5).unwrap();
    for _ in 0..15 {
        pop.evaluate(|g, _| g.num_hidden() as f64 + g.num_enabled_links() as f64 * 0.1);
        pop.next_generation();
    }
    pop.evaluate(|g, _| g.num_hidden() as f64 + g.num_enabled_links() as f64 * 0.1);
    pop.champion().unwrap().0.clone()
}

fn experiment(config: &Config) -> Episode {
    let scenario = load_scenario(None).unwrap();
    Episode::new(config, &scenario.scenario).unwrap()
}

/// The default run's champion (`vivae evolve`, seed 1: generation 398,
/// 3.61 px/step; `benches/paper-champion.json`): a controller that drives
/// the loop and turns, as most of a run's evaluations do. The synthetic
/// genome above hardly turns, so its evaluation skips the heading's
/// `sincos` that costs a run 8 %.
fn paper_champion() -> Genome {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/paper-champion.json");
    vivae_lab::tasks::read_champion(std::path::Path::new(path))
        .unwrap()
        .genome
}

/// One evaluation of the default run's champion, in each precision.
#[divan::bench(args = ["exact", "fast"])]
fn evaluation_of_the_paper_champion(bencher: divan::Bencher, precision: &str) {
    let mut config = Config::default();
    config.experiment.precision = precision.parse().unwrap();
    let exp = experiment(&config);
    let g = paper_champion();
    let robot_steps = (exp.robots() as u64) * u64::from(exp.steps());
    bencher
        .counter(ItemsCount::new(robot_steps))
        .bench(|| divan::black_box(exp.fitness(divan::black_box(&g))));
}

/// One evaluation of the paper's experiment: decode + 5 robots × 1000 steps.
#[divan::bench]
fn evaluation_3x5_to_3x3(bencher: divan::Bencher) {
    evaluation_3x5(bencher, Precision::Exact);
}

/// The same in fast precision (`experiment.precision = "fast"`).
#[divan::bench]
fn evaluation_3x5_to_3x3_fast(bencher: divan::Bencher) {
    evaluation_3x5(bencher, Precision::Fast);
}

fn evaluation_3x5(bencher: divan::Bencher, precision: Precision) {
    let mut config = Config::default();
    config.experiment.precision = precision;
    let exp = experiment(&config);
    let g = genome(&exp);
    let robot_steps = (exp.robots() as u64) * u64::from(exp.steps());
    bencher
        .counter(ItemsCount::new(robot_steps))
        .bench(|| divan::black_box(exp.fitness(divan::black_box(&g))));
}

/// The same at the re-sampled resolution 3×6 → 9×9.
#[divan::bench]
fn evaluation_3x6_to_9x9(bencher: divan::Bencher) {
    let mut config = Config::default();
    config.surface_sensors.angles = 6;
    config.substrate.neurons = vivae_lab::controller::substrate::PolarGrid {
        rings: 9,
        angles: 9,
    };
    let exp = experiment(&config);
    let g = genome(&exp);
    let robot_steps = (exp.robots() as u64) * u64::from(exp.steps());
    bencher
        .counter(ItemsCount::new(robot_steps))
        .bench(|| divan::black_box(exp.fitness(divan::black_box(&g))));
}

/// One evaluation at camera resolution: 32×96 surface sensors → 9×9 neurons
/// (decode of 255,474 links + 5 robots × 1000 steps).
#[divan::bench(sample_count = 10, sample_size = 1)]
fn evaluation_32x96_to_9x9(bencher: divan::Bencher) {
    evaluation_32x96(bencher, Precision::Exact);
}

/// The same in fast precision (`experiment.precision = "fast"`).
#[divan::bench(sample_count = 10, sample_size = 1)]
fn evaluation_32x96_to_9x9_fast(bencher: divan::Bencher) {
    evaluation_32x96(bencher, Precision::Fast);
}

fn evaluation_32x96(bencher: divan::Bencher, precision: Precision) {
    let mut config = Config::default();
    config.experiment.precision = precision;
    config.surface_sensors.rings = 32;
    config.surface_sensors.angles = 96;
    config.substrate.neurons = vivae_lab::controller::substrate::PolarGrid {
        rings: 9,
        angles: 9,
    };
    let exp = experiment(&config);
    let g = genome(&exp);
    let robot_steps = (exp.robots() as u64) * u64::from(exp.steps());
    bencher
        .counter(ItemsCount::new(robot_steps))
        .bench(|| divan::black_box(exp.fitness(divan::black_box(&g))));
}

/// Decoding the paper's substrate (15 inputs, 9 neurons: 225 CPPN queries).
#[divan::bench]
fn decode_paper_substrate(bencher: divan::Bencher) {
    let exp = experiment(&Config::default());
    let g = genome(&exp);
    bencher.bench(|| divan::black_box(exp.controller(divan::black_box(&g)).unwrap()));
}

//! Speed of the figures a run draws at its end, at camera resolution: the
//! network of a 32×96 → 9×9 champion (~250,000 links, drawn as receptive
//! fields), the convergence figure of a 400-generation run of 100, and the
//! trajectory figure of one episode.
//!
//! The champion is the paper's (tests/data/paper-champion.json) re-sampled to
//! 32×96 sensors and 9×9 neurons, as `--sensors 32x96 --neurons 9x9` do.

use vivae::figures::convergence::{self, ConvergenceOptions};
use vivae::figures::network::{self, NetworkOptions};
use vivae_lab::config::Config;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_neat::hyperneat::SubstrateController;
use vivae_sim::draw::{self, DrawOptions};

fn main() {
    divan::main();
}

/// The camera-resolution experiment and its champion's controller.
fn camera() -> (Episode, SubstrateController) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/paper-champion.json"
    );
    let champion = vivae_lab::tasks::read_champion(std::path::Path::new(path)).unwrap();
    let mut config = Config::default();
    config.surface_sensors.rings = 32;
    config.surface_sensors.angles = 96;
    config.substrate.neurons = PolarGrid::new(9, 9).unwrap();
    let scenario = load_scenario(None).unwrap();
    let experiment = Episode::new(&config, &scenario.scenario).unwrap();
    let controller = experiment.controller(&champion.genome).unwrap();
    (experiment, controller)
}

/// The network figure, SVG and PNG, as the end of a run writes it.
#[divan::bench]
fn network_32x96_to_9x9(bencher: divan::Bencher) {
    let (experiment, controller) = camera();
    let opts = NetworkOptions::default();
    bencher.bench(|| network::render(experiment.substrate_spec(), &controller, &opts).unwrap());
}

/// The network figure's SVG alone, as `report.html` embeds it.
#[divan::bench]
fn network_svg_32x96_to_9x9(bencher: divan::Bencher) {
    let (experiment, controller) = camera();
    let opts = NetworkOptions::default();
    bencher.bench(|| network::figure_svg(experiment.substrate_spec(), &controller, &opts).unwrap());
}

/// Decoding the champion at 32×96 → 9×9 (the figure's first step at the end of a run).
#[divan::bench]
fn decode_32x96_to_9x9(bencher: divan::Bencher) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/paper-champion.json"
    );
    let champion = vivae_lab::tasks::read_champion(std::path::Path::new(path)).unwrap();
    let (experiment, _) = camera();
    bencher.bench(|| experiment.controller(&champion.genome).unwrap());
}

/// The convergence figure of the default run's size: 400 generations × 100.
#[divan::bench]
fn convergence_400_generations(bencher: divan::Bencher) {
    let generations: Vec<Vec<f64>> = (0..400)
        .map(|g| {
            (0..100)
                .map(|i| f64::from(g) / 100.0 + f64::from(i % 17) * 0.05)
                .collect()
        })
        .collect();
    let opts = ConvergenceOptions::default();
    bencher.bench(|| convergence::render(&generations, &opts).unwrap());
}

/// The trajectory figure of one recorded champion episode (drawing only).
#[divan::bench]
fn trajectories_drawing(bencher: divan::Bencher) {
    let (experiment, controller) = camera();
    let (_, world) = experiment.run_world(&controller, true);
    let opts = DrawOptions {
        trajectories: true,
        title: Some("Champion".into()),
        ..DrawOptions::default()
    };
    bencher.bench(|| {
        let svg = draw::render_svg(&world, &opts);
        let png = draw::render_png(&world, &opts).unwrap();
        (svg, png)
    });
}

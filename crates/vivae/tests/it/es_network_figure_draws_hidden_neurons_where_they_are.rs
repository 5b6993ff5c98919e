//! The network figure of an ES-HyperNEAT controller draws every discovered
//! hidden neuron (at its place in the plane) and its links, at the paper's
//! sensor sheet and at camera resolution.
//!
//! The CPPN is the paper's evolved champion (tests/data/paper-champion.json)
//! decoded as ES-HyperNEAT. `VIVAE_FIGURES=docs/figures cargo test --release
//! -p vivae --test it es_network_figure` also writes the PNGs
//! (`es-network-3x5.png`, `es-network-32x96.png`).

use std::path::Path;

use vivae::figures::network::{self, NetworkOptions};
use vivae::tasks::driving::substrate;
use vivae_lab::config::Config;
use vivae_lab::controller::es::SubstrateKind;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;

/// The champion as an ES controller on `sensors`: (hidden neurons, links, SVG).
fn figure(sensors: (usize, usize)) -> (usize, usize, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/paper-champion.json");
    let champion = vivae_lab::tasks::read_champion(&path).unwrap();
    let mut config = Config::default();
    config.substrate.kind = SubstrateKind::EsHyperneat;
    config.surface_sensors.rings = sensors.0;
    config.surface_sensors.angles = sensors.1;
    let scenario = load_scenario(None).unwrap();
    let experiment = Episode::new(&config, &scenario.scenario).unwrap();
    let controller = experiment.robot_controller(&champion.genome).unwrap();
    let es = controller.as_es().unwrap();
    let options = NetworkOptions {
        title: format!(
            "Paper champion as ES-HyperNEAT, {}x{} sensors",
            sensors.0, sensors.1
        ),
        ..NetworkOptions::default()
    };
    let fig = network::render_robot(substrate(&experiment), &controller, &options).unwrap();
    assert_eq!(&fig.png[..8], b"\x89PNG\r\n\x1a\n");
    if let Ok(dir) = std::env::var("VIVAE_FIGURES") {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let name = format!("es-network-{}x{}.png", sensors.0, sensors.1);
        std::fs::write(root.join(dir).join(name), &fig.png).unwrap();
    }
    (es.hidden_neurons(), es.expressed_links(), fig.svg)
}

/// Circles of radius `r` in an SVG.
fn circles(svg: &str, r: u32) -> usize {
    svg.matches(&format!("r=\"{r}\"")).count()
}

#[test]
fn es_network_figure_draws_every_hidden_neuron_and_link() {
    let (hidden, links, svg) = figure((3, 5));
    assert!(hidden > 0 && links > 0, "{hidden} hidden, {links} links");
    assert!(svg.contains(&format!("{hidden} hidden neurons found, {links} links")));
    // Each hidden neuron is a filled dot and its outline (and the legend has a sensor dot).
    assert_eq!(circles(&svg, 6), 2 * hidden + 1);
    // One curve per link (plus frame, axes and guides).
    assert!(svg.matches("<polyline").count() >= links);
}

#[test]
fn es_network_figure_at_camera_resolution_stays_bounded() {
    let (hidden, links, svg) = figure((32, 96));
    assert!(hidden > 0);
    assert_eq!(circles(&svg, 6), 2 * hidden + 1);
    if links > 4000 {
        assert!(svg.contains("the strongest 4000 drawn"));
    }
    assert!(svg.len() < 8 << 20, "SVG of {} bytes", svg.len());
}

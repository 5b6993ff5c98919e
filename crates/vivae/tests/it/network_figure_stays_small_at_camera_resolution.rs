//! The network figure of a camera-resolution controller (32×96 sensors → 9×9
//! neurons, ~250,000 links) is drawn as receptive fields and stays small; the
//! paper's 3×5 → 3×3 controller keeps its line-per-link drawing.
//!
//! The controllers are the paper's evolved champion (tests/data/paper-champion.json,
//! generation 398 of the default run) re-sampled, as `--sensors`/`--neurons` do.
//! `VIVAE_FIGURES=docs/figures cargo test --release -p vivae --test it
//! network_figure_stays_small_at_camera_resolution` also writes the PNGs the
//! guide shows (`network-3x5.png`, `network-20x60.png`, `network-32x96.png`).

use std::path::Path;

use vivae::figures::network::{self, NetworkOptions};
use vivae_lab::config::Config;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;

/// The paper's champion decoded on `sensors` → `neurons`, and its figure.
fn figure(sensors: (usize, usize), neurons: (usize, usize)) -> (usize, vivae::figures::Figure) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/paper-champion.json");
    let champion = vivae_lab::tasks::read_champion(&path).unwrap();
    let mut config = Config::default();
    config.surface_sensors.rings = sensors.0;
    config.surface_sensors.angles = sensors.1;
    config.substrate.neurons = PolarGrid::new(neurons.0, neurons.1).unwrap();
    let scenario = load_scenario(None).unwrap();
    let experiment = Episode::new(&config, &scenario.scenario).unwrap();
    let controller = experiment.controller(&champion.genome).unwrap();
    let options = NetworkOptions {
        title: format!(
            "Paper champion re-sampled to {}x{} sensors, {}x{} neurons",
            sensors.0, sensors.1, neurons.0, neurons.1
        ),
        ..NetworkOptions::default()
    };
    let fig = network::render(experiment.substrate_spec(), &controller, &options).unwrap();
    if let Ok(dir) = std::env::var("VIVAE_FIGURES") {
        // Relative to the workspace root, where the command is typed.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let name = format!("network-{}x{}.png", sensors.0, sensors.1);
        std::fs::write(root.join(dir).join(name), &fig.png).unwrap();
    }
    (controller.expressed_links(), fig)
}

#[test]
fn camera_controller_is_drawn_as_receptive_fields_in_a_few_megabytes() {
    let (links, fig) = figure((32, 96), (9, 9));
    assert!(links > 200_000, "{links} links");
    // The link drawing of this controller was a 29 MB SVG; heat maps cost pixels, not links.
    assert!(fig.svg.len() < 4 << 20, "SVG of {} bytes", fig.svg.len());
    assert!(fig.png.len() < 4 << 20, "PNG of {} bytes", fig.png.len());
    // Outlines and ticks only: no line per link.
    assert!(fig.svg.matches("<polyline").count() < 200);
    // Panel grid, recurrent matrix and bias row, embedded as PNG images.
    assert_eq!(fig.svg.matches("<image ").count(), 3);
    assert_eq!(fig.svg.matches("href=\"data:image/png;base64,").count(), 3);
    for label in [
        "drawn as receptive fields",
        "32x96",
        "recurrent weights",
        ">\nbias\n<",
        ">\nL\n<",
        ">\nR\n<",
    ] {
        assert!(fig.svg.contains(label), "missing {label:?}");
    }
    assert_eq!(&fig.png[..8], b"\x89PNG\r\n\x1a\n");
}

#[test]
fn a_20x60_controller_is_drawn_as_receptive_fields_too() {
    let (links, fig) = figure((20, 60), (9, 9));
    assert!(links > 400);
    assert!(fig.svg.contains("drawn as receptive fields"));
    assert!(fig.svg.len() < 4 << 20 && fig.png.len() < 4 << 20);
}

#[test]
fn paper_controller_keeps_a_line_per_link() {
    let (links, fig) = figure((3, 5), (3, 3));
    assert!(links <= 216);
    assert!(!fig.svg.contains("<image "));
    assert!(fig.svg.contains("expressed of 216 possible links"));
    assert!(fig.svg.matches("<polyline").count() > links / 2);
}

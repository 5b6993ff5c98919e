//! The viewer page in a real headless Chromium draws an ES-HyperNEAT
//! controller's discovered hidden neurons where the CPPN put them, coloured
//! by their activity (issue 22 item 4), at the paper's 3×5 sensors and at
//! camera resolution (32×96). Skipped, with a SKIPPED note, without chromium.
//! Screenshots (`view-es-3x5.png`, `view-es-32x96.png`) are left in
//! `target/…/browser-screenshots/` to look at.

use std::path::{Path, PathBuf};

use crate::common::browser::{Browser, Viewer, shots};
use crate::common::scratch;
use vivae_lab::config::Config;
use vivae_lab::controller::es::SubstrateKind;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::scenarios::load_scenario;

/// The paper's champion (tests/data) as a genome file that records an
/// ES-HyperNEAT config, so that the viewer decodes it as ES.
fn es_champion_file(dir: &Path) -> PathBuf {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/paper-champion.json");
    let mut champion: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(data).unwrap()).unwrap();
    champion["config"] = serde_json::to_value(es_config((3, 5))).unwrap();
    let path = dir.join("es-champion.json");
    std::fs::write(&path, champion.to_string()).unwrap();
    path
}

fn es_config(sensors: (usize, usize)) -> Config {
    let mut config = Config::default();
    config.substrate.kind = SubstrateKind::EsHyperneat;
    config.surface_sensors.rings = sensors.0;
    config.surface_sensors.angles = sensors.1;
    config
}

/// The champion's hidden neurons' places when decoded on `sensors`.
fn hidden_neurons(champion: &Path, sensors: (usize, usize)) -> Vec<[f64; 2]> {
    let champion = vivae_lab::tasks::read_champion(champion).unwrap();
    let scenario = load_scenario(None).unwrap();
    let experiment = Episode::new(&es_config(sensors), &scenario.scenario).unwrap();
    let controller = experiment.robot_controller(&champion.genome).unwrap();
    controller.as_es().unwrap().network().hidden().to_vec()
}

/// Waits until the page draws `hidden` hidden neurons and gets their activity.
fn wait_for_hidden(b: &Browser, hidden: usize, what: &str) {
    b.wait_for(
        &format!(
            "var v = window.vivaeView;
             return v.hidden === {hidden} && v.hiddenDrawn === {hidden} &&
                    v.activations === {hidden} + 2 && v.frames > 5;"
        ),
        what,
    );
}

/// How many of `places` (CPPN plane) are painted on the neuron panel.
fn painted(b: &Browser, places: &[[f64; 2]]) -> u64 {
    let places = serde_json::to_string(places).unwrap();
    b.eval(&format!(
        "var c = document.getElementById('neuronpanel'), g = c.getContext('2d');
         var half = Math.min(c.width, c.height) / 2 - 10, n = 0;
         {places}.forEach(function (p) {{
           var x = Math.round(c.width / 2 + p[0] * half), y = Math.round(c.height / 2 - p[1] * half);
           if (g.getImageData(x, y, 1, 1).data[3] > 0) {{ n += 1; }}
         }});
         return n;"
    ))
    .as_u64()
    .unwrap()
}

#[test]
fn an_es_run_shows_its_hidden_neurons_where_they_are_at_low_and_high_resolution() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-es");
    let champion = es_champion_file(&dir);
    let low = hidden_neurons(&champion, (3, 5));
    let high = hidden_neurons(&champion, (32, 96));
    assert!(!low.is_empty() && !high.is_empty());
    let v = Viewer::start(&[champion.as_os_str()]);
    b.goto(&v.url);
    wait_for_hidden(&b, low.len(), "the 3×5 ES network's hidden neurons drawn");
    let count = b.eval("return document.getElementById('neuroncount').textContent;");
    assert!(
        count
            .as_str()
            .unwrap()
            .starts_with(&format!("ES-HyperNEAT: {} hidden neurons found", low.len())),
        "{count}"
    );
    assert_eq!(painted(&b, &low), low.len() as u64);
    b.save_screenshot(&shots().join("view-es-3x5.png"));

    // Re-sampled: new sensors grow new quadtrees, so other hidden neurons.
    b.eval(
        "document.getElementById('sensors').value = '32x96';
         document.getElementById('apply').click(); return true;",
    );
    b.wait_for("return window.vivaeView.sensors === 3072;", "32×96 sensors");
    wait_for_hidden(
        &b,
        high.len(),
        "the 32×96 ES network's hidden neurons drawn",
    );
    assert_eq!(painted(&b, &high), high.len() as u64);
    b.save_screenshot(&shots().join("view-es-32x96.png"));

    // Nobody driving: no network, the dense sheet's panel again.
    b.eval(
        "var s = document.getElementById('controller'); s.value = 'none'; s.onchange(); return true;",
    );
    b.wait_for(
        "var v = window.vivaeView; return v.hidden === 0 && v.hiddenDrawn === 0 && v.activations === 0;",
        "no hidden neurons without a controller",
    );
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

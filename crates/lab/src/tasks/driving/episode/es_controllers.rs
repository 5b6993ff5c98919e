//! ES-HyperNEAT controllers as an episode builds and drives them: tests of
//! `controller::es` that need an [`Episode`], which that module does not import.

use vivae_neat::hyperneat::es::decode_es_genome;
use vivae_neat::{Network, Population};

use super::Episode;
use crate::config::Config;
use crate::controller::es::tests::{es_config, leo_config};
use crate::controller::es::{ES_LEO_OUTPUT, es_wheel_nodes};
use crate::controller::polar::{SURFACE_OUTPUT, WHEEL_RADIUS};
use crate::tasks::scenarios::load_scenario;

fn experiment(config: &Config) -> Episode {
    Episode::new(config, &load_scenario(None).unwrap().scenario).unwrap()
}

#[test]
fn rollout_steps_each_robot_as_the_reference_network_does() {
    let exp = experiment(&es_config());
    let pop = Population::new(es_config().neat, exp.cppn_spec(), 5).unwrap();
    let mut checked = 0;
    for g in pop.genomes().iter().take(40) {
        let controller = exp.robot_controller(g).unwrap();
        let es = controller.as_es().unwrap();
        if es.hidden_neurons() == 0 {
            continue;
        }
        checked += 1;
        let mut nets = vec![es.network().clone(); exp.robots()];
        let mut world = exp.world().clone();
        let mut rollout = exp.rollout(&controller);
        let mut inputs = vec![0.0; es.network().num_inputs()];
        let mut want = [0.0; 2];
        for _ in 0..exp.steps() {
            let mut expected = Vec::new();
            for (robot, net) in nets.iter_mut().enumerate() {
                exp.read_inputs(&world, robot, &mut inputs);
                net.activate(&inputs, &mut want);
                expected.push(want);
            }
            rollout.step(&mut world, &controller, None);
            let ni = es.network().num_inputs();
            for (robot, e) in expected.iter().enumerate() {
                assert_eq!(rollout.outputs(robot), e);
                assert_eq!(rollout.controls(robot), *e);
                // What the viewer draws: every node, the wheels after the inputs.
                let values = rollout.node_values(robot).unwrap();
                assert_eq!(values.len(), es.network().num_nodes());
                assert_eq!(&values[ni..ni + 2], e);
            }
        }
    }
    assert!(checked >= 5, "only {checked} genomes with hidden neurons");
}

#[test]
fn default_and_es_substrates_decode_the_same_genome() {
    let polar = experiment(&Config::default());
    let es = experiment(&es_config());
    assert_eq!(polar.cppn_spec(), es.cppn_spec());
    let g = &Population::new(Config::default().neat, polar.cppn_spec(), 1)
        .unwrap()
        .genomes()[0]
        .clone();
    let dense = polar.robot_controller(g).unwrap();
    assert!(dense.as_polar().is_some());
    assert!(polar.rollout(&dense).node_values(0).is_none());
    assert!(es.robot_controller(g).unwrap().as_es().is_some());
    assert!(
        es.controller(g).is_err(),
        "an ES experiment has no dense sheet"
    );
    // A default config writes neither key: existing configs and runs are unchanged.
    let text = toml::to_string(&Config::default()).unwrap();
    assert!(
        !text.contains("kind") && !text.contains("[substrate.es]"),
        "{text}"
    );
}

#[test]
fn wheel_neurons_sit_on_the_wheel_ring_behind_the_sensors() {
    let [l, r] = es_wheel_nodes();
    let (l, r) = (l.cartesian(), r.cartesian());
    let s = WHEEL_RADIUS * std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        (l[0] + s).abs() < 1e-12 && (l[1] + s).abs() < 1e-12,
        "{l:?}"
    );
    assert!(
        (r[0] - s).abs() < 1e-12 && (r[1] + s).abs() < 1e-12,
        "{r:?}"
    );
    // A 270° sensor sheet puts a node on them: refused, not merged.
    let mut config = es_config();
    config.surface_sensors.angles = 7;
    config.surface_sensors.fov = 270.0;
    let e = Episode::new(&config, &load_scenario(None).unwrap().scenario).unwrap_err();
    assert!(e.to_string().contains("surface_sensors.fov"), "{e}");
}

#[test]
fn normalize_scales_the_sensor_links_of_a_resampled_sheet() {
    let mut config = es_config();
    config.surface_sensors.angles = 6;
    let exp = experiment(&config);
    let setup = exp.es_setup().unwrap();
    assert!(setup.input_scale.iter().all(|&f| f == 15.0 / 18.0));
    let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 2).unwrap();
    for g in pop.genomes().iter().take(10) {
        let raw = decode_es_genome(g, &setup.layout, &setup.params).unwrap();
        let scaled = exp.robot_controller(g).unwrap();
        let scaled = scaled.as_es().unwrap().network();
        assert_eq!(raw.links().len(), scaled.links().len());
        for (a, b) in raw.links().iter().zip(scaled.links()) {
            let f = if a.source < 18 { 15.0 / 18.0 } else { 1.0 };
            assert_eq!(a.weight * f, b.weight);
        }
    }
}

#[test]
fn leo_expresses_only_links_whose_cppn_output_2_is_positive_and_drops_the_threshold() {
    let config = leo_config();
    let exp = experiment(&config);
    let setup = exp.es_setup().unwrap();
    assert_eq!(setup.layout.leo_output, Some(ES_LEO_OUTPUT));
    // Without the key nothing changes: the weight threshold decides.
    let plain = experiment(&es_config());
    assert_eq!(plain.es_setup().unwrap().layout.leo_output, None);
    assert_eq!(plain.cppn_spec(), exp.cppn_spec());

    let genomes =
        crate::search::leo_seeded(&exp.cppn_spec(), &config.neat, config.experiment.seed).unwrap();
    let hyper = config.hyperneat;
    let (mut links, mut below_threshold) = (0, 0);
    for g in genomes.iter().take(40) {
        let controller = exp.robot_controller(g).unwrap();
        let net = controller.as_es().unwrap().network();
        // The library's decode with the same layout gives the same links.
        let raw = decode_es_genome(g, &setup.layout, &setup.params).unwrap();
        assert_eq!(raw.links().len(), net.links().len());
        let ni = setup.layout.inputs.len();
        let pos = |i: usize| match i {
            i if i < ni => setup.layout.inputs[i],
            i if i < ni + 2 => setup.layout.outputs[i - ni],
            i => net.hidden()[i - ni - 2],
        };
        let mut cppn = vivae_neat::feedforward::FeedForwardNetwork::from_genome(g);
        let mut out = [0.0; 3];
        for l in net.links() {
            let ([x1, y1], [x2, y2]) = (pos(l.target), pos(l.source));
            cppn.activate(&[x1, y1, x2, y2, 1.0], &mut out);
            assert!(out[ES_LEO_OUTPUT] > 0.0, "link {l:?}: LEO output {out:?}");
            let scale = setup.input_scale.get(l.source).copied().unwrap_or(1.0);
            assert_eq!(
                l.weight,
                out[SURFACE_OUTPUT].clamp(-1.0, 1.0) * hyper.amplitude * scale
            );
            links += 1;
            below_threshold += usize::from(out[SURFACE_OUTPUT].abs() <= hyper.threshold);
        }
    }
    assert!(links > 0, "no seeded genome expressed a link");
    assert!(
        below_threshold > 0,
        "LEO expressed no link the threshold would have dropped ({links} links)"
    );
}

#[test]
fn leo_seed_starts_every_strategy_that_takes_a_population_from_seeded_genomes_drawn_from_the_run_seed()
 {
    use crate::search::Search;
    use vivae_neat::activation::Activation;
    use vivae_neat::genome::NodeKind;
    use vivae_neat::hyperneat::CPPN_INPUTS;
    let config = leo_config();
    let exp = experiment(&config);
    let space = crate::search::BehaviourSpace {
        lower: vec![0.0],
        upper: vec![1.0],
        names: vec!["x".into()],
    };
    let search = |c: &Config| {
        let metrics = crate::tasks::metric_names(c);
        Search::new(c, exp.cppn_spec(), &space, None, metrics).unwrap()
    };
    let a = search(&config).batch();
    assert_eq!(a, search(&config).batch(), "the seed is not deterministic");
    assert_eq!(a.len(), config.neat.population_size);
    for g in &a {
        // One hidden node, the Gaussian of Δx, feeding the LEO output.
        assert_eq!(g.num_hidden(), 1, "{g:?}");
        let hidden = g
            .nodes()
            .iter()
            .find(|n| n.kind == NodeKind::Hidden)
            .unwrap();
        assert_eq!(hidden.activation, Activation::Gaussian);
        let leo_node = (CPPN_INPUTS + ES_LEO_OUTPUT) as u32;
        assert!(
            g.links()
                .iter()
                .any(|l| l.from == hidden.id && l.to == leo_node)
        );
    }
    // Another run seed draws other weights; without the key the genomes are minimal.
    let mut other = config.clone();
    other.experiment.seed += 1;
    assert_ne!(a, search(&other).batch());
    let mut unseeded = config.clone();
    unseeded.substrate.es.leo_seed = false;
    assert!(
        search(&unseeded)
            .batch()
            .iter()
            .all(|g| g.num_hidden() == 0)
    );
    // Every strategy that starts from given genomes starts from the same ones.
    let takers = crate::search::entries()
        .into_iter()
        .filter(|e| e.takes_population);
    for e in takers {
        let mut other = config.clone();
        crate::search::StrategyConfig::update(&mut other, |s| s.kind = e.kind.into());
        assert_eq!(search(&other).batch(), a, "{}", e.kind);
    }
}

#[test]
fn a_feed_forward_es_net_links_the_sensors_ahead_to_the_wheels_behind() {
    use vivae_neat::hyperneat::es::{EsParams, Flow};
    let mut config = es_config();
    config.substrate.es.recurrent = false;
    let exp = experiment(&config);
    let setup = exp.es_setup().unwrap();
    assert_eq!(setup.params.flow, Flow::Downward);
    // Why the paper's upward rule cannot work here: every sensor lies above
    // both wheel neurons, so no input → output path goes upward.
    let lowest_sensor = setup
        .layout
        .inputs
        .iter()
        .map(|p| p[1])
        .fold(f64::MAX, f64::min);
    assert!(setup.layout.outputs.iter().all(|w| w[1] < lowest_sensor));
    let upward = EsParams {
        flow: Flow::Upward,
        ..setup.params
    };
    let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 3).unwrap();
    let (mut links, mut hidden, mut upward_links) = (0, 0, 0);
    for g in pop.genomes().iter().take(40) {
        upward_links += decode_es_genome(g, &setup.layout, &upward)
            .unwrap()
            .links()
            .len();
        let controller = exp.robot_controller(g).unwrap();
        let net = controller.as_es().unwrap().network();
        assert!(!net.is_recurrent());
        let ni = setup.layout.inputs.len();
        let y = |i: usize| match i {
            i if i < ni => setup.layout.inputs[i][1],
            i if i < ni + 2 => setup.layout.outputs[i - ni][1],
            i => net.hidden()[i - ni - 2][1],
        };
        for l in net.links() {
            assert!(y(l.source) > y(l.target), "link {l:?} does not go backward");
        }
        links += net.links().len();
        hidden += net.num_hidden();
    }
    assert_eq!(upward_links, 0);
    assert!(links > 40 && hidden > 0, "links {links}, hidden {hidden}");
}

#[test]
fn a_feed_forward_es_net_in_polar_coordinates_is_refused_saying_what_to_change() {
    let mut config = es_config();
    config.substrate.es.recurrent = false;
    config.substrate.coordinates = crate::controller::polar::CoordMode::Polar;
    // By the config's own check (`vivae config check`) and by the episode.
    let checked = config.validate().unwrap_err().to_string();
    let built = Episode::new(&config, &load_scenario(None).unwrap().scenario)
        .unwrap_err()
        .to_string();
    for e in [checked, built] {
        assert!(
            e.contains("substrate.es.recurrent = false") && e.contains("substrate.coordinates"),
            "{e}"
        );
        assert_eq!(e.lines().count(), 1, "{e}");
    }
    // Recurrent, polar coordinates are fine.
    config.substrate.es.recurrent = true;
    assert!(config.validate().is_ok());
}

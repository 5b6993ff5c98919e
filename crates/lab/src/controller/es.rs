//! ES-HyperNEAT as the robots' substrate (`substrate.kind = "es-hyperneat"`):
//! the CPPN decides where hidden neurons go in the polar plane and how many.
//!
//! The inputs are the robots' sensor nodes where they sit in the polar
//! substrate plane ([`layout_of`](crate::controller::substrate::layout_of)); the outputs
//! are the two wheel neurons. Their place cannot be the dense sheet's
//! `(∓2/3, 0)`: a 3-ring sensor sheet over 180° has a node exactly there, and
//! in ES-HyperNEAT a node's position is its identity (one plane, one weight
//! output). They sit on the same wheel ring (`ρ = 2/3`) at `φ = ∓135°`,
//! behind-left and behind-right, where no sensor of a field of view up to
//! 270° looks. Hidden neurons are discovered anywhere in `[−1, 1]²`, with
//! recurrent links by default (the paper's controller is recurrent).
//!
//! The CPPN keeps the polar substrate's outputs: output 0 (surface sensors →
//! neurons) paints every ES link, output 1 the biases; output 2 is unused, so
//! one genome decodes as either kind. With `substrate.es.leo` output 2
//! ([`ES_LEO_OUTPUT`]) becomes the link expression output (HyperNEAT-LEO): a
//! link exists iff it is > 0, and the weight threshold no longer applies.
//! `substrate.normalize` scales the links leaving the sensors as it does on
//! the dense sheet.

use vivae_neat::hyperneat::SubstrateController;
use vivae_neat::hyperneat::es::{EsLayout, EsParams, decode_es_genome};
use vivae_neat::hyperneat::{HyperError, SparseLink, SparseNetwork};
use vivae_neat::{Genome, Network};

use crate::config::Config;
pub use crate::config::es::{ES_LEO_OUTPUT, EsConfig, SubstrateKind};
use crate::controller::polar::{
    BIAS_OUTPUT, CoordMode, PolarNode, SURFACE_OUTPUT, WHEEL_RADIUS, WheelNeurons,
};
use crate::controller::sensors::SensorSheet;
use crate::tasks::driving::rollout::{Drive, RobotStates};

/// Where the wheel neurons sit in the ES plane: on the wheel ring at ∓135°.
pub const ES_WHEEL_ANGLE_DEG: f64 = 135.0;

/// The wheel neurons' nodes in the ES plane, left then right.
pub fn es_wheel_nodes() -> [PolarNode; 2] {
    let phi = ES_WHEEL_ANGLE_DEG.to_radians();
    let node = |phi| PolarNode {
        ring: 0,
        angle_index: 0,
        rho: WHEEL_RADIUS,
        phi,
    };
    [node(-phi), node(phi)]
}

/// What an experiment needs to decode its genomes into ES controllers.
#[derive(Debug, Clone, PartialEq)]
pub struct EsSetup {
    /// Sensor nodes (inputs) and wheel neurons (outputs) in the CPPN's plane.
    pub layout: EsLayout,
    /// Quadtree, thresholds, recurrence and weight expression.
    pub params: EsParams,
    /// The factor of each input's outgoing links (`substrate.normalize`).
    pub input_scale: Vec<f64>,
}

impl EsSetup {
    /// The ES substrate over `sheets` (the surface sensors only) in `mode`,
    /// inputs' links scaled by `input_scale`, links expressed by LEO (CPPN
    /// output [`ES_LEO_OUTPUT`]) if `leo`; an error says what does not fit.
    pub fn new(
        sheets: &[SensorSheet],
        mode: CoordMode,
        params: EsParams,
        input_scale: Vec<f64>,
        leo: bool,
    ) -> Result<EsSetup, String> {
        if sheets.iter().any(|s| s.cppn_output != SURFACE_OUTPUT) {
            return Err(
                "substrate.kind = \"es-hyperneat\" reads the surface sensors only: \
                 set distance_sensors.rays = 0"
                    .into(),
            );
        }
        let inputs: Vec<[f64; 2]> = sheets
            .iter()
            .flat_map(|s| s.nodes())
            .map(|n| n.coords(mode))
            .collect();
        let layout = EsLayout {
            inputs,
            outputs: es_wheel_nodes().iter().map(|n| n.coords(mode)).collect(),
            weight_output: SURFACE_OUTPUT,
            bias_output: Some(BIAS_OUTPUT),
            leo_output: leo.then_some(ES_LEO_OUTPUT),
        };
        layout.check(ES_LEO_OUTPUT + 1).map_err(|e| {
            format!(
                "substrate.kind = \"es-hyperneat\": {e} (the wheel neurons sit at ∓{ES_WHEEL_ANGLE_DEG}° on ring 2/3, \
                 and a 360° sheet has two nodes at ±180°): narrow surface_sensors.fov"
            )
        })?;
        params
            .validate()
            .map_err(|e| format!("substrate.es: {e}"))?;
        Ok(EsSetup {
            layout,
            params,
            input_scale,
        })
    }

    /// Decodes `genome` into the robots' ES controller.
    pub fn decode(&self, genome: &Genome) -> Result<EsController, HyperError> {
        let net = decode_es_genome(genome, &self.layout, &self.params)?;
        EsController::new(net, &self.input_scale)
    }
}

/// The ES substrate of `config` over its `sensors` (`factors`: the
/// [`SourceScale`](crate::controller::normalize::SourceScale) factor of each source,
/// inputs first); an error names the key that does not fit.
pub fn es_setup(
    config: &Config,
    sensors: &[SensorSheet],
    factors: &[f64],
) -> Result<EsSetup, String> {
    let sub = &config.substrate;
    let unused = if !sub.recurrence.is_full() {
        Some("substrate.recurrence (use substrate.es.recurrent)")
    } else if !sub.train_neurons.is_empty() {
        Some("substrate.train_neurons (there is no neuron sheet)")
    } else if !sub.normalize_self_loops {
        Some("substrate.normalize_self_loops (there is no neuron sheet)")
    } else {
        None
    };
    if let Some(key) = unused {
        return Err(format!(
            "{key} does not apply to substrate.kind = \"es-hyperneat\": remove it"
        ));
    }
    sub.es.validate()?;
    let inputs: usize = sensors.iter().map(SensorSheet::len).sum();
    EsSetup::new(
        sensors,
        sub.coordinates,
        sub.es.params(config.hyperneat),
        factors[..inputs].to_vec(),
        sub.es.leo,
    )
}

/// A decoded ES-HyperNEAT network driving the wheels: output 0 is the left
/// wheel, output 1 the right.
#[derive(Debug, Clone, PartialEq)]
pub struct EsController {
    net: SparseNetwork,
}

impl EsController {
    /// `net` with the links leaving input `i` scaled by `input_scale[i]` (a
    /// factor of 1 leaves a weight's bits untouched).
    pub fn new(net: SparseNetwork, input_scale: &[f64]) -> Result<EsController, HyperError> {
        let ni = net.num_inputs();
        if input_scale.len() != ni {
            return Err(HyperError::Inconsistent("one scale per input"));
        }
        if input_scale.iter().all(|&f| f == 1.0) {
            return Ok(EsController { net });
        }
        let links: Vec<SparseLink> = net
            .links()
            .iter()
            .map(|l| match input_scale.get(l.source) {
                Some(&f) if f != 1.0 => SparseLink {
                    weight: l.weight * f,
                    ..*l
                },
                _ => *l,
            })
            .collect();
        let net = SparseNetwork::new(
            ni,
            net.num_outputs(),
            net.hidden().to_vec(),
            net.biases().to_vec(),
            links,
        )?;
        Ok(EsController { net })
    }

    /// The decoded network (inputs, the two wheel neurons, then hidden nodes).
    pub fn network(&self) -> &SparseNetwork {
        &self.net
    }

    /// Number of hidden neurons discovered.
    pub fn hidden_neurons(&self) -> usize {
        self.net.num_hidden()
    }

    /// Number of links.
    pub fn expressed_links(&self) -> usize {
        self.net.links().len()
    }

    /// Links the network's nodes could have: every non-input node from every node.
    pub fn possible_links(&self) -> usize {
        let n = self.net.num_nodes();
        n * (n - self.net.num_inputs())
    }
}

impl Drive for EsController {
    fn num_inputs(&self) -> usize {
        self.net.num_inputs()
    }

    fn num_outputs(&self) -> usize {
        self.net.num_outputs()
    }

    fn robot_states(&self, robots: usize) -> RobotStates {
        let n = self.net.num_nodes();
        RobotStates::Es {
            values: vec![0.0; robots * n],
            next: vec![0.0; robots * n],
        }
    }

    fn step_robots(&self, states: &mut RobotStates, inputs: &[f64], outputs: &mut [f64]) {
        let RobotStates::Es { values, next } = states else {
            panic!("an ES controller steps ES states (Rollout::new built them)");
        };
        let (n, ni, no) = (self.net.num_nodes(), self.num_inputs(), self.num_outputs());
        let robots = values.chunks_exact_mut(n).zip(next.chunks_exact_mut(n));
        let io = inputs.chunks_exact(ni).zip(outputs.chunks_exact_mut(no));
        for ((v, x), (i, o)) in robots.zip(io) {
            self.net.activate_in(v, x, i, o);
        }
    }

    fn wheel_outputs(&self) -> Option<WheelNeurons> {
        Some(WheelNeurons { left: 0, right: 1 })
    }
}

/// The controller of an experiment: the dense polar sheet or an ES network.
#[derive(Debug, Clone, PartialEq)]
pub enum RobotController {
    /// The dense polar substrate (`substrate.kind = "polar"`).
    Polar(SubstrateController),
    /// An ES-HyperNEAT network (`substrate.kind = "es-hyperneat"`).
    Es(EsController),
}

impl RobotController {
    /// The dense controller, if this is one.
    pub fn as_polar(&self) -> Option<&SubstrateController> {
        match self {
            RobotController::Polar(c) => Some(c),
            RobotController::Es(_) => None,
        }
    }

    /// The ES controller, if this is one.
    pub fn as_es(&self) -> Option<&EsController> {
        match self {
            RobotController::Polar(_) => None,
            RobotController::Es(c) => Some(c),
        }
    }

    /// Number of links expressed.
    pub fn expressed_links(&self) -> usize {
        match self {
            RobotController::Polar(c) => c.expressed_links(),
            RobotController::Es(c) => c.expressed_links(),
        }
    }

    /// Number of links the substrate could express.
    pub fn possible_links(&self) -> usize {
        match self {
            RobotController::Polar(c) => c.possible_links(),
            RobotController::Es(c) => c.possible_links(),
        }
    }
}

impl Drive for RobotController {
    fn num_inputs(&self) -> usize {
        match self {
            RobotController::Polar(c) => Drive::num_inputs(c),
            RobotController::Es(c) => Drive::num_inputs(c),
        }
    }

    fn num_outputs(&self) -> usize {
        match self {
            RobotController::Polar(c) => Drive::num_outputs(c),
            RobotController::Es(c) => Drive::num_outputs(c),
        }
    }

    fn robot_states(&self, robots: usize) -> RobotStates {
        match self {
            RobotController::Polar(c) => c.robot_states(robots),
            RobotController::Es(c) => c.robot_states(robots),
        }
    }

    fn step_robots(&self, states: &mut RobotStates, inputs: &[f64], outputs: &mut [f64]) {
        match self {
            RobotController::Polar(c) => c.step_robots(states, inputs, outputs),
            RobotController::Es(c) => c.step_robots(states, inputs, outputs),
        }
    }

    fn single_inputs(&self) -> bool {
        match self {
            RobotController::Polar(c) => c.single_inputs(),
            RobotController::Es(c) => c.single_inputs(),
        }
    }

    fn step_robots_single(
        &self,
        states: &mut RobotStates,
        inputs: &[f32],
        wide: &mut [f64],
        outputs: &mut [f64],
    ) {
        match self {
            RobotController::Polar(c) => c.step_robots_single(states, inputs, wide, outputs),
            RobotController::Es(c) => c.step_robots_single(states, inputs, wide, outputs),
        }
    }

    fn wheel_outputs(&self) -> Option<WheelNeurons> {
        match self {
            RobotController::Polar(c) => c.wheel_outputs(),
            RobotController::Es(c) => c.wheel_outputs(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::load_scenario;
    use crate::tasks::driving::episode::Episode;
    use vivae_neat::Population;

    fn es_config() -> Config {
        let mut config = Config::default();
        config.substrate.kind = SubstrateKind::EsHyperneat;
        config.experiment.steps = 60;
        config
    }

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

    fn leo_config() -> Config {
        let mut config = es_config();
        config.substrate.es.leo = true;
        config.substrate.es.leo_seed = true;
        config
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
            crate::search::leo_seeded(&exp.cppn_spec(), &config.neat, config.experiment.seed)
                .unwrap();
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
        let bounds = (vec![0.0], vec![1.0]);
        let search = |c: &Config| Search::new(c, exp.cppn_spec(), bounds.clone(), None).unwrap();
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
            other.strategy.kind = e.kind.into();
            assert_eq!(search(&other).batch(), a, "{}", e.kind);
        }
    }

    #[test]
    fn leo_keys_are_refused_where_they_do_not_apply_and_written_only_when_set() {
        for (text, needle) in [
            (
                "[substrate.es]\nleo = true\n",
                "substrate.es.leo = true applies to substrate.kind",
            ),
            (
                "[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\nleo_seed = true\n",
                "substrate.es.leo_seed = true",
            ),
            (
                "[experiment]\ninit_population = \"x.json\"\n[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\nleo = true\nleo_seed = true\n",
                "experiment.init_population",
            ),
        ] {
            let e = crate::tasks::config_from_toml(text)
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{text}: {e}");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        // A strategy that breeds from minimal genomes refuses the seed.
        let minimal = crate::search::entries()
            .into_iter()
            .filter(|e| !e.takes_population);
        for e in minimal {
            let kind = e.kind;
            let text = format!(
                "[strategy]\nkind = \"{kind}\"\n[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\nleo = true\nleo_seed = true\n"
            );
            let e = crate::tasks::config_from_toml(&text)
                .unwrap_err()
                .to_string();
            let needle = format!("a {kind} run starts from minimal genomes");
            assert!(e.contains(&needle) && e.lines().count() == 1, "{text}: {e}");
        }
        let text = toml::to_string(&leo_config()).unwrap();
        assert!(
            text.contains("leo = true") && text.contains("leo_seed = true"),
            "{text}"
        );
        let mut other = es_config();
        other.substrate.es.max_depth = 4;
        let text = toml::to_string(&other).unwrap();
        assert!(
            text.contains("[substrate.es]") && !text.contains("leo"),
            "{text}"
        );
        assert!(leo_config().validate().is_ok());
    }

    #[test]
    fn es_keys_are_checked_by_name() {
        for (text, needle) in [
            ("max_depth = 11", "substrate.es.max_depth = 11"),
            ("initial_depth = 5", "substrate.es.initial_depth = 5"),
            (
                "division_threshold = nan",
                "substrate.es.division_threshold",
            ),
            (
                "variance_threshold = -1.0",
                "substrate.es.variance_threshold",
            ),
            ("iteration_level = 99", "substrate.es.iteration_level"),
        ] {
            let config = format!("[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\n{text}\n");
            let e = Config::from_toml(&config)
                .and_then(|c| c.validate().map(|_| c))
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{text}: {e}");
        }
        let c = Config::from_toml("[substrate.es]\nrecurrent = false\nmax_depth = 5\n").unwrap();
        assert!(!c.substrate.es.recurrent);
        assert_eq!(c.substrate.es.band_threshold, 0.3);
        assert!(Config::from_toml("[substrate.es]\nmaxdepth = 5\n").is_err());
    }
}

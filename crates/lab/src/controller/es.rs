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
//! recurrent links by default (the paper's controller is recurrent). A
//! feed-forward net (`substrate.es.recurrent = false`) keeps only links
//! going from ahead to behind ([`Flow::Downward`](vivae_neat::hyperneat::es::Flow)),
//! the way from the sensors (y ≥ 0 within 180°) to the wheel neurons (y =
//! −0.47): the paper's upward rule would leave no path at all. That needs the
//! cartesian plane; in polar coordinates it is refused.
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
use crate::controller::drive::{Drive, RobotStates};
use crate::controller::polar::{
    BIAS_OUTPUT, CoordMode, PolarNode, SURFACE_OUTPUT, WHEEL_RADIUS, WheelNeurons,
};
use crate::controller::sensors::SensorSheet;

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
        crate::config::es::check_feed_forward(params.recurrent, mode)?;
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

/// Configs of the ES tests here and of those that need an episode
/// (`tasks::driving::episode::es_controllers`).
#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The default run on an ES-HyperNEAT substrate, 60 steps an episode.
    pub(crate) fn es_config() -> Config {
        let mut config = Config::default();
        config.substrate.kind = SubstrateKind::EsHyperneat;
        config.experiment.steps = 60;
        config
    }

    /// [`es_config`] with LEO and its seed.
    pub(crate) fn leo_config() -> Config {
        let mut config = es_config();
        config.substrate.es.leo = true;
        config.substrate.es.leo_seed = true;
        config
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
            let needle = format!("{} run starts from minimal genomes", crate::error::a(kind));
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

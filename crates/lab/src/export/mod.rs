//! Taking a controller out of vivae: the decoded network of a run's genome
//! (the dense polar sheet or an ES-HyperNEAT network, at any resolution) as
//! one plain step function, written as JSON ([`json`]), a dependency-free C
//! file and header ([`c`]) or an ONNX model ([`onnx`]); [`image`] feeds it
//! what a camera (or a top-down map) sees, and [`choose`] finds the
//! genome in a run directory.
//!
//! Every format computes the same step as vivae: each node's sum is its
//! bias, then `+= w·x` over its links in source order (the sensors, then
//! the previous state), then the bipolar sigmoid `2/(1 + exp(−4.9·s)) − 1`
//! with vivae's portable `exp`; in f64 for an exact controller, and for a
//! fast one ([`Precision::Fast`]: the dense sheet of a `--precision fast`
//! run, or any dense controller exported with `--precision fast`) in f32,
//! each `+= w·x` one fused multiply-add and σ with the f32 `exp`, as
//! vivae's fast step.
//!
//! Readings: every format reads an input `x` as [`StepNet::readings`] reads
//! it ([`Readings::read`]): clamped to the range the controller's task
//! declares, NaN read as 0 (then clamped), ±∞ as the range's ends. A
//! robot's substrate network reads the sensors' range [0, 1], as vivae does
//! where readings come from outside the simulator (the simulator's own are
//! in [0, 1] already, so this changes none of its bits); a plain task's
//! network reads its observations unbounded ([`Readings::UNBOUNDED`]: every
//! finite value as it is, the identity on what vivae feeds it). Every
//! reading is therefore finite, and links of weight 0 can be left out:
//! adding `0·x` (x finite) changes at most the sign of a zero sum, and
//! σ(±0) is +0 in either precision, so the result keeps its bits. A state
//! stays in [−1, 1] except where a sum overflows (readings of unbounded
//! range near ±1.8e308): it is NaN where +∞ and −∞ meet, in every format.

pub mod c;
pub mod choose;
pub mod frames;
pub mod image;
pub mod json;
pub mod onnx;
mod proto;

use std::path::{Path, PathBuf};

use serde::Serialize;
use vivae_neat::Precision;
use vivae_neat::hyperneat::{SparseNetwork, SubstrateController};
use vivae_neat::precision::{bipolar_sigmoid_f32, fma_f32};

use crate::controller::es::RobotController;
pub use crate::controller::readings::Readings;
use crate::controller::sensors::SensorSheet;
use crate::tasks::substrate::SubstrateEpisode;

/// The slope of the bipolar sigmoid every node applies (`vivae_neat::activation`).
pub const SIGMOID_SLOPE: f64 = 4.9;

/// A decoded controller as one step: `(inputs, state) → (outputs, next state)`
/// (a robot's outputs are its wheels, left then right).
///
/// Node `k` is state entry `k`. A link's source `j` is sensor `j` when
/// `j < inputs`, else node `j − inputs` (its value in the previous state when
/// [`StepNet::synchronous`], else its value already updated this step).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepNet {
    /// Sensor values in.
    pub inputs: usize,
    /// Nodes (the length of the state).
    pub nodes: usize,
    /// Bias per node.
    pub bias: Vec<f64>,
    /// Links into node `k` are `starts[k]..starts[k + 1]` of `sources` and `weights`.
    pub starts: Vec<usize>,
    /// Source of each link, in increasing order within a node.
    pub sources: Vec<usize>,
    /// Weight of each link.
    pub weights: Vec<f64>,
    /// The order nodes are updated in.
    pub order: Vec<usize>,
    /// Every node reads the previous state (a recurrent network, updated
    /// synchronously); otherwise nodes update in place in `order` (a
    /// feed-forward network in topological order).
    pub synchronous: bool,
    /// The nodes whose new values are the step's outputs, in the network's
    /// output order (a robot's: the left wheel's, then the right's).
    pub outputs: Vec<usize>,
    /// The arithmetic of the step: exact (f64) or fast (f32; every weight
    /// and bias then an f32 value).
    pub precision: Precision,
    /// The range every input is read in: the sensors' [0, 1] for a robot's
    /// substrate network, the task's declared range for a plain one (an
    /// exact network: a fast one's range lies within binary32's).
    pub readings: Readings,
}

/// A sensor reading as a robot's controller reads it: clamped to [0, 1]
/// (the sensors' range, [`Readings::SENSORS`]), NaN read as 0 — one meaning
/// in vivae and every export format, so that a broken sensor cannot make
/// the state NaN for good. The identity on the simulator's readings.
#[inline]
pub fn reading(x: f64) -> f64 {
    Readings::SENSORS.read(x)
}

/// `2/(1 + exp(−4.9·s)) − 1`: vivae's bipolar sigmoid with its portable `exp`.
pub fn sigmoid(s: f64) -> f64 {
    vivae_neat::activation::bipolar_sigmoid(s)
}

impl StepNet {
    /// The dense polar sheet: neurons are the nodes, updated synchronously.
    pub fn from_polar(c: &SubstrateController, wheels: [usize; 2]) -> StepNet {
        let (ni, n) = (vivae_neat::Network::num_inputs(c), c.num_neurons());
        let mut net = StepNet::empty(ni, n, c.biases().to_vec(), true, wheels.to_vec());
        net.precision = c.precision();
        for target in 0..n {
            for j in 0..ni + n {
                let w = if j < ni {
                    c.input_weight(j, target)
                } else {
                    c.recurrent_weight(j - ni, target)
                };
                if w != 0.0 {
                    net.sources.push(j);
                    net.weights.push(w);
                }
            }
            net.starts.push(net.sources.len());
        }
        net
    }

    /// An ES network: its outputs (the wheels, left then right) and hidden
    /// nodes are the nodes; synchronous when its links form a cycle.
    pub fn from_sparse(s: &SparseNetwork) -> StepNet {
        let ni = vivae_neat::Network::num_inputs(s);
        let n = s.num_nodes() - ni;
        let mut net = StepNet::empty(ni, n, s.biases().to_vec(), s.is_recurrent(), vec![0, 1]);
        // Links come sorted by (target, source): the order vivae sums them in.
        let links = s.links();
        let mut at = 0;
        for target in 0..n {
            while at < links.len() && links[at].target == ni + target {
                net.sources.push(links[at].source);
                net.weights.push(links[at].weight);
                at += 1;
            }
            net.starts.push(at);
        }
        if !net.synchronous {
            net.order = net.topological_order();
        }
        net
    }

    /// A plain NEAT network (a [`crate::tasks::plain`] task's genome): its
    /// non-input nodes by id are the nodes (the outputs first), each
    /// summing its links in the genome's order as vivae's networks do;
    /// synchronous when `recurrent`, else in topological order; any number
    /// of outputs (at least one), in the genome's output order. The writers
    /// compute the bipolar sigmoid only: another activation is refused,
    /// saying so.
    pub fn from_genome(genome: &vivae_neat::Genome, recurrent: bool) -> Result<StepNet, String> {
        use vivae_neat::{Activation, NodeKind};
        let nodes = genome.nodes();
        let ni = genome.num_inputs();
        if genome.num_outputs() == 0 {
            return Err("the network has no outputs: an exported step has at least one".into());
        }
        let computed: Vec<_> = nodes.iter().filter(|n| n.kind != NodeKind::Input).collect();
        if let Some(n) = computed
            .iter()
            .find(|n| n.activation != Activation::BipolarSigmoid)
        {
            return Err(format!(
                "node {} computes {:?}: the exported step computes the bipolar sigmoid only",
                n.id, n.activation
            ));
        }
        let index = |id: u32| -> Option<usize> {
            match nodes.binary_search_by_key(&id, |n| n.id).ok()? {
                i if nodes[i].kind == NodeKind::Input => Some(i),
                _ => Some(ni + computed.iter().position(|n| n.id == id)?),
            }
        };
        let n = computed.len();
        // The network's outputs in its order: its output nodes by id.
        let outputs = (computed.iter().enumerate())
            .filter(|(_, c)| c.kind == NodeKind::Output)
            .map(|(k, _)| k)
            .collect();
        let mut net = StepNet::empty(ni, n, vec![0.0; n], recurrent, outputs);
        for target in &computed {
            for l in genome
                .links()
                .iter()
                .filter(|l| l.enabled && l.to == target.id)
            {
                let source = index(l.from).ok_or("a link from a node the genome lacks")?;
                net.sources.push(source);
                net.weights.push(l.weight);
            }
            net.starts.push(net.sources.len());
        }
        if !recurrent {
            net.order = net.topological_order();
        }
        Ok(net)
    }

    fn empty(
        ni: usize,
        n: usize,
        bias: Vec<f64>,
        synchronous: bool,
        outputs: Vec<usize>,
    ) -> StepNet {
        StepNet {
            inputs: ni,
            nodes: n,
            bias,
            starts: vec![0],
            sources: Vec::new(),
            weights: Vec::new(),
            order: (0..n).collect(),
            synchronous,
            outputs,
            precision: Precision::Exact,
            readings: Readings::SENSORS,
        }
    }

    /// Kahn's order, smallest node first (any topological order gives the
    /// same values: a node reads only nodes already final).
    fn topological_order(&self) -> Vec<usize> {
        let (ni, n) = (self.inputs, self.nodes);
        let mut indegree = vec![0usize; n];
        let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (t, degree) in indegree.iter_mut().enumerate() {
            for &s in &self.sources[self.starts[t]..self.starts[t + 1]] {
                if s >= ni {
                    *degree += 1;
                    out[s - ni].push(t);
                }
            }
        }
        let mut ready: std::collections::BTreeSet<usize> =
            (0..n).filter(|&k| indegree[k] == 0).collect();
        let mut order = Vec::with_capacity(n);
        while let Some(k) = ready.pop_first() {
            order.push(k);
            for &t in &out[k] {
                indegree[t] -= 1;
                if indegree[t] == 0 {
                    ready.insert(t);
                }
            }
        }
        order
    }

    /// Number of links.
    pub fn links(&self) -> usize {
        self.sources.len()
    }

    /// One step: `state` (`nodes` long, zero at the start) becomes the next
    /// state, and `out` (one value an output: [`StepNet::outputs`] long)
    /// the outputs' new values. `scratch` is `nodes` long.
    /// Each input is read as [`StepNet::readings`] reads it.
    /// In fast precision inputs and states are rounded to f32 (exact for the
    /// f32 values a fast controller reads and makes) and the new states are
    /// f32 values.
    pub fn step(&self, inputs: &[f64], state: &mut [f64], scratch: &mut [f64], out: &mut [f64]) {
        assert!(inputs.len() == self.inputs && state.len() == self.nodes);
        assert_eq!(out.len(), self.outputs.len());
        let ni = self.inputs;
        let fast = self.precision == Precision::Fast;
        for &k in &self.order {
            let links = self.starts[k]..self.starts[k + 1];
            let source = |j: usize| {
                if j < ni {
                    self.readings.read(inputs[j])
                } else {
                    state[j - ni]
                }
            };
            let y = if fast {
                let mut s = self.bias[k] as f32;
                for l in links {
                    s = fma_f32(self.weights[l] as f32, source(self.sources[l]) as f32, s);
                }
                f64::from(bipolar_sigmoid_f32(s))
            } else {
                let mut s = self.bias[k];
                for l in links {
                    s += self.weights[l] * source(self.sources[l]);
                }
                sigmoid(s)
            };
            if self.synchronous {
                scratch[k] = y;
            } else {
                state[k] = y;
            }
        }
        if self.synchronous {
            state.copy_from_slice(&scratch[..self.nodes]);
        }
        for (o, &k) in out.iter_mut().zip(&self.outputs) {
            *o = state[k];
        }
    }
}

/// One sensor sheet as a robot must read it, in controller-input order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SheetGeometry {
    /// The sensor (`"surface"`, `"distance"`).
    pub sensor: String,
    /// First input of this sheet.
    pub first_input: usize,
    /// Rings of the sheet.
    pub rings: usize,
    /// Field of view, degrees, centred ahead.
    pub fov_deg: f64,
    /// What one reading is.
    pub reading: String,
    /// Every reading's place, in input order.
    pub places: Vec<Place>,
}

/// Where one reading is taken, relative to the robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Place {
    /// Ring (0 = nearest).
    pub ring: usize,
    /// Angle index (0 = leftmost).
    pub angle_index: usize,
    /// Angle from straight ahead, degrees, negative = left.
    pub angle_deg: f64,
    /// Distance from the robot's centre, px (distance rays: ray length from the rim).
    pub distance: f64,
}

/// What a robot's two outputs mean.
pub const WHEELS: &str = "out[0] = left wheel, out[1] = right wheel, each in [-1, 1]; \
vivae's robot accelerates by a_max*(L+R)/2 and turns by omega_max*(L-R)/2*(1 - speed/v_max) per step \
(clockwise when L > R)";

/// An exported controller: its step and everything a robot needs to feed it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Exported {
    /// What it is: the run, the member and the substrate.
    pub description: String,
    /// `"polar"` or `"es-hyperneat"`.
    pub substrate: String,
    /// The sensor sheets, in input order.
    pub sheets: Vec<SheetGeometry>,
    /// What the outputs mean: a robot's wheels ([`WHEELS`]), a plain
    /// task's actions as its task describes them.
    pub outputs: String,
    /// Simulator units: 1 px = one unit of the scenario; a step is one simulation step.
    pub units: String,
    /// The network.
    pub net: StepNet,
}

impl Exported {
    /// `controller` of `episode` (decoded from its genome), described by `description`.
    pub fn new(
        episode: &dyn SubstrateEpisode,
        controller: &RobotController,
        description: &str,
    ) -> Exported {
        let (substrate, net) = match controller {
            RobotController::Polar(c) => {
                let w = episode.wheels();
                ("polar", StepNet::from_polar(c, [w.left, w.right]))
            }
            RobotController::Es(c) => ("es-hyperneat", StepNet::from_sparse(c.network())),
        };
        Exported {
            description: description.to_string(),
            substrate: substrate.into(),
            sheets: sheet_geometry(episode.sensors()),
            outputs: WHEELS.into(),
            units: "distances in scenario px; one step = one simulation step".into(),
            net,
        }
    }
}

impl Exported {
    /// Whether the outputs are a robot's wheels ([`WHEELS`]: a robot's
    /// substrate network), which the ONNX model also names `wheels`.
    pub fn drives_wheels(&self) -> bool {
        self.outputs == WHEELS
    }

    /// A plain NEAT network ([`StepNet::from_genome`]) whose inputs are one
    /// sheet, `observation`, read in `readings` (its task's range), and
    /// whose outputs mean `outputs` (the task's words, after the count and
    /// order this adds).
    pub fn plain(
        genome: &vivae_neat::Genome,
        recurrent: bool,
        readings: Readings,
        outputs: &str,
        description: &str,
    ) -> Result<Exported, String> {
        let mut net = StepNet::from_genome(genome, recurrent)?;
        net.readings = readings;
        let places = (0..net.inputs)
            .map(|i| Place {
                ring: 0,
                angle_index: i,
                angle_deg: 0.0,
                distance: 0.0,
            })
            .collect();
        Ok(Exported {
            description: description.to_string(),
            substrate: "neat".into(),
            sheets: vec![SheetGeometry {
                sensor: "observation".into(),
                first_input: 0,
                rings: 1,
                fov_deg: 0.0,
                reading: "the task's observation, one value an input (no place)".into(),
                places,
            }],
            outputs: plain_outputs(net.outputs.len(), outputs),
            units: "the task's own".into(),
            net,
        })
    }
}

/// What the `count` outputs of a plain network mean: how many, in which
/// order and range, then the task's `meaning`.
fn plain_outputs(count: usize, meaning: &str) -> String {
    let which = match count {
        1 => "1 output, out[0], in [-1, 1]".to_string(),
        n => format!(
            "{n} outputs, out[0] .. out[{}] in the network's output order, each in [-1, 1]",
            n - 1
        ),
    };
    format!("{which}; {meaning}")
}

/// The geometry of `sheets`, in input order.
fn sheet_geometry(sheets: &[SensorSheet]) -> Vec<SheetGeometry> {
    let mut first = 0;
    sheets
        .iter()
        .map(|s| {
            let places: Vec<Place> = (s.sensor.places().iter())
                .map(|p| Place {
                    ring: p.ring,
                    angle_index: p.angle_index,
                    angle_deg: p.angle.to_degrees(),
                    distance: p.distance,
                })
                .collect();
            let angles = places.iter().map(|p| p.angle_deg);
            let lo = angles.clone().fold(f64::INFINITY, f64::min);
            let hi = angles.fold(f64::NEG_INFINITY, f64::max);
            let g = SheetGeometry {
                sensor: s.name().into(),
                first_input: first,
                rings: s.sensor.rings(),
                fov_deg: if places.len() > 1 { hi - lo } else { 0.0 },
                reading: reading_of(s.name()).into(),
                places,
            };
            first += s.len();
            g
        })
        .collect()
}

/// What a reading of sensor `name` is.
fn reading_of(name: &str) -> &'static str {
    match name {
        "surface" => {
            "the surface under the place: 1 = the least friction (road) ... 0 = the most \
             (grass), (hi - friction)/(hi - lo) over the scenario's materials; 0 outside the arena"
        }
        "distance" => {
            "1 - (free length of the ray)/(range): 0 = nothing within range, 1 = touching"
        }
        _ => "the sensor's reading in [0, 1]",
    }
}

/// The artifact formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// ONNX, opset [`onnx::OPSET`], f64 tensors (f32 in fast precision).
    Onnx,
    /// A C file and its header.
    C,
    /// JSON.
    Json,
}

impl std::str::FromStr for Format {
    type Err = String;
    fn from_str(s: &str) -> Result<Format, String> {
        match s {
            "onnx" => Ok(Format::Onnx),
            "c" => Ok(Format::C),
            "json" => Ok(Format::Json),
            _ => Err(format!("unknown format {s:?} (expected onnx, c or json)")),
        }
    }
}

/// Writes `exported` as `format` to `path` (C: also the header beside it,
/// `path` with extension `.h`), atomically; returns the files written.
pub fn write(exported: &Exported, format: Format, path: &Path) -> crate::Result<Vec<PathBuf>> {
    match format {
        Format::Json => {
            crate::io::write_atomic(path, json::to_json(exported).as_bytes())?;
            Ok(vec![path.to_path_buf()])
        }
        Format::Onnx => {
            crate::io::write_atomic(path, &onnx::to_onnx(exported))?;
            Ok(vec![path.to_path_buf()])
        }
        Format::C => {
            let header = path.with_extension("h");
            let name = header.file_name().map_or_else(
                || "controller.h".into(),
                |n| n.to_string_lossy().into_owned(),
            );
            crate::io::write_atomic(&header, c::header(exported).as_bytes())?;
            crate::io::write_atomic(path, c::source(exported, &name).as_bytes())?;
            Ok(vec![path.to_path_buf(), header])
        }
    }
}

#[cfg(test)]
mod tests;

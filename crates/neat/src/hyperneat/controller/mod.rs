//! The decoded controller: a one-layer, fully recurrent network.
//!
//! This file holds the controller (its padded, panelled storage, its
//! accessors and checkpoint form) and the batch state of several robots;
//! [`step`] is the update itself, vectorised at every instruction level;
//! [`fast`] the f32 copy the fast [`Precision`] steps with.

mod fast;
mod pages;
mod step;

use serde::{Deserialize, Serialize};

use super::error::HyperError;
use super::layout::SubstrateLayout;
use crate::network::Network;
use crate::precision::Precision;
use crate::simd::{self, SimdLevel};
use fast::{Fast, FastStates};
use step::Kernel;

/// The source end of a controller link.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum LinkSource {
    /// Node `index` of input sheet `sheet`.
    Input {
        /// Index of the input sheet in the layout.
        sheet: usize,
        /// Index of the node within that sheet.
        index: usize,
    },
    /// Neuron `index` (a recurrent link; may equal the target: a self-loop).
    Neuron(usize),
}

/// One expressed link of a controller.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Link {
    /// Where the link comes from.
    pub source: LinkSource,
    /// The target neuron.
    pub target: usize,
    /// The link weight (never 0).
    pub weight: f64,
}

/// Serialised form of a [`SubstrateController`] (validated on load).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ControllerData {
    sheet_sizes: Vec<usize>,
    neurons: usize,
    bias: Vec<f64>,
    weights: Vec<f64>,
    /// Absent in exact precision (and in every file written before there was a fast one).
    #[serde(default, skip_serializing_if = "is_exact")]
    precision: Precision,
}

fn is_exact(p: &Precision) -> bool {
    *p == Precision::Exact
}

/// Neuron columns are padded to a multiple of this many lanes (one AVX-512
/// vector of f64), so every vector loop runs on whole vectors.
const PAD: usize = 8;

/// Neurons per weight panel: the weights to neurons `16p..16p + 16` from
/// every source are stored together, so a step streams each panel once,
/// sequentially (the last panel is 8 wide when the padded count is not a
/// multiple of 16).
const PANEL: usize = 2 * PAD;

/// A one-layer, fully recurrent controller decoded from a CPPN.
///
/// `y(t+1) = σ(b + W·s(t) + U·y(t))`, σ the bipolar sigmoid, all neurons
/// updated synchronously once per `activate`. Inputs are the input sheets'
/// nodes concatenated; outputs are the neuron states `y(t+1)`.
///
/// Storage is one dense matrix `[W | U]`, neurons padded with zeros to a
/// multiple of 8 and cut into panels of 16 neurons; within a panel it is
/// source-major: the panel's column `j` holds the weights from source `j`
/// (inputs first, then neurons) to the panel's neurons. A step is a sequence
/// of `acc += column_j · x_j` updates over whole vectors and contiguous
/// memory, which vectorises without reordering any sum (results are
/// bit-identical on every machine and at every [`SimdLevel`]). Unexpressed
/// links are stored as 0.
///
/// The weights are read-only during a step: one controller drives any number
/// of robots through [`activate_batch`](Self::activate_batch), each robot's
/// neuron states held in a [`BatchState`]. The [`Network`] implementation is
/// the same step for one robot whose state the controller holds itself.
///
/// In [`Precision::Fast`] ([`set_precision`](Self::set_precision)) the
/// weights are held in f32 only (half the memory; every accessor widens
/// them) and the step runs on f32 weights, biases and states: other bits
/// than exact precision, but again the same on every machine and at every
/// level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ControllerData", into = "ControllerData")]
pub struct SubstrateController {
    /// Number of nodes of each input sheet.
    sheet_sizes: Vec<usize>,
    /// Total inputs (sum of `sheet_sizes`).
    num_inputs: usize,
    /// Number of neurons.
    n: usize,
    /// `n` rounded up to a multiple of [`PAD`]: the length of a column.
    stride: usize,
    /// Bias per neuron (0 = none), padded to `stride`.
    bias: Vec<f64>,
    /// Panel-major, then source-major weights, `(num_inputs + n) × stride`
    /// values (padding lanes 0); see [`SubstrateController::at`]. Empty in
    /// fast precision, where `fast` holds the weights.
    weights: Vec<f64>,
    /// Neuron states `y(t)` of the [`Network`] interface, padded to `stride`.
    state: Vec<f64>,
    /// Scratch for the synchronous update, padded to `stride`.
    acc: Vec<f64>,
    /// Number of non-zero weights.
    expressed: usize,
    /// The f32 weights, biases and states of fast precision (`None`: exact).
    fast: Option<Box<Fast>>,
}

impl TryFrom<ControllerData> for SubstrateController {
    type Error = HyperError;

    fn try_from(d: ControllerData) -> Result<Self, HyperError> {
        let num_inputs: usize = d.sheet_sizes.iter().sum();
        if d.neurons == 0 {
            return Err(HyperError::NoNeurons);
        }
        if d.bias.len() != d.neurons {
            return Err(HyperError::Inconsistent("bias length differs from neurons"));
        }
        if Some(d.weights.len()) != (num_inputs + d.neurons).checked_mul(d.neurons) {
            return Err(HyperError::Inconsistent(
                "weights length differs from (inputs + neurons) * neurons",
            ));
        }
        if d.weights.iter().chain(&d.bias).any(|w| !w.is_finite()) {
            return Err(HyperError::Inconsistent("non-finite weight or bias"));
        }
        let mut c = SubstrateController::new(d.sheet_sizes, d.neurons, &d.bias, &d.weights);
        c.set_precision(d.precision);
        Ok(c)
    }
}

impl From<SubstrateController> for ControllerData {
    fn from(c: SubstrateController) -> Self {
        let m = c.num_inputs + c.n;
        let weights = (0..m)
            .flat_map(|j| (0..c.n).map(move |i| (j, i)))
            .map(|(j, i)| c.weight(j, i))
            .collect();
        ControllerData {
            precision: c.precision(),
            neurons: c.n,
            bias: c.biases().to_vec(),
            sheet_sizes: c.sheet_sizes,
            weights,
        }
    }
}

impl SubstrateController {
    /// A controller from dense, unpadded parts: `bias` (one per neuron) and
    /// source-major `weights` (`(inputs + neurons) × neurons`).
    fn new(sheet_sizes: Vec<usize>, n: usize, bias: &[f64], weights: &[f64]) -> Self {
        let mut c = SubstrateController::shell(sheet_sizes, n, bias, Precision::Exact);
        c.expressed = weights.iter().filter(|w| **w != 0.0).count();
        for (j, column) in weights.chunks_exact(n).enumerate() {
            for (i, &w) in column.iter().enumerate() {
                let at = c.at(j, i);
                c.weights[at] = w;
            }
        }
        c
    }

    /// A controller with `bias` and zero weights, exact ones only for
    /// `Precision::Exact` (fast precision's are its caller's to add), no
    /// links counted.
    fn shell(sheet_sizes: Vec<usize>, n: usize, bias: &[f64], precision: Precision) -> Self {
        let num_inputs: usize = sheet_sizes.iter().sum();
        let stride = n.next_multiple_of(PAD);
        let mut padded_bias = vec![0.0; stride];
        padded_bias[..n].copy_from_slice(bias);
        SubstrateController {
            sheet_sizes,
            num_inputs,
            n,
            stride,
            bias: padded_bias,
            weights: match precision {
                Precision::Exact => pages::zeroed((num_inputs + n) * stride),
                Precision::Fast => Vec::new(),
            },
            state: vec![0.0; stride],
            acc: vec![0.0; stride],
            expressed: 0,
            fast: None,
        }
    }

    /// Index in `weights` of the weight from source `j` to neuron `i`.
    fn at(&self, j: usize, i: usize) -> usize {
        let p0 = i / PANEL * PANEL;
        let width = PANEL.min(self.stride - p0);
        p0 * (self.num_inputs + self.n) + j * width + (i - p0)
    }

    /// The weights from source `j` to every neuron, into `column` (`n`
    /// values); exact precision only (fast holds no f64 weights).
    fn column(&self, j: usize, column: &mut [f64]) {
        let m = self.num_inputs + self.n;
        for (p0, dst) in (0..).step_by(PANEL).zip(column[..self.n].chunks_mut(PANEL)) {
            let at = p0 * m + j * PANEL.min(self.stride - p0);
            dst.copy_from_slice(&self.weights[at..at + dst.len()]);
        }
    }

    /// The weight from source `j` (inputs, then neurons) to neuron `i`.
    fn weight(&self, j: usize, i: usize) -> f64 {
        match &self.fast {
            Some(f) => f64::from(f.weight(j, i)),
            None => self.weights[self.at(j, i)],
        }
    }

    /// The precision [`activate_batch`](Self::activate_batch) and
    /// [`activate`](Network::activate) compute in (exact unless set).
    pub fn precision(&self) -> Precision {
        if self.fast.is_some() {
            Precision::Fast
        } else {
            Precision::Exact
        }
    }

    /// Makes every later step compute in `precision`, states from zero.
    /// Exact to fast rounds every weight and bias to f32 (and drops the
    /// f64 weights); fast to exact widens them back, exactly. Batch states
    /// made before do not fit any more.
    pub fn set_precision(&mut self, precision: Precision) {
        let m = self.num_inputs + self.n;
        match (precision, self.fast.take()) {
            (Precision::Exact, None) => {}
            (Precision::Fast, Some(f)) => self.fast = Some(f),
            (Precision::Fast, None) => {
                let mut f = Fast::zeroed(self.num_inputs, self.n, &self.bias[..self.n]);
                let mut column = vec![0.0; self.n];
                for j in 0..m {
                    self.column(j, &mut column);
                    f.set_column(j, &column);
                }
                self.expressed = f.expressed();
                self.weights = Vec::new();
                self.fast = Some(Box::new(f));
                self.round_biases();
            }
            (Precision::Exact, Some(f)) => {
                self.weights = vec![0.0; m * self.stride];
                for j in 0..m {
                    for i in 0..self.n {
                        let at = self.at(j, i);
                        self.weights[at] = f64::from(f.weight(j, i));
                    }
                }
            }
        }
    }

    /// In fast precision: the f64 biases become the f32 ones widened, so
    /// that [`biases`](Self::biases) tells what the step adds.
    fn round_biases(&mut self) {
        if let Some(f) = &self.fast {
            for (b, fb) in self.bias.iter_mut().zip(f.biases()) {
                *b = f64::from(*fb);
            }
        }
    }

    /// Number of neurons.
    pub fn num_neurons(&self) -> usize {
        self.n
    }

    /// Number of nodes in each input sheet, in layout order.
    pub fn sheet_sizes(&self) -> &[usize] {
        &self.sheet_sizes
    }

    /// Number of expressed links (input → neuron and neuron → neuron; biases not counted).
    pub fn expressed_links(&self) -> usize {
        self.expressed
    }

    /// Number of possible links: `neurons × (inputs + neurons)`.
    pub fn possible_links(&self) -> usize {
        self.n * (self.num_inputs + self.n)
    }

    /// Biases of the neurons (0 where the CPPN expressed none).
    pub fn biases(&self) -> &[f64] {
        &self.bias[..self.n]
    }

    /// Current neuron states `y(t)` (of the [`Network`] interface).
    pub fn state(&self) -> &[f64] {
        &self.state[..self.n]
    }

    /// Multiplies every weight leaving source `source` by `factor`: sources are
    /// the inputs (all sheets concatenated), then the neurons. Panics when out of range.
    pub fn scale_source(&mut self, source: usize, factor: f64) {
        assert!(
            source < self.num_inputs + self.n,
            "source {source} out of range"
        );
        for target in 0..self.n {
            self.scale_weight(source, target, factor);
        }
    }

    /// Multiplies the weight of neuron `source` → neuron `target` by `factor`.
    /// Panics when out of range.
    pub fn scale_recurrent(&mut self, source: usize, target: usize, factor: f64) {
        assert!(source < self.n && target < self.n);
        self.scale_weight(self.num_inputs + source, target, factor);
    }

    /// Multiplies the weight from source `j` to neuron `i` by `factor` (in
    /// fast precision: the f32 weight, widened, times `factor`, rounded back).
    fn scale_weight(&mut self, j: usize, i: usize, factor: f64) {
        match &mut self.fast {
            Some(f) => {
                let w = f64::from(f.weight(j, i)) * factor;
                f.set_weight(j, i, w);
            }
            None => {
                let k = self.at(j, i);
                self.weights[k] *= factor;
            }
        }
    }

    /// Weight of input `input` (over all sheets concatenated) → neuron `target`; 0 = no link.
    /// Panics when an index is out of range.
    pub fn input_weight(&self, input: usize, target: usize) -> f64 {
        assert!(input < self.num_inputs && target < self.n);
        self.weight(input, target)
    }

    /// Weight of neuron `source` → neuron `target`; 0 = no link. Panics when out of range.
    pub fn recurrent_weight(&self, source: usize, target: usize) -> f64 {
        assert!(source < self.n && target < self.n);
        self.weight(self.num_inputs + source, target)
    }

    /// All expressed links, input links first (sheet by sheet), then recurrent links.
    pub fn links(&self) -> impl Iterator<Item = Link> + '_ {
        // Map a flat source index to its kind without a per-link search.
        let sources = self
            .sheet_sizes
            .iter()
            .enumerate()
            .flat_map(|(sheet, &len)| (0..len).map(move |index| LinkSource::Input { sheet, index }))
            .chain((0..self.n).map(LinkSource::Neuron));
        sources.enumerate().flat_map(move |(j, source)| {
            (0..self.n).filter_map(move |target| {
                let weight = self.weight(j, target);
                (weight != 0.0).then_some(Link {
                    source,
                    target,
                    weight,
                })
            })
        })
    }

    /// Fresh (all-zero) neuron states for `robots` robots driven by this controller.
    pub fn batch_state(&self, robots: usize) -> BatchState {
        BatchState {
            robots,
            n: self.n,
            stride: self.stride,
            state: vec![0.0; robots * self.stride],
            acc: vec![0.0; robots * self.stride],
            fast: (self.fast.as_ref()).map(|f| FastStates::new(robots, self.num_inputs, f.stride)),
            wide: Vec::new(),
        }
    }

    /// One synchronous update of every robot in `states`: robot `r` reads
    /// `inputs[r * num_inputs..][..num_inputs]` and writes its new neuron
    /// states to `outputs[r * neurons..][..neurons]`.
    ///
    /// Bit for bit the same as a separate controller per robot, each
    /// [`activate`](Network::activate)d in turn; but each weight column is
    /// read once per step for all robots (streamed once rather than once per
    /// robot when the weights outgrow the caches). Never allocates. Panics
    /// when a length does not fit.
    pub fn activate_batch(&self, states: &mut BatchState, inputs: &[f64], outputs: &mut [f64]) {
        self.activate_batch_at(simd::level(), states, inputs, outputs);
    }

    /// [`activate_batch`](Self::activate_batch) at a given instruction level
    /// (clamped to what the CPU supports).
    pub(crate) fn activate_batch_at(
        &self,
        level: SimdLevel,
        states: &mut BatchState,
        inputs: &[f64],
        outputs: &mut [f64],
    ) {
        self.check_outputs(states, outputs.len());
        self.step_batch_at(level, states, inputs);
        self.copy_outputs(states, outputs);
    }

    /// [`activate_batch`](Self::activate_batch) without copying the new
    /// states out: each robot's stay in `states` ([`BatchState::state`]).
    /// For a caller that reads a few of them, such as the two wheel neurons
    /// of a robot (the copy was 1.7 % of the default run).
    pub fn step_batch(&self, states: &mut BatchState, inputs: &[f64]) {
        self.step_batch_at(simd::level(), states, inputs);
    }

    /// [`step_batch`](Self::step_batch) at a given instruction level
    /// (clamped to what the CPU supports).
    pub(crate) fn step_batch_at(&self, level: SimdLevel, states: &mut BatchState, inputs: &[f64]) {
        let robots = states.robots;
        self.check_inputs(states, inputs.len());
        match (&self.fast, &mut states.fast) {
            (None, None) => {
                self.kernel()
                    .step(level, robots, inputs, &mut states.state, &mut states.acc)
            }
            (Some(f), Some(fs)) => f.step(level, fs, inputs, &mut states.state, self.stride),
            _ => panic!("batch state of another controller precision"),
        }
    }

    /// [`activate_batch`](Self::activate_batch) with inputs in f32, as the
    /// fast precision computes with them: they go into the f32 step as they
    /// are (no rounding). An exact controller widens them to f64 first
    /// (exactly), in a buffer of `states` kept for the purpose.
    pub fn activate_batch_single(
        &self,
        states: &mut BatchState,
        inputs: &[f32],
        outputs: &mut [f64],
    ) {
        self.activate_batch_single_at(simd::level(), states, inputs, outputs);
    }

    /// [`activate_batch_single`](Self::activate_batch_single) at a given
    /// instruction level (clamped to what the CPU supports).
    pub(crate) fn activate_batch_single_at(
        &self,
        level: SimdLevel,
        states: &mut BatchState,
        inputs: &[f32],
        outputs: &mut [f64],
    ) {
        self.check_outputs(states, outputs.len());
        self.step_batch_single_at(level, states, inputs);
        self.copy_outputs(states, outputs);
    }

    /// [`activate_batch_single`](Self::activate_batch_single) without
    /// copying the new states out (see [`step_batch`](Self::step_batch)).
    pub fn step_batch_single(&self, states: &mut BatchState, inputs: &[f32]) {
        self.step_batch_single_at(simd::level(), states, inputs);
    }

    /// [`step_batch_single`](Self::step_batch_single) at a given instruction
    /// level (clamped to what the CPU supports).
    pub(crate) fn step_batch_single_at(
        &self,
        level: SimdLevel,
        states: &mut BatchState,
        inputs: &[f32],
    ) {
        let robots = states.robots;
        self.check_inputs(states, inputs.len());
        match (&self.fast, &mut states.fast) {
            (Some(f), Some(fs)) => f.step_single(level, fs, inputs, &mut states.state, self.stride),
            (None, None) => {
                let mut wide = std::mem::take(&mut states.wide);
                wide.clear();
                wide.extend(inputs.iter().map(|&v| f64::from(v)));
                self.kernel()
                    .step(level, robots, &wide, &mut states.state, &mut states.acc);
                states.wide = wide;
            }
            _ => panic!("batch state of another controller precision"),
        }
    }

    /// Panics unless `states` is this controller's shape and the input
    /// length fits its robots.
    fn check_inputs(&self, states: &BatchState, inputs: usize) {
        assert!(
            states.n == self.n && states.stride == self.stride,
            "batch state of another controller shape"
        );
        assert_eq!(
            inputs,
            states.robots * self.num_inputs,
            "controller input length"
        );
    }

    /// Panics unless the output length fits the robots of `states`.
    fn check_outputs(&self, states: &BatchState, outputs: usize) {
        assert_eq!(outputs, states.robots * self.n, "controller output length");
    }

    /// Each robot's new neuron states from `states` into `outputs`, robot after robot.
    fn copy_outputs(&self, states: &BatchState, outputs: &mut [f64]) {
        if self.n > 0 {
            for (out, y) in outputs
                .chunks_exact_mut(self.n)
                .zip(states.state.chunks_exact(self.stride))
            {
                // A call to `memcpy` for the paper's 9 values took 1–2 % of a run.
                crate::compile::copy_short(out, &y[..self.n]);
            }
        }
    }

    fn kernel(&self) -> Kernel<'_, f64> {
        Kernel {
            ni: self.num_inputs,
            n: self.n,
            stride: self.stride,
            bias: &self.bias,
            weights: &self.weights,
        }
    }
}

/// The neuron states of several robots that one [`SubstrateController`] drives.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchState {
    /// Number of robots.
    robots: usize,
    /// Neurons per robot.
    n: usize,
    /// The controller's padded column length.
    stride: usize,
    /// `y(t)` of robot `r` at `state[r * stride..][..n]` (padding lanes stay 0).
    state: Vec<f64>,
    /// Scratch for the synchronous update, laid out as `state`.
    acc: Vec<f64>,
    /// The f32 states that advance in fast precision (`state` then holds
    /// them widened to f64).
    fast: Option<FastStates>,
    /// f32 inputs widened to f64 when an exact controller is given them
    /// ([`SubstrateController::activate_batch_single`]); empty until then.
    wide: Vec<f64>,
}

impl BatchState {
    /// Number of robots.
    pub fn robots(&self) -> usize {
        self.robots
    }

    /// Current neuron states `y(t)` of robot `robot`.
    #[inline]
    pub fn state(&self, robot: usize) -> &[f64] {
        &self.state[robot * self.stride..][..self.n]
    }

    /// Clears every robot's state (as [`Network::reset`]).
    pub fn reset(&mut self) {
        self.state.fill(0.0);
        if let Some(f) = &mut self.fast {
            f.reset();
        }
    }
}

impl Network for SubstrateController {
    fn num_inputs(&self) -> usize {
        self.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.n
    }

    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        assert_eq!(inputs.len(), self.num_inputs, "controller input length");
        assert_eq!(outputs.len(), self.n, "controller output length");
        if let Some(f) = &mut self.fast {
            let mut own = std::mem::take(&mut f.own);
            f.step(
                simd::level(),
                &mut own,
                inputs,
                &mut self.state,
                self.stride,
            );
            f.own = own;
        } else {
            let kernel = Kernel {
                ni: self.num_inputs,
                n: self.n,
                stride: self.stride,
                bias: &self.bias,
                weights: &self.weights,
            };
            kernel.step(simd::level(), 1, inputs, &mut self.state, &mut self.acc);
        }
        outputs.copy_from_slice(&self.state[..self.n]);
    }

    fn reset(&mut self) {
        self.state.fill(0.0);
        if let Some(f) = &mut self.fast {
            f.own.reset();
        }
    }
}

impl SubstrateController {
    /// Assembles a decoded controller (sizes consistent with `layout`):
    /// `bias` per neuron, and `column(j, out)` writes the weights from source
    /// `j` (inputs, then neurons) to every neuron into `out` (one per neuron),
    /// sources in order. The columns go straight into the padded panels.
    pub(super) fn build(
        layout: &SubstrateLayout,
        bias: &[f64],
        precision: Precision,
        mut column: impl FnMut(usize, &mut [f64]),
    ) -> Self {
        let n = bias.len();
        let sheets = layout.inputs.iter().map(|s| s.coords.len()).collect();
        let mut c = SubstrateController::shell(sheets, n, bias, precision);
        let m = c.num_inputs + n;
        // Fast precision keeps f32 weights only, converted while the column is in cache.
        let mut fast = (precision == Precision::Fast).then(|| Fast::zeroed(c.num_inputs, n, bias));
        let mut values = vec![0.0; n];
        let mut expressed = 0;
        for j in 0..m {
            column(j, &mut values);
            if let Some(f) = &mut fast {
                f.set_column(j, &values);
                continue;
            }
            // Counted here, while the column is in cache, not in a pass over every weight.
            expressed += values.iter().filter(|w| **w != 0.0).count();
            // Whole panels as fixed-size copies: a `memcpy` call per panel was
            // 4-6 % of a large decode.
            let whole = n / PANEL * PANEL;
            for p0 in (0..whole).step_by(PANEL) {
                let to: &mut [f64; PANEL] = (&mut c.weights[p0 * m + j * PANEL..][..PANEL])
                    .try_into()
                    .unwrap();
                *to = values[p0..p0 + PANEL].try_into().unwrap();
            }
            if whole < n {
                let width = c.stride - whole;
                c.weights[whole * m + j * width..][..n - whole].copy_from_slice(&values[whole..]);
            }
        }
        c.expressed = match &fast {
            Some(f) => f.expressed(),
            None => expressed,
        };
        c.fast = fast.map(Box::new);
        c.round_biases();
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::activation::bipolar_sigmoid;
    use crate::hyperneat::test_util::{FnCppn, close, known, layout};
    use crate::hyperneat::{HyperParams, InputSheet, decode};

    #[test]
    fn scaling_a_source_or_one_link_touches_only_its_links() {
        let layout = SubstrateLayout {
            inputs: vec![
                InputSheet {
                    coords: vec![[0.1, 0.2], [0.3, 0.4]],
                    cppn_output: 0,
                },
                InputSheet {
                    coords: vec![[0.5, 0.6]],
                    cppn_output: 0,
                },
            ],
            neurons: vec![[0.0, 0.5], [0.5, 0.0]],
            bias_output: 1,
            recurrent_output: 2,
        };
        let mut cppn = FnCppn(|q: &[f64]| {
            let v = (3.0 * q[0] + 2.0 * q[1] - q[2] + 0.5 * q[3]).sin();
            [v, 0.5, -v]
        });
        let c = decode(&mut cppn, &layout, &HyperParams::default()).unwrap();
        assert!(c.expressed_links() > 4, "the test needs expressed links");
        let mut scaled = c.clone();
        // Source 2 is the second sheet's only input; sources 3 and 4 are the neurons.
        scaled.scale_source(2, 0.5);
        scaled.scale_source(3, 2.0);
        scaled.scale_recurrent(1, 0, -1.0);
        for t in 0..2 {
            assert_eq!(scaled.biases()[t], c.biases()[t]);
            for s in 0..2 {
                assert_eq!(scaled.input_weight(s, t), c.input_weight(s, t));
            }
            assert_eq!(scaled.input_weight(2, t), 0.5 * c.input_weight(2, t));
            assert_eq!(
                scaled.recurrent_weight(0, t),
                2.0 * c.recurrent_weight(0, t)
            );
        }
        assert_eq!(scaled.recurrent_weight(1, 0), -c.recurrent_weight(1, 0));
        assert_eq!(scaled.recurrent_weight(1, 1), c.recurrent_weight(1, 1));
    }

    #[test]
    fn recurrent_links_include_self_loops() {
        // Weight neuron→neuron is 0.9 everywhere: every pair, incl. i→i, is expressed.
        let mut cppn = FnCppn(|_: &[f64]| [0.0, 0.0, 0.9]);
        let l = layout(
            vec![[0.0, 1.0]; 2],
            vec![[0.5, 0.5], [-0.5, 0.5], [0.0, 1.0]],
        );
        let c = decode(&mut cppn, &l, &HyperParams::default()).unwrap();
        assert_eq!(c.expressed_links(), 9);
        assert_eq!(c.possible_links(), 3 * (2 + 3));
        let w = HyperParams::default().express(0.9).unwrap();
        for i in 0..3 {
            assert!(close(c.recurrent_weight(i, i), w));
        }
        let links: Vec<Link> = c.links().collect();
        assert_eq!(links.len(), 9);
        assert!(
            links
                .iter()
                .all(|l| matches!(l.source, LinkSource::Neuron(_)))
        );
        assert_eq!(
            links
                .iter()
                .filter(|l| l.source == LinkSource::Neuron(l.target))
                .count(),
            3
        );
    }

    #[test]
    fn controller_follows_the_update_equation() {
        let inputs = vec![[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let neurons = vec![[-0.5, 0.0], [0.5, 0.5], [0.0, 0.2]];
        let l = layout(inputs, neurons);
        let mut c = decode(&mut FnCppn(known), &l, &HyperParams::default()).unwrap();
        let s = [[0.2, -0.7, 1.0], [1.0, 0.0, 0.3], [0.0, 0.0, 0.0]];
        let mut y = [0.0; 3];
        let mut out = [0.0; 3];
        for step in 0..2 {
            for st in &s {
                let mut next = [0.0; 3];
                for (i, v) in next.iter_mut().enumerate() {
                    let mut a = c.biases()[i];
                    for (j, x) in st.iter().enumerate() {
                        a += c.input_weight(j, i) * x;
                    }
                    for (k, yk) in y.iter().enumerate() {
                        a += c.recurrent_weight(k, i) * yk;
                    }
                    *v = bipolar_sigmoid(a);
                }
                y = next;
                c.activate(st, &mut out);
                for i in 0..3 {
                    assert!(close(out[i], y[i]), "step {step}: {out:?} vs {y:?}");
                }
                assert_eq!(c.state(), &out);
            }
            // After reset the controller repeats exactly.
            c.reset();
            y = [0.0; 3];
            assert_eq!(c.state(), &[0.0; 3]);
        }
        // A clone has its own state.
        let mut d = c.clone();
        c.activate(&s[0], &mut out);
        assert_eq!(d.state(), &[0.0; 3]);
        let mut out2 = [0.0; 3];
        d.activate(&s[0], &mut out2);
        assert_eq!(out, out2);
    }

    /// Deterministic pseudo-random values in [-3, 3), a quarter of them 0.
    fn values(count: usize, seed: u64) -> Vec<f64> {
        let mut s = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        (0..count)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                let u = (s >> 11) as f64 / (1u64 << 53) as f64;
                if s.is_multiple_of(4) {
                    0.0
                } else {
                    6.0 * u - 3.0
                }
            })
            .collect()
    }

    /// The update equation written out plainly, one neuron at a time.
    fn reference_step(c: &SubstrateController, x: &[f64], y: &mut Vec<f64>) {
        let next: Vec<f64> = (0..c.num_neurons())
            .map(|i| {
                let mut a = c.biases()[i];
                for (j, v) in x.iter().enumerate() {
                    a += c.input_weight(j, i) * v;
                }
                for (k, v) in y.iter().enumerate() {
                    a += c.recurrent_weight(k, i) * v;
                }
                bipolar_sigmoid(a)
            })
            .collect();
        *y = next;
    }

    fn random_controller(sheets: Vec<usize>, n: usize, seed: u64) -> SubstrateController {
        let inputs: usize = sheets.iter().sum();
        let bias = values(n, seed);
        let weights = values((inputs + n) * n, seed + 1);
        SubstrateController::new(sheets, n, &bias, &weights)
    }

    #[test]
    fn batched_step_equals_one_controller_per_robot_at_every_level() {
        for (case, &(sheets, n)) in [
            (&[15][..], 9),
            (&[15, 4][..], 1),
            (&[3][..], 7),
            (&[2][..], 8),
            (&[40][..], 17),
            (&[5, 6][..], 24),
            // 4 neurons past a multiple of 8: AVX-512's half-width last vector, full.
            (&[7][..], 12),
            (&[300][..], 81),
        ]
        .iter()
        .enumerate()
        {
            let c = random_controller(sheets.to_vec(), n, 100 + case as u64);
            let ni = c.num_inputs();
            for robots in [1, 2, 5, 8, 9, 13] {
                let mut expected: Vec<Vec<f64>> = vec![vec![0.0; n]; robots];
                let mut per_robot: Vec<SubstrateController> = vec![c.clone(); robots];
                let mut batches: Vec<(SimdLevel, BatchState)> = simd::available()
                    .into_iter()
                    .map(|l| (l, c.batch_state(robots)))
                    .collect();
                let mut out = vec![0.0; robots * n];
                let mut one = vec![0.0; n];
                for step in 0..6 {
                    let x = values(robots * ni, 1000 * step + robots as u64);
                    for (r, y) in expected.iter_mut().enumerate() {
                        reference_step(&c, &x[r * ni..][..ni], y);
                        per_robot[r].activate(&x[r * ni..][..ni], &mut one);
                        assert_eq!(bits(&one), bits(y), "robot {r} alone, step {step}");
                    }
                    for (level, state) in &mut batches {
                        c.activate_batch_at(*level, state, &x, &mut out);
                        for (r, y) in expected.iter().enumerate() {
                            assert_eq!(
                                bits(&out[r * n..][..n]),
                                bits(y),
                                "{level:?}, {n} neurons, robot {r} of {robots}, step {step}"
                            );
                            assert_eq!(bits(state.state(r)), bits(y));
                            // Padding lanes stay 0: the squash packs the sums and never writes them.
                            let pad = &state.state[r * state.stride..][n..state.stride];
                            assert!(pad.iter().all(|v| v.to_bits() == 0), "{level:?} padding");
                        }
                    }
                }
                for (_, state) in &mut batches {
                    state.reset();
                    assert!(state.state(robots - 1).iter().all(|&v| v == 0.0));
                }
            }
        }
    }

    #[test]
    fn extreme_sums_give_the_same_bits_at_every_level() {
        // Sums far outside exp's range, exact zeros and signed zeros.
        let n = 11;
        let mut bias = values(n, 3);
        bias[0] = 1e300;
        bias[1] = -1e300;
        bias[2] = -0.0;
        bias[3] = 0.0;
        let mut weights = values((2 + n) * n, 4);
        weights[4] = 1e308;
        weights[5] = -1e308;
        let c = SubstrateController::new(vec![2], n, &bias, &weights);
        let x = [1e10, -0.0];
        let mut first: Option<Vec<u64>> = None;
        for level in simd::available() {
            let mut state = c.batch_state(1);
            let mut out = vec![0.0; n];
            for _ in 0..3 {
                c.activate_batch_at(level, &mut state, &x, &mut out);
            }
            let b = bits(&out);
            assert!(out.iter().all(|v| (-1.0..=1.0).contains(v)), "{out:?}");
            match &first {
                None => first = Some(b),
                Some(f) => assert_eq!(&b, f, "{level:?}"),
            }
        }
    }

    /// The update equation in f32 with fused multiply-adds, one neuron at a
    /// time: what fast precision computes.
    fn reference_step_f32(c: &SubstrateController, x: &[f64], y: &mut Vec<f32>) {
        let next: Vec<f32> = (0..c.num_neurons())
            .map(|i| {
                // Each term fused: one rounding per `+= w·x`.
                let fma = crate::precision::fma_f32;
                let mut a = c.biases()[i] as f32;
                for (j, &v) in x.iter().enumerate() {
                    a = fma(c.input_weight(j, i) as f32, v as f32, a);
                }
                for (k, &v) in y.iter().enumerate() {
                    a = fma(c.recurrent_weight(k, i) as f32, v, a);
                }
                crate::precision::bipolar_sigmoid_f32(a)
            })
            .collect();
        *y = next;
    }

    #[test]
    fn fast_batched_step_follows_the_f32_equation_at_every_level() {
        for (case, &(sheets, n)) in [
            (&[15][..], 9),
            (&[3][..], 7),
            (&[40][..], 17),
            // 8 neurons past a multiple of 16: AVX-512's half-width last vector, full.
            (&[20][..], 40),
            (&[300][..], 81),
        ]
        .iter()
        .enumerate()
        {
            let mut c = random_controller(sheets.to_vec(), n, 200 + case as u64);
            c.set_precision(Precision::Fast);
            assert_eq!(c.precision(), Precision::Fast);
            let ni = c.num_inputs();
            for robots in [1, 3, 8, 9, 17] {
                let mut expected: Vec<Vec<f32>> = vec![vec![0.0; n]; robots];
                let mut per_robot: Vec<SubstrateController> = vec![c.clone(); robots];
                let mut batches: Vec<(SimdLevel, BatchState)> = simd::available()
                    .into_iter()
                    .map(|l| (l, c.batch_state(robots)))
                    .collect();
                let (mut out, mut one) = (vec![0.0; robots * n], vec![0.0; n]);
                for step in 0..5 {
                    let x = values(robots * ni, 7000 * step + robots as u64);
                    for (r, y) in expected.iter_mut().enumerate() {
                        reference_step_f32(&c, &x[r * ni..][..ni], y);
                        per_robot[r].activate(&x[r * ni..][..ni], &mut one);
                        let wide: Vec<f64> = y.iter().map(|&v| f64::from(v)).collect();
                        assert_eq!(bits(&one), bits(&wide), "robot {r} alone, step {step}");
                    }
                    for (level, state) in &mut batches {
                        c.activate_batch_at(*level, state, &x, &mut out);
                        for (r, y) in expected.iter().enumerate() {
                            let wide: Vec<f64> = y.iter().map(|&v| f64::from(v)).collect();
                            let at = format!("{level:?}, {n} neurons, robot {r} of {robots}");
                            assert_eq!(bits(&out[r * n..][..n]), bits(&wide), "{at}, step {step}");
                            assert_eq!(bits(state.state(r)), bits(&wide));
                        }
                    }
                }
                for (_, state) in &mut batches {
                    state.reset();
                    assert!(state.state(robots - 1).iter().all(|&v| v == 0.0));
                }
            }
        }
    }

    #[test]
    fn single_inputs_step_as_their_f64_widening_in_both_precisions() {
        // f32 inputs are what the sensors' single-precision read hands over:
        // a fast controller steps on them as they are, an exact one on their
        // (exact) widening; either way the bits of the f64 call on the same values.
        for precision in [Precision::Exact, Precision::Fast] {
            let (n, robots) = (81, 5);
            let mut c = random_controller(vec![300], n, 300);
            c.set_precision(precision);
            let ni = c.num_inputs();
            for level in simd::available() {
                let mut wide_state = c.batch_state(robots);
                let mut single_state = c.batch_state(robots);
                let (mut a, mut b) = (vec![0.0; robots * n], vec![0.0; robots * n]);
                for step in 0..4 {
                    let x32: Vec<f32> = values(robots * ni, 9000 + step)
                        .iter()
                        .map(|&v| v as f32)
                        .collect();
                    let x64: Vec<f64> = x32.iter().map(|&v| f64::from(v)).collect();
                    c.activate_batch_at(level, &mut wide_state, &x64, &mut a);
                    c.activate_batch_single_at(level, &mut single_state, &x32, &mut b);
                    assert_eq!(bits(&a), bits(&b), "{precision:?} {level:?} step {step}");
                }
            }
        }
    }

    #[test]
    fn step_batch_leaves_in_the_states_what_activate_batch_copies_out() {
        for precision in [Precision::Exact, Precision::Fast] {
            let (n, robots) = (9, 5);
            let mut c = random_controller(vec![15], n, 400);
            c.set_precision(precision);
            let ni = c.num_inputs();
            for level in simd::available() {
                let [mut copied, mut kept, mut copied32, mut kept32] =
                    std::array::from_fn(|_| c.batch_state(robots));
                let mut out = vec![0.0; robots * n];
                let mut out32 = vec![0.0; robots * n];
                for step in 0..4 {
                    let x = values(robots * ni, 9500 + step);
                    let x32: Vec<f32> = x.iter().map(|&v| v as f32).collect();
                    c.activate_batch_at(level, &mut copied, &x, &mut out);
                    c.step_batch_at(level, &mut kept, &x);
                    c.activate_batch_single_at(level, &mut copied32, &x32, &mut out32);
                    c.step_batch_single_at(level, &mut kept32, &x32);
                    for r in 0..robots {
                        let at = format!("{precision:?} {level:?} robot {r} step {step}");
                        assert_eq!(bits(kept.state(r)), bits(&out[r * n..][..n]), "{at}");
                        assert_eq!(bits(kept32.state(r)), bits(&out32[r * n..][..n]), "{at}");
                    }
                }
            }
        }
    }

    #[test]
    fn fast_extreme_sums_give_the_same_bits_at_every_level() {
        let n = 11;
        let mut bias = values(n, 3);
        bias[0] = 1e30;
        bias[1] = -1e30;
        bias[2] = -0.0;
        let mut weights = values((2 + n) * n, 4);
        weights[4] = 1e300; // beyond f32: an infinite weight
        weights[5] = -3e38;
        let mut c = SubstrateController::new(vec![2], n, &bias, &weights);
        c.set_precision(Precision::Fast);
        let x = [1e10, -0.0];
        let mut first: Option<Vec<u64>> = None;
        for level in simd::available() {
            let mut state = c.batch_state(1);
            let mut out = vec![0.0; n];
            for _ in 0..3 {
                c.activate_batch_at(level, &mut state, &x, &mut out);
            }
            let b = bits(&out);
            match &first {
                None => first = Some(b),
                Some(f) => assert_eq!(&b, f, "{level:?}"),
            }
        }
    }

    #[test]
    fn fast_precision_is_kept_through_serde_and_scaling() {
        let mut c = random_controller(vec![5, 2], 9, 7);
        let exact_json = serde_json::to_string(&c).unwrap();
        assert!(
            !exact_json.contains("precision"),
            "exact files stay as they were"
        );
        c.set_precision(Precision::Fast);
        let d: SubstrateController =
            serde_json::from_str(&serde_json::to_string(&c).unwrap()).unwrap();
        assert_eq!(d.precision(), Precision::Fast);
        assert_eq!(c, d);
        // Scaling a fast controller scales its f32 copy too.
        let mut scaled = c.clone();
        scaled.scale_source(0, -1.0);
        let mut again = random_controller(vec![5, 2], 9, 7);
        again.scale_source(0, -1.0);
        again.set_precision(Precision::Fast);
        assert_eq!(scaled, again);
        // A fast weight scales as f32 widened, times the factor, rounded back.
        let (s, t) = (0..9)
            .flat_map(|s| (0..9).map(move |t| (s, t)))
            .find(|&(s, t)| scaled.recurrent_weight(s, t) != 0.0)
            .expect("an expressed recurrent link");
        let before = scaled.recurrent_weight(s, t);
        scaled.scale_recurrent(s, t, 0.37);
        let after = scaled.recurrent_weight(s, t);
        assert_eq!(after, f64::from((before * 0.37) as f32));
        assert_ne!(after, before);
        let (mut a, mut b) = ([0.0; 9], [0.0; 9]);
        let x = [0.05; 7];
        scaled.activate(&x, &mut a);
        c.activate(&x, &mut b);
        assert_ne!(a, b);
    }

    #[test]
    fn fast_precision_holds_each_weight_rounded_to_f32_and_widens_back() {
        // 17 and 40 neurons cross f64 panels (16) and f32 panels (32).
        for n in [9, 17, 40, 70] {
            let exact = random_controller(vec![5, 2], n, 3);
            let mut fast = exact.clone();
            fast.set_precision(Precision::Fast);
            assert!(fast.weights.is_empty(), "no f64 weights in fast precision");
            for t in 0..n {
                let round = |w: f64| f64::from(w as f32);
                for s in 0..7 {
                    let w = exact.input_weight(s, t);
                    assert_eq!(fast.input_weight(s, t), round(w), "{n}: {s} → {t}");
                }
                for s in 0..n {
                    let w = exact.recurrent_weight(s, t);
                    assert_eq!(fast.recurrent_weight(s, t), round(w), "{n}: {s} → {t}");
                }
                assert_eq!(fast.biases()[t], round(exact.biases()[t]));
            }
            assert_eq!(fast.links().count(), fast.expressed_links());
            // Back to exact: the widened f32 values, and fast again is the same.
            let mut back = fast.clone();
            back.set_precision(Precision::Exact);
            assert_eq!(back.input_weight(3, 1), fast.input_weight(3, 1));
            back.set_precision(Precision::Fast);
            assert_eq!(back, fast);
        }
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn padded_storage_round_trips_through_the_unpadded_form() {
        let c = random_controller(vec![5, 2], 9, 7);
        assert_eq!(c.possible_links(), 9 * 16);
        let json = serde_json::to_value(&c).unwrap();
        assert_eq!(json["weights"].as_array().unwrap().len(), 9 * 16);
        assert_eq!(json["bias"].as_array().unwrap().len(), 9);
        let d: SubstrateController = serde_json::from_value(json).unwrap();
        assert_eq!(c, d);
        assert_eq!(c.links().count(), c.expressed_links());
        assert!(c.links().all(|l| l.target < 9));
    }

    #[test]
    fn controller_serde_round_trip_and_validation() {
        let l = layout(vec![[-1.0, 0.0], [1.0, 0.0]], vec![[-0.5, 0.0], [0.5, 0.5]]);
        let mut c = decode(&mut FnCppn(known), &l, &HyperParams::default()).unwrap();
        let json = serde_json::to_string(&c).unwrap();
        let mut d: SubstrateController = serde_json::from_str(&json).unwrap();
        assert_eq!(c, d);
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        c.activate(&[0.3, 0.9], &mut a);
        d.activate(&[0.3, 0.9], &mut b);
        assert_eq!(a, b);
        let broken = json.replace("\"neurons\":2", "\"neurons\":3");
        assert!(serde_json::from_str::<SubstrateController>(&broken).is_err());
    }
}

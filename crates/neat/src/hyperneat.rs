//! HyperNEAT: decoding a CPPN into a substrate controller.
//!
//! The module knows nothing about robots or polar grids: a [`SubstrateLayout`]
//! is a list of input sheets and one sheet of neurons, each node a point in
//! the plane. A CPPN with inputs `(x1, y1, x2, y2, 1)` — `(x1, y1)` the target
//! neuron, `(x2, y2)` the source node — paints every possible connection:
//!
//! * input sheet `s` → neuron: CPPN output `inputs[s].cppn_output`;
//! * neuron bias: output `bias_output`, queried with `x2 = y2 = 0`;
//! * neuron → neuron (all ordered pairs, self-loops included): `recurrent_output`.
//!
//! An output `o` is expressed as a connection only when `|o| > t`, with weight
//! `w = sign(o)·(|o| − t)/(1 − t)·amplitude` ([`HyperParams`]). The same rule
//! decides whether a bias is present. The result is a one-layer, fully
//! recurrent [`SubstrateController`].

use serde::{Deserialize, Serialize};

use std::collections::{BTreeMap, BTreeSet};

use crate::activation::{Activation, bipolar_sigmoid};
use crate::feedforward::FeedForwardNetwork;
use crate::genome::{Genome, NodeKind};
use crate::network::Network;

/// Number of CPPN inputs a substrate query feeds: `(x1, y1, x2, y2, 1)`.
pub const CPPN_INPUTS: usize = 5;

/// Errors of substrate decoding.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HyperError {
    /// A hyper-parameter is out of its valid range.
    #[error("invalid HyperNEAT parameter {field} = {value}: {reason}")]
    InvalidParam {
        /// Name of the offending field.
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the valid range is.
        reason: &'static str,
    },
    /// The CPPN does not take the 5 substrate-query inputs.
    #[error("the CPPN has {0} inputs; substrate queries need 5 (x1, y1, x2, y2, bias)")]
    CppnInputs(usize),
    /// The layout refers to a CPPN output the CPPN does not have.
    #[error(
        "the layout uses CPPN output {output} for {role}, but the CPPN has only {available} outputs"
    )]
    CppnOutput {
        /// Which query uses the output.
        role: &'static str,
        /// The requested output index.
        output: usize,
        /// How many outputs the CPPN has.
        available: usize,
    },
    /// The layout has no neurons.
    #[error("the substrate has no neurons")]
    NoNeurons,
    /// A node coordinate is not finite.
    #[error("{sheet} node {index} has a non-finite coordinate {coord:?}")]
    BadCoordinate {
        /// Which sheet.
        sheet: &'static str,
        /// Node index within the sheet.
        index: usize,
        /// The coordinate.
        coord: [f64; 2],
    },
    /// Serialised controller data are inconsistent.
    #[error("inconsistent controller data: {0}")]
    Inconsistent(&'static str),
}

/// HyperNEAT expression parameters (DESIGN §7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HyperParams {
    /// Expression threshold `t`: CPPN outputs with `|o| <= t` express no connection.
    ///
    /// Paper: 0.2.
    pub threshold: f64,
    /// Largest controller weight: an output `o` maps to `sign(o)·(|o| − t)/(1 − t)·amplitude`.
    ///
    /// Paper: 3.0.
    pub amplitude: f64,
}

impl Default for HyperParams {
    fn default() -> Self {
        HyperParams {
            threshold: 0.2,
            amplitude: 3.0,
        }
    }
}

impl HyperParams {
    /// Checks that `0 ≤ threshold < 1` and `amplitude` is finite and positive.
    pub fn validate(&self) -> Result<(), HyperError> {
        if !(self.threshold >= 0.0 && self.threshold < 1.0) {
            return Err(HyperError::InvalidParam {
                field: "threshold",
                value: self.threshold,
                reason: "must satisfy 0 <= threshold < 1",
            });
        }
        if !(self.amplitude.is_finite() && self.amplitude > 0.0) {
            return Err(HyperError::InvalidParam {
                field: "amplitude",
                value: self.amplitude,
                reason: "must be finite and > 0",
            });
        }
        Ok(())
    }

    /// Maps a CPPN output to a connection weight, `None` when not expressed.
    ///
    /// Outputs beyond ±1 (possible only if a CPPN output is not a bipolar
    /// sigmoid) are clamped so weights never exceed the amplitude; a NaN
    /// output expresses nothing.
    #[inline]
    pub fn express(&self, o: f64) -> Option<f64> {
        let w = self.weight_or_zero(o);
        if w == 0.0 { None } else { Some(w) }
    }

    /// As [`HyperParams::express`], with 0 for "no connection" (an expressed
    /// weight is never exactly 0, since `|o| − t > 0`).
    #[inline]
    fn weight_or_zero(&self, o: f64) -> f64 {
        let a = o.abs();
        // NaN fails `a > t` and so expresses nothing.
        if a.is_nan() || a <= self.threshold {
            return 0.0;
        }
        let scaled = (a.min(1.0) - self.threshold) / (1.0 - self.threshold) * self.amplitude;
        // Guard against underflow to 0 turning an expressed link into "none".
        let scaled = scaled.max(f64::MIN_POSITIVE);
        if o < 0.0 { -scaled } else { scaled }
    }
}

/// One input sheet: node coordinates and which CPPN output paints its links.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputSheet {
    /// CPPN-space coordinates of the sheet's nodes, in controller-input order.
    pub coords: Vec<[f64; 2]>,
    /// Index of the CPPN output giving the weight sheet node → neuron.
    pub cppn_output: usize,
}

/// The geometry of a substrate: input sheets and the neuron sheet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubstrateLayout {
    /// Input sheets; the controller's inputs are their nodes concatenated in order.
    pub inputs: Vec<InputSheet>,
    /// CPPN-space coordinates of the neurons (the controller's outputs, in order).
    pub neurons: Vec<[f64; 2]>,
    /// CPPN output giving each neuron's bias (queried with `x2 = y2 = 0`).
    pub bias_output: usize,
    /// CPPN output giving the weight neuron → neuron.
    pub recurrent_output: usize,
}

impl SubstrateLayout {
    /// Total number of input nodes over all sheets.
    pub fn num_inputs(&self) -> usize {
        self.inputs.iter().map(|s| s.coords.len()).sum()
    }

    /// Number of CPPN queries a decode makes: one per possible link plus one per bias.
    pub fn num_queries(&self) -> usize {
        let n = self.neurons.len();
        n * (self.num_inputs() + n + 1)
    }

    /// Checks the layout against a CPPN's input and output counts.
    pub fn check(&self, cppn_inputs: usize, cppn_outputs: usize) -> Result<(), HyperError> {
        if cppn_inputs != CPPN_INPUTS {
            return Err(HyperError::CppnInputs(cppn_inputs));
        }
        if self.neurons.is_empty() {
            return Err(HyperError::NoNeurons);
        }
        let out = |role, output| {
            if output < cppn_outputs {
                Ok(())
            } else {
                Err(HyperError::CppnOutput {
                    role,
                    output,
                    available: cppn_outputs,
                })
            }
        };
        out("the neuron bias", self.bias_output)?;
        out("neuron -> neuron weights", self.recurrent_output)?;
        for sheet in &self.inputs {
            out("input -> neuron weights", sheet.cppn_output)?;
        }
        let finite = |sheet, coords: &[[f64; 2]]| {
            for (index, c) in coords.iter().enumerate() {
                if !(c[0].is_finite() && c[1].is_finite()) {
                    return Err(HyperError::BadCoordinate {
                        sheet,
                        index,
                        coord: *c,
                    });
                }
            }
            Ok(())
        };
        finite("neuron", &self.neurons)?;
        for sheet in &self.inputs {
            finite("input", &sheet.coords)?;
        }
        Ok(())
    }
}

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
}

/// A one-layer, fully recurrent controller decoded from a CPPN.
///
/// `y(t+1) = σ(b + W·s(t) + U·y(t))`, σ the bipolar sigmoid, all neurons
/// updated synchronously once per `activate`. Inputs are the input sheets'
/// nodes concatenated; outputs are the neuron states `y(t+1)`.
///
/// Storage is one dense, source-major matrix `[W | U]`: column `j` holds the
/// weights from source `j` (inputs first, then neurons) to every neuron, so a
/// step is a sequence of `acc += column_j · x_j` updates over contiguous
/// memory, which vectorises without reordering any sum (results are
/// bit-identical on every machine). Unexpressed links are stored as 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ControllerData", into = "ControllerData")]
pub struct SubstrateController {
    /// Number of nodes of each input sheet.
    sheet_sizes: Vec<usize>,
    /// Total inputs (sum of `sheet_sizes`).
    num_inputs: usize,
    /// Number of neurons.
    n: usize,
    /// Bias per neuron (0 = none).
    bias: Vec<f64>,
    /// Source-major weights, `(num_inputs + n) × n`.
    weights: Vec<f64>,
    /// Neuron states `y(t)`.
    state: Vec<f64>,
    /// Scratch for the synchronous update.
    acc: Vec<f64>,
    /// Number of non-zero entries of `weights`.
    expressed: usize,
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
        let expressed = d.weights.iter().filter(|w| **w != 0.0).count();
        Ok(SubstrateController {
            sheet_sizes: d.sheet_sizes,
            num_inputs,
            n: d.neurons,
            bias: d.bias,
            weights: d.weights,
            state: vec![0.0; d.neurons],
            acc: vec![0.0; d.neurons],
            expressed,
        })
    }
}

impl From<SubstrateController> for ControllerData {
    fn from(c: SubstrateController) -> Self {
        ControllerData {
            sheet_sizes: c.sheet_sizes,
            neurons: c.n,
            bias: c.bias,
            weights: c.weights,
        }
    }
}

impl SubstrateController {
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
        self.weights.len()
    }

    /// Biases of the neurons (0 where the CPPN expressed none).
    pub fn biases(&self) -> &[f64] {
        &self.bias
    }

    /// Current neuron states `y(t)`.
    pub fn state(&self) -> &[f64] {
        &self.state
    }

    /// Multiplies every weight leaving source sheet `sheet` by `factor`: input
    /// sheets are `0..sheet_sizes().len()`, the neuron sheet (recurrent links)
    /// is `sheet_sizes().len()`. Used to keep a sheet's total drive constant
    /// when it is re-sampled at another density. Panics when `sheet` is out of range.
    pub fn scale_source_sheet(&mut self, sheet: usize, factor: f64) {
        let first: usize = self.sheet_sizes[..sheet.min(self.sheet_sizes.len())]
            .iter()
            .sum();
        let count = match self.sheet_sizes.get(sheet) {
            Some(&size) => size,
            None if sheet == self.sheet_sizes.len() => self.n,
            None => panic!("sheet {sheet} out of range"),
        };
        for w in &mut self.weights[first * self.n..(first + count) * self.n] {
            *w *= factor;
        }
    }

    /// Weight of input `input` (over all sheets concatenated) → neuron `target`; 0 = no link.
    /// Panics when an index is out of range.
    pub fn input_weight(&self, input: usize, target: usize) -> f64 {
        assert!(input < self.num_inputs && target < self.n);
        self.weights[input * self.n + target]
    }

    /// Weight of neuron `source` → neuron `target`; 0 = no link. Panics when out of range.
    pub fn recurrent_weight(&self, source: usize, target: usize) -> f64 {
        assert!(source < self.n && target < self.n);
        self.weights[(self.num_inputs + source) * self.n + target]
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
        sources
            .zip(self.weights.chunks_exact(self.n))
            .flat_map(|(source, column)| {
                column.iter().enumerate().filter(|(_, w)| **w != 0.0).map(
                    move |(target, &weight)| Link {
                        source,
                        target,
                        weight,
                    },
                )
            })
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
        let n = self.n;
        let acc = &mut self.acc[..n];
        // Blocks of BLOCK neurons keep their sums in registers over all sources;
        // each neuron still adds its terms in source order (bias, inputs, then
        // neurons), so results do not depend on the blocking.
        let (w_in, w_rec) = self.weights.split_at(self.num_inputs * n);
        let mut start = 0;
        while start + BLOCK <= n {
            let mut sum: [f64; BLOCK] = self.bias[start..start + BLOCK].try_into().expect("block");
            for (column, &x) in w_in.chunks_exact(n).zip(inputs) {
                accumulate(&mut sum, &column[start..start + BLOCK], x);
            }
            for (column, &x) in w_rec.chunks_exact(n).zip(&self.state) {
                accumulate(&mut sum, &column[start..start + BLOCK], x);
            }
            acc[start..start + BLOCK].copy_from_slice(&sum);
            start += BLOCK;
        }
        for (i, a) in acc.iter_mut().enumerate().skip(start) {
            let mut sum = self.bias[i];
            for (column, &x) in w_in.chunks_exact(n).zip(inputs) {
                sum += column[i] * x;
            }
            for (column, &x) in w_rec.chunks_exact(n).zip(&self.state) {
                sum += column[i] * x;
            }
            *a = sum;
        }
        for ((y, out), &a) in self
            .state
            .iter_mut()
            .zip(outputs.iter_mut())
            .zip(acc.iter())
        {
            let v = bipolar_sigmoid(a);
            *y = v;
            *out = v;
        }
    }

    fn reset(&mut self) {
        self.state.fill(0.0);
    }
}

/// Neurons whose sums are accumulated together in registers.
const BLOCK: usize = 4;

/// `sum += w · x` for one block of neurons.
#[inline(always)]
fn accumulate(sum: &mut [f64; BLOCK], w: &[f64], x: f64) {
    let w: &[f64; BLOCK] = w.try_into().expect("block");
    for k in 0..BLOCK {
        sum[k] += w[k] * x;
    }
}

/// Decodes `cppn` over `layout` into a controller.
///
/// Makes `layout.num_queries()` CPPN activations; never allocates per query.
/// Query order (which matters only for stateful CPPNs) is: every neuron's
/// bias, then for each source (input sheets in order, then neurons) every
/// target neuron.
pub fn decode(
    cppn: &mut impl Network,
    layout: &SubstrateLayout,
    params: &HyperParams,
) -> Result<SubstrateController, HyperError> {
    params.validate()?;
    let num_outputs = cppn.num_outputs();
    layout.check(cppn.num_inputs(), num_outputs)?;
    let n = layout.neurons.len();
    let num_inputs = layout.num_inputs();
    let mut weights = vec![0.0; (num_inputs + n) * n];
    let mut bias = vec![0.0; n];
    let mut out = vec![0.0; num_outputs];
    let mut query = [0.0, 0.0, 0.0, 0.0, 1.0];
    for (target, &[x1, y1]) in layout.neurons.iter().enumerate() {
        query[0] = x1;
        query[1] = y1;
        cppn.activate(&query, &mut out);
        bias[target] = params.weight_or_zero(out[layout.bias_output]);
    }
    // Source-major so that each source's column `weights[j*n..(j+1)*n]` is
    // written contiguously (target-major writes stride through the matrix).
    let sources = layout
        .inputs
        .iter()
        .flat_map(|s| s.coords.iter().map(move |&c| (c, s.cppn_output)))
        .chain(layout.neurons.iter().map(|&c| (c, layout.recurrent_output)));
    for (([x2, y2], output), column) in sources.zip(weights.chunks_exact_mut(n)) {
        query[2] = x2;
        query[3] = y2;
        for (&[x1, y1], w) in layout.neurons.iter().zip(column.iter_mut()) {
            query[0] = x1;
            query[1] = y1;
            cppn.activate(&query, &mut out);
            *w = params.weight_or_zero(out[output]);
        }
    }
    Ok(SubstrateController::from_parts(layout, bias, weights))
}

impl SubstrateController {
    /// Assembles a decoded controller (sizes already consistent with `layout`).
    fn from_parts(layout: &SubstrateLayout, bias: Vec<f64>, weights: Vec<f64>) -> Self {
        let n = bias.len();
        let expressed = weights.iter().filter(|w| **w != 0.0).count();
        SubstrateController {
            sheet_sizes: layout.inputs.iter().map(|s| s.coords.len()).collect(),
            num_inputs: layout.num_inputs(),
            n,
            bias,
            weights,
            state: vec![0.0; n],
            acc: vec![0.0; n],
            expressed,
        }
    }
}

/// Queries per batch: the batch's node values (≈ 14 nodes × 256 × 8 bytes) stay in L1.
const BATCH: usize = 256;

/// A CPPN genome compiled for batched substrate queries.
///
/// Gives bit-identical outputs to [`FeedForwardNetwork`] (same per-node sum
/// order, same activation functions), but evaluates one output at a time for
/// a whole batch of source nodes: each node's weighted sum runs over
/// contiguous arrays (vectorised), activation functions run in tight loops,
/// and only the nodes the requested output depends on are computed.
#[derive(Debug, Clone)]
pub struct BatchCppn {
    num_inputs: usize,
    /// Computed nodes in topological order: activation and `(source slot, weight)` links.
    nodes: Vec<(Activation, Vec<(usize, f64)>)>,
    /// For each output: the computed nodes it depends on (topological order) and its slot.
    plans: Vec<(Vec<usize>, usize)>,
    /// Node values, slot-major: `values[slot * BATCH + q]`.
    values: Vec<f64>,
}

impl BatchCppn {
    /// Compiles `genome`; `None` if its enabled links form a cycle (use
    /// [`FeedForwardNetwork`] then, which breaks cycles its own way).
    pub fn new(genome: &Genome) -> Option<BatchCppn> {
        let ids = |kind| -> Vec<u32> {
            genome
                .nodes()
                .iter()
                .filter(|n| n.kind == kind)
                .map(|n| n.id)
                .collect()
        };
        let inputs = ids(NodeKind::Input);
        let outputs = ids(NodeKind::Output);
        let enabled: Vec<_> = genome.links().iter().filter(|l| l.enabled).collect();
        // Ancestors of each output (nodes it depends on), inputs excluded.
        let is_input = |id: u32| inputs.binary_search(&id).is_ok();
        let ancestors: Vec<BTreeSet<u32>> = outputs
            .iter()
            .map(|&o| {
                let mut seen = BTreeSet::from([o]);
                let mut stack = vec![o];
                while let Some(n) = stack.pop() {
                    for l in enabled.iter().filter(|l| l.to == n) {
                        if !is_input(l.from) && seen.insert(l.from) {
                            stack.push(l.from);
                        }
                    }
                }
                seen
            })
            .collect();
        let needed: BTreeSet<u32> = ancestors.iter().flatten().copied().collect();
        // Kahn's algorithm over the needed nodes; leftovers mean a cycle.
        let mut indegree: BTreeMap<u32, usize> = needed.iter().map(|&id| (id, 0)).collect();
        for l in &enabled {
            if needed.contains(&l.from)
                && let Some(d) = indegree.get_mut(&l.to)
            {
                *d += 1;
            }
        }
        let mut ready: BTreeSet<u32> = indegree
            .iter()
            .filter(|(_, d)| **d == 0)
            .map(|(&id, _)| id)
            .collect();
        let mut order = Vec::with_capacity(needed.len());
        while let Some(n) = ready.pop_first() {
            order.push(n);
            for l in enabled.iter().filter(|l| l.from == n) {
                if let Some(d) = indegree.get_mut(&l.to) {
                    *d -= 1;
                    if *d == 0 {
                        ready.insert(l.to);
                    }
                }
            }
        }
        if order.len() != needed.len() {
            return None;
        }
        let mut slot: BTreeMap<u32, usize> = BTreeMap::new();
        for (k, &id) in inputs.iter().enumerate() {
            slot.insert(id, k);
        }
        for (k, &id) in order.iter().enumerate() {
            slot.insert(id, inputs.len() + k);
        }
        // Links into each node in genome order: the sum order FeedForwardNetwork uses.
        let nodes = order
            .iter()
            .map(|&id| {
                let act = genome.node(id).map_or(Activation::Linear, |n| n.activation);
                let links = enabled
                    .iter()
                    .filter(|l| l.to == id)
                    .filter_map(|l| slot.get(&l.from).map(|&s| (s, l.weight)))
                    .collect();
                (act, links)
            })
            .collect();
        let plans = outputs
            .iter()
            .zip(&ancestors)
            .map(|(o, anc)| {
                let plan = order
                    .iter()
                    .enumerate()
                    .filter(|(_, id)| anc.contains(id))
                    .map(|(k, _)| k)
                    .collect();
                (plan, slot[o])
            })
            .collect();
        Some(BatchCppn {
            num_inputs: inputs.len(),
            values: vec![0.0; (inputs.len() + order.len()) * BATCH],
            nodes,
            plans,
        })
    }

    /// Number of CPPN inputs.
    pub fn num_inputs(&self) -> usize {
        self.num_inputs
    }

    /// Number of CPPN outputs.
    pub fn num_outputs(&self) -> usize {
        self.plans.len()
    }

    /// Output `output` for target `target` and each of `sources`, into
    /// `out[q]` (`out.len() == sources.len()`); bias input 1.
    pub fn query_sources(
        &mut self,
        output: usize,
        target: [f64; 2],
        sources: &[[f64; 2]],
        out: &mut [f64],
    ) {
        self.query(output, Points::Many(sources), Points::One(target), out);
    }

    /// Output `output` for each of `targets` and source `source`, into
    /// `out[q]` (`out.len() == targets.len()`); bias input 1.
    pub fn query_targets(
        &mut self,
        output: usize,
        targets: &[[f64; 2]],
        source: [f64; 2],
        out: &mut [f64],
    ) {
        self.query(output, Points::One(source), Points::Many(targets), out);
    }

    fn query(&mut self, output: usize, sources: Points<'_>, targets: Points<'_>, out: &mut [f64]) {
        assert_eq!(
            self.num_inputs, CPPN_INPUTS,
            "substrate queries need 5 CPPN inputs"
        );
        assert!(output < self.plans.len(), "no CPPN output {output}");
        for points in [sources, targets] {
            if let Points::Many(p) = points {
                assert_eq!(p.len(), out.len(), "one output per point");
            }
        }
        for (start, out) in (0..).step_by(BATCH).zip(out.chunks_mut(BATCH)) {
            let b = out.len();
            let v = &mut self.values;
            // Input slots 0..5 = x1, y1, x2, y2, bias.
            for (slot, points) in [(0, targets), (2, sources)] {
                match points {
                    Points::One([x, y]) => {
                        v[slot * BATCH..slot * BATCH + b].fill(x);
                        v[(slot + 1) * BATCH..(slot + 1) * BATCH + b].fill(y);
                    }
                    Points::Many(points) => {
                        for (q, &[x, y]) in points[start..start + b].iter().enumerate() {
                            v[slot * BATCH + q] = x;
                            v[(slot + 1) * BATCH + q] = y;
                        }
                    }
                }
            }
            v[4 * BATCH..4 * BATCH + b].fill(1.0);
            let (plan, out_slot) = &self.plans[output];
            for &k in plan {
                let (act, links) = &self.nodes[k];
                let slot = self.num_inputs + k;
                let (before, rest) = v.split_at_mut(slot * BATCH);
                let acc = &mut rest[..b];
                acc.fill(0.0);
                for &(src, w) in links {
                    let x = &before[src * BATCH..src * BATCH + b];
                    for (a, &x) in acc.iter_mut().zip(x) {
                        *a += x * w;
                    }
                }
                apply_all(*act, acc);
            }
            out.copy_from_slice(&v[out_slot * BATCH..out_slot * BATCH + b]);
        }
    }
}

/// One fixed point or one point per query.
#[derive(Clone, Copy)]
enum Points<'a> {
    One([f64; 2]),
    Many(&'a [[f64; 2]]),
}

/// Applies `act` to every element, one tight loop per function.
fn apply_all(act: Activation, xs: &mut [f64]) {
    macro_rules! each {
        ($f:expr) => {
            for x in xs.iter_mut() {
                *x = $f.apply(*x);
            }
        };
    }
    match act {
        Activation::BipolarSigmoid => each!(Activation::BipolarSigmoid),
        Activation::Linear => {}
        Activation::Gaussian => each!(Activation::Gaussian),
        Activation::Abs => each!(Activation::Abs),
        Activation::Sine => each!(Activation::Sine),
        Activation::Cosine => each!(Activation::Cosine),
        Activation::Sigmoid => each!(Activation::Sigmoid),
    }
}

/// Decodes a CPPN genome over `layout`: the batched path ([`BatchCppn`]) for
/// acyclic genomes, [`decode`] with a [`FeedForwardNetwork`] otherwise. The
/// result equals `decode(&mut FeedForwardNetwork::from_genome(genome), ..)`.
pub fn decode_genome(
    genome: &Genome,
    layout: &SubstrateLayout,
    params: &HyperParams,
) -> Result<SubstrateController, HyperError> {
    let Some(mut cppn) = BatchCppn::new(genome) else {
        return decode(&mut FeedForwardNetwork::from_genome(genome), layout, params);
    };
    params.validate()?;
    layout.check(cppn.num_inputs(), cppn.num_outputs())?;
    let n = layout.neurons.len();
    let mut weights = vec![0.0; (layout.num_inputs() + n) * n];
    let mut bias = vec![0.0; n];
    let mut out = vec![0.0; n];
    cppn.query_targets(layout.bias_output, &layout.neurons, [0.0, 0.0], &mut out);
    for (b, &o) in bias.iter_mut().zip(&out) {
        *b = params.weight_or_zero(o);
    }
    // One batch per source: all targets, written to the source's column.
    let sources = layout
        .inputs
        .iter()
        .flat_map(|s| s.coords.iter().map(move |&c| (c, s.cppn_output)))
        .chain(layout.neurons.iter().map(|&c| (c, layout.recurrent_output)));
    for ((source, output), column) in sources.zip(weights.chunks_exact_mut(n)) {
        cppn.query_targets(output, &layout.neurons, source, &mut out);
        for (w, &o) in column.iter_mut().zip(&out) {
            *w = params.weight_or_zero(o);
        }
    }
    Ok(SubstrateController::from_parts(layout, bias, weights))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hand-written CPPN: a closure from the 5 inputs to `N` outputs.
    struct FnCppn<F, const N: usize>(F);

    impl<F: FnMut(&[f64]) -> [f64; N], const N: usize> Network for FnCppn<F, N> {
        fn num_inputs(&self) -> usize {
            5
        }
        fn num_outputs(&self) -> usize {
            N
        }
        fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
            assert_eq!(inputs[4], 1.0, "bias input must be 1");
            outputs.copy_from_slice(&(self.0)(inputs));
        }
        fn reset(&mut self) {}
    }

    fn layout(inputs: Vec<[f64; 2]>, neurons: Vec<[f64; 2]>) -> SubstrateLayout {
        SubstrateLayout {
            inputs: vec![InputSheet {
                coords: inputs,
                cppn_output: 0,
            }],
            neurons,
            bias_output: 1,
            recurrent_output: 2,
        }
    }

    #[test]
    fn scaling_a_source_sheet_touches_only_its_links() {
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
        scaled.scale_source_sheet(1, 0.5);
        scaled.scale_source_sheet(2, 2.0);
        for t in 0..2 {
            assert_eq!(scaled.biases()[t], c.biases()[t]);
            for s in 0..2 {
                assert_eq!(scaled.input_weight(s, t), c.input_weight(s, t));
                assert_eq!(
                    scaled.recurrent_weight(s, t),
                    2.0 * c.recurrent_weight(s, t)
                );
            }
            assert_eq!(scaled.input_weight(2, t), 0.5 * c.input_weight(2, t));
        }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn threshold_and_scaling_formula() {
        let p = HyperParams::default();
        assert_eq!(p.express(0.0), None);
        assert_eq!(p.express(0.2), None);
        assert_eq!(p.express(-0.2), None);
        assert_eq!(p.express(f64::NAN), None);
        assert!(close(p.express(0.6).unwrap(), 0.4 / 0.8 * 3.0));
        assert!(close(p.express(-0.6).unwrap(), -1.5));
        assert!(close(p.express(1.0).unwrap(), 3.0));
        assert!(close(p.express(-1.0).unwrap(), -3.0));
        // Just above the threshold: a tiny, but present, link.
        let w = p.express(0.2 + 1e-12).unwrap();
        assert!(w > 0.0 && w < 1e-10);
        // Outputs beyond ±1 are clamped to the amplitude.
        assert!(close(p.express(7.0).unwrap(), 3.0));
        let q = HyperParams {
            threshold: 0.0,
            amplitude: 5.0,
        };
        assert!(close(q.express(0.5).unwrap(), 2.5));
    }

    #[test]
    fn params_validate_names_the_field() {
        let bad = HyperParams {
            threshold: 1.0,
            ..Default::default()
        };
        assert!(matches!(
            bad.validate(),
            Err(HyperError::InvalidParam {
                field: "threshold",
                ..
            })
        ));
        let bad = HyperParams {
            amplitude: f64::NAN,
            ..Default::default()
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("amplitude")
        );
        assert!(HyperParams::default().validate().is_ok());
    }

    #[test]
    fn params_serde_defaults_and_unknown_fields() {
        let p: HyperParams = serde_json::from_str(r#"{"threshold": 0.3}"#).unwrap();
        assert_eq!(p.threshold, 0.3);
        assert_eq!(p.amplitude, 3.0);
        assert!(serde_json::from_str::<HyperParams>(r#"{"treshold": 0.3}"#).is_err());
    }

    #[test]
    fn bias_is_queried_with_zero_source() {
        let mut seen = Vec::new();
        let mut cppn = FnCppn(|q: &[f64]| {
            seen.push([q[0], q[1], q[2], q[3]]);
            // Bias output encodes (x1 + 2 y1) and is only valid at x2 = y2 = 0.
            let bias = if q[2] == 0.0 && q[3] == 0.0 {
                0.1 * (q[0] + 2.0 * q[1]) + 0.5
            } else {
                f64::NAN
            };
            [0.0, bias, 0.0]
        });
        let l = layout(vec![[0.3, 0.4]], vec![[1.0, 0.0], [0.0, 1.0]]);
        let c = decode(&mut cppn, &l, &HyperParams::default()).unwrap();
        let p = HyperParams::default();
        assert!(close(c.biases()[0], p.express(0.6).unwrap()));
        assert!(close(c.biases()[1], p.express(0.7).unwrap()));
        // 2 biases + 2×(1 input + 2 neurons) links.
        assert_eq!(seen.len(), l.num_queries());
        assert_eq!(seen.len(), 8);
        assert_eq!(
            seen.iter().filter(|q| q[2] == 0.0 && q[3] == 0.0).count(),
            2
        );
        assert_eq!(c.expressed_links(), 0);
        assert_eq!(c.possible_links(), 6);
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

    /// A CPPN whose weights are a known function of the coordinates.
    fn known(q: &[f64]) -> [f64; 3] {
        let (x1, y1, x2, y2) = (q[0], q[1], q[2], q[3]);
        [
            (x1 - x2).tanh(),
            0.5 * y1,
            (-((x1 - x2).powi(2) + (y1 - y2).powi(2))).exp() * (x1 - 0.5).signum(),
        ]
    }

    #[test]
    fn known_cppn_gives_known_weights() {
        let inputs = vec![[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let neurons = vec![[-0.5, 0.0], [0.5, 0.5]];
        let l = layout(inputs.clone(), neurons.clone());
        let p = HyperParams::default();
        let c = decode(&mut FnCppn(known), &l, &p).unwrap();
        let mut expressed = 0;
        for (t, &[x1, y1]) in neurons.iter().enumerate() {
            let b = known(&[x1, y1, 0.0, 0.0, 1.0])[1];
            assert_eq!(c.biases()[t], p.express(b).unwrap_or(0.0));
            for (s, &[x2, y2]) in inputs.iter().enumerate() {
                let o = known(&[x1, y1, x2, y2, 1.0])[0];
                assert_eq!(c.input_weight(s, t), p.express(o).unwrap_or(0.0));
                expressed += usize::from(p.express(o).is_some());
            }
            for (s, &[x2, y2]) in neurons.iter().enumerate() {
                let o = known(&[x1, y1, x2, y2, 1.0])[2];
                assert_eq!(c.recurrent_weight(s, t), p.express(o).unwrap_or(0.0));
                expressed += usize::from(p.express(o).is_some());
            }
        }
        assert_eq!(c.expressed_links(), expressed);
        assert_eq!(c.links().count(), expressed);
        // Spot values: input (1, 0) → neuron (−0.5, 0): o = tanh(−1.5).
        let o = (-1.5f64).tanh();
        assert!(close(c.input_weight(2, 0), -(o.abs() - 0.2) / 0.8 * 3.0));
        // Self-loop of neuron 1 at (0.5, 0.5): o = e^0 · signum(0) = 1 → +3.
        assert!(close(c.recurrent_weight(1, 1), 3.0));
        // Self-loop of neuron 0 at (−0.5, 0): o = −1 → −3.
        assert!(close(c.recurrent_weight(0, 0), -3.0));
    }

    #[test]
    fn resampling_the_same_cppn_at_another_resolution() {
        let grid = |k: usize| -> Vec<[f64; 2]> {
            (0..k)
                .flat_map(|i| {
                    (0..k).map(move |j| [i as f64 / (k - 1) as f64, j as f64 / (k - 1) as f64])
                })
                .collect()
        };
        let p = HyperParams::default();
        let coarse = decode(&mut FnCppn(known), &layout(grid(3), grid(3)), &p).unwrap();
        let fine = decode(&mut FnCppn(known), &layout(grid(5), grid(9)), &p).unwrap();
        assert_eq!(fine.num_neurons(), 81);
        assert_eq!(fine.possible_links(), 81 * (25 + 81));
        // Nodes of the 3-grid sit in the finer grids: index (i, j) ↦ (s·i, s·j).
        let at = |k: usize, s: usize, i: usize, j: usize| (s * i) * k + s * j;
        for ti in 0..3 {
            for tj in 0..3 {
                let t3 = ti * 3 + tj;
                let t9 = at(9, 4, ti, tj);
                assert_eq!(coarse.biases()[t3], fine.biases()[t9]);
                for si in 0..3 {
                    for sj in 0..3 {
                        let s3 = si * 3 + sj;
                        assert_eq!(
                            coarse.input_weight(s3, t3),
                            fine.input_weight(at(5, 2, si, sj), t9)
                        );
                        assert_eq!(
                            coarse.recurrent_weight(s3, t3),
                            fine.recurrent_weight(at(9, 4, si, sj), t9)
                        );
                    }
                }
            }
        }
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

    #[test]
    fn multiple_input_sheets_use_their_own_output() {
        let mut cppn = FnCppn(|_: &[f64]| [0.5, 0.0, 0.0, -0.9]);
        let l = SubstrateLayout {
            inputs: vec![
                InputSheet {
                    coords: vec![[0.0, 1.0], [1.0, 0.0]],
                    cppn_output: 0,
                },
                InputSheet {
                    coords: vec![[0.0, 0.5]],
                    cppn_output: 3,
                },
            ],
            neurons: vec![[0.0, 0.3]],
            bias_output: 1,
            recurrent_output: 2,
        };
        let p = HyperParams::default();
        let c = decode(&mut cppn, &l, &p).unwrap();
        assert_eq!(c.sheet_sizes(), &[2, 1]);
        assert_eq!(c.input_weight(0, 0), p.express(0.5).unwrap());
        assert_eq!(c.input_weight(2, 0), p.express(-0.9).unwrap());
        let sources: Vec<LinkSource> = c.links().map(|l| l.source).collect();
        assert_eq!(
            sources,
            vec![
                LinkSource::Input { sheet: 0, index: 0 },
                LinkSource::Input { sheet: 0, index: 1 },
                LinkSource::Input { sheet: 1, index: 0 },
            ]
        );
    }

    #[test]
    fn bad_layouts_are_errors() {
        let p = HyperParams::default();
        let mut three = FnCppn(|_: &[f64]| [0.0; 3]);
        let mut l = layout(vec![[0.0, 0.0]], vec![[0.0, 1.0]]);
        l.inputs[0].cppn_output = 3;
        assert!(matches!(
            decode(&mut three, &l, &p),
            Err(HyperError::CppnOutput { output: 3, .. })
        ));
        let l = layout(vec![[0.0, 0.0]], vec![]);
        assert_eq!(
            decode(&mut three, &l, &p).unwrap_err(),
            HyperError::NoNeurons
        );
        let l = layout(vec![[f64::INFINITY, 0.0]], vec![[0.0, 1.0]]);
        assert!(matches!(
            decode(&mut three, &l, &p),
            Err(HyperError::BadCoordinate { .. })
        ));
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

    /// Random CPPN genomes grown by the NEAT mutations.
    fn random_genomes(count: usize, seed: u64) -> Vec<Genome> {
        use crate::genome::GenomeSpec;
        use crate::innovation::InnovationTracker;
        use crate::mutation::{
            mutate_activation, mutate_add_link, mutate_add_node, mutate_toggle_enable,
        };
        use crate::params::NeatParams;
        use rand::SeedableRng;
        let spec = GenomeSpec::cppn();
        let params = NeatParams::default();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        (0..count)
            .map(|i| {
                let mut tracker = InnovationTracker::new(8);
                let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
                for _ in 0..(i % 7) * 3 {
                    mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
                    mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
                    mutate_activation(&mut g, &spec, &mut rng);
                    mutate_toggle_enable(&mut g, &mut rng);
                }
                g
            })
            .collect()
    }

    #[test]
    fn batched_decode_equals_feed_forward_decode() {
        let grid = |r: usize, a: usize| -> Vec<[f64; 2]> {
            (0..r * a)
                .map(|i| {
                    [
                        (i % a) as f64 / a as f64 - 0.5,
                        (i / a + 1) as f64 / r as f64,
                    ]
                })
                .collect()
        };
        // Sheets longer than one batch exercise the chunking.
        let l = SubstrateLayout {
            inputs: vec![InputSheet {
                coords: grid(3, 100),
                cppn_output: 0,
            }],
            neurons: grid(2, 5),
            bias_output: 1,
            recurrent_output: 2,
        };
        let p = HyperParams::default();
        let mut hidden = 0;
        for g in random_genomes(20, 7) {
            hidden += g.num_hidden();
            let batched = decode_genome(&g, &l, &p).unwrap();
            let plain = decode(&mut FeedForwardNetwork::from_genome(&g), &l, &p).unwrap();
            assert_eq!(batched, plain);
        }
        assert!(hidden > 20, "genomes should have hidden nodes");
    }

    #[test]
    fn batch_cppn_matches_single_queries() {
        for g in random_genomes(10, 11) {
            let mut ff = FeedForwardNetwork::from_genome(&g);
            let mut b = BatchCppn::new(&g).unwrap();
            let sources: Vec<[f64; 2]> = (0..300)
                .map(|i| [(i as f64 * 0.37).sin(), i as f64 / 300.0])
                .collect();
            for output in 0..3 {
                let mut batched = vec![0.0; sources.len()];
                b.query_sources(output, [0.25, -0.5], &sources, &mut batched);
                for (q, &[x2, y2]) in sources.iter().enumerate() {
                    let mut out = [0.0; 3];
                    ff.activate(&[0.25, -0.5, x2, y2, 1.0], &mut out);
                    assert_eq!(out[output].to_bits(), batched[q].to_bits());
                }
                b.query_targets(output, &sources, [0.7, 0.1], &mut batched);
                for (q, &[x1, y1]) in sources.iter().enumerate() {
                    let mut out = [0.0; 3];
                    ff.activate(&[x1, y1, 0.7, 0.1, 1.0], &mut out);
                    assert_eq!(out[output].to_bits(), batched[q].to_bits());
                }
            }
        }
    }
}

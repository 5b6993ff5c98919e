//! The decoded controller: a one-layer, fully recurrent network.

use serde::{Deserialize, Serialize};

use super::error::HyperError;
use super::layout::SubstrateLayout;
use crate::activation::bipolar_sigmoid;
use crate::network::Network;

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

impl SubstrateController {
    /// Assembles a decoded controller (sizes already consistent with `layout`).
    pub(super) fn from_parts(layout: &SubstrateLayout, bias: Vec<f64>, weights: Vec<f64>) -> Self {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperneat::test_util::{FnCppn, close, known, layout};
    use crate::hyperneat::{HyperParams, InputSheet, decode};

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

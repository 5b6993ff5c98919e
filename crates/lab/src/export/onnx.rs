//! The ONNX artifact: one step as an ONNX graph (opset [`OPSET`], IR version
//! [`IR_VERSION`], every tensor f64, or f32 for a controller in fast
//! precision), encoded by hand (`super::proto`):
//! no dependency, and the file is a few `MatMul`, `Add`, `Exp` and
//! element-wise nodes any runtime has.
//!
//! Inputs `sensors` `[N, inputs]` (each read as vivae reads it: NaN as 0,
//! then clamped to the net's reading range) and `state` `[N, nodes]` (zeros at the
//! start); outputs `outputs` `[N, outputs]` (the network's outputs in
//! its order) and `next_state` `[N, nodes]`, and for a robot's controller
//! `wheels` `[N, 2]` (left, right: the same values as `outputs`, under the
//! name earlier exports gave them). A recurrent network is one synchronous update of every
//! node; a feed-forward ES network is one update per topological level
//! (each level's new values are placed into the value vector by a 0/1
//! matrix, which adds exact zeros only). The sums are `MatMul`s, so their
//! order is the runtime's, not vivae's: equal to rounding (the measured
//! bounds are in docs/howto/export-bits.md).
//! The sensor geometry and what the outputs mean are in the model's
//! `metadata_props` (`vivae_geometry`: JSON; `outputs`, and `wheels` for a
//! robot's controller; `description`).

use vivae_neat::Precision;

use super::proto::Message;
use super::{Exported, SIGMOID_SLOPE, StepNet};

/// The operator set the model imports.
pub const OPSET: i64 = 17;
/// The ONNX IR version of opset 17.
pub const IR_VERSION: i64 = 8;
/// ONNX's data type number of f64.
const DOUBLE: i64 = 11;
/// ONNX's data type number of f32.
const FLOAT: i64 = 1;
/// ONNX's data type number of i64.
const INT64: i64 = 7;
/// AttributeProto's type number of an int.
const ATTRIBUTE_INT: i64 = 2;

/// The graph being built: its nodes and constant tensors.
struct Graph {
    graph: Message,
    counter: usize,
    /// The real tensors' type: [`DOUBLE`] or [`FLOAT`].
    real: i64,
}

impl Graph {
    /// A fresh name for an intermediate value.
    fn fresh(&mut self, what: &str) -> String {
        self.counter += 1;
        format!("{what}_{}", self.counter)
    }

    /// Node `op` of `inputs` into a fresh output (or `out`), with int attributes.
    fn node(
        &mut self,
        op: &str,
        inputs: &[&str],
        out: Option<&str>,
        ints: &[(&str, i64)],
    ) -> String {
        let out = out.map_or_else(|| self.fresh(&op.to_lowercase()), str::to_string);
        let mut n = Message::new();
        for i in inputs {
            n.string(1, i);
        }
        n.string(2, &out).string(3, &out).string(4, op);
        for (name, v) in ints {
            let mut a = Message::new();
            a.string(1, name).int(3, *v).int(20, ATTRIBUTE_INT);
            n.message(5, &a);
        }
        self.graph.message(1, &n);
        out
    }

    /// A constant real tensor of shape `dims` (f32: each value rounded,
    /// exact for the f32 values of a fast controller).
    fn reals(&mut self, what: &str, dims: &[usize], v: &[f64]) -> String {
        let raw: Vec<u8> = if self.real == FLOAT {
            v.iter().flat_map(|&x| (x as f32).to_le_bytes()).collect()
        } else {
            v.iter().flat_map(|x| x.to_le_bytes()).collect()
        };
        self.tensor(what, dims, self.real, &raw)
    }

    /// A constant i64 tensor of shape `dims`.
    fn longs(&mut self, what: &str, dims: &[usize], v: &[i64]) -> String {
        let raw: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.tensor(what, dims, INT64, &raw)
    }

    fn tensor(&mut self, what: &str, dims: &[usize], data_type: i64, raw: &[u8]) -> String {
        let name = self.fresh(what);
        let mut t = Message::new();
        for &d in dims {
            t.int(1, d as i64);
        }
        t.int(2, data_type).string(8, &name).bytes(9, raw);
        self.graph.message(5, &t);
        name
    }

    /// σ(z) = 2/(1 + exp(−4.9·z)) − 1, node by node.
    fn sigma(&mut self, z: &str, out: Option<&str>) -> String {
        let slope = self.reals("slope", &[], &[-SIGMOID_SLOPE]);
        let one = self.reals("one", &[], &[1.0]);
        let two = self.reals("two", &[], &[2.0]);
        let t = self.node("Mul", &[z, &slope], None, &[]);
        let e = self.node("Exp", &[&t], None, &[]);
        let d = self.node("Add", &[&e, &one], None, &[]);
        let q = self.node("Div", &[&two, &d], None, &[]);
        self.node("Sub", &[&q, &one], out, &[])
    }
}

/// A value declaration `[N, width]` of the real type `real`.
fn value_info(name: &str, width: usize, real: i64) -> Message {
    let mut batch = Message::new();
    batch.string(2, "N");
    let mut w = Message::new();
    w.int(1, width as i64);
    let mut shape = Message::new();
    shape.message(1, &batch).message(1, &w);
    let mut tensor = Message::new();
    tensor.int(1, real).message(2, &shape);
    let mut ty = Message::new();
    ty.message(1, &tensor);
    let mut v = Message::new();
    v.string(1, name).message(2, &ty);
    v
}

/// The nodes of each topological level of a feed-forward net (a node's
/// level is one more than its deepest node source's).
pub(super) fn levels(net: &StepNet) -> Vec<Vec<usize>> {
    let ni = net.inputs;
    let mut level = vec![0usize; net.nodes];
    for &k in &net.order {
        let sources = &net.sources[net.starts[k]..net.starts[k + 1]];
        level[k] = (sources.iter().filter(|&&j| j >= ni))
            .map(|&j| level[j - ni] + 1)
            .max()
            .unwrap_or(0);
    }
    let deepest = level.iter().copied().max().unwrap_or(0);
    let mut out = vec![Vec::new(); deepest + 1];
    for &k in &net.order {
        out[level[k]].push(k);
    }
    out
}

/// The weights `[sources, nodes.len()]` and biases of `nodes`, dense.
fn dense(net: &StepNet, nodes: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let m = net.inputs + net.nodes;
    let mut w = vec![0.0; m * nodes.len()];
    for (c, &k) in nodes.iter().enumerate() {
        for l in net.starts[k]..net.starts[k + 1] {
            w[net.sources[l] * nodes.len() + c] = net.weights[l];
        }
    }
    (w, nodes.iter().map(|&k| net.bias[k]).collect())
}

/// One update of `nodes` from the value vector `v`: their new values `[N, nodes.len()]`.
fn update(g: &mut Graph, net: &StepNet, v: &str, nodes: &[usize], out: Option<&str>) -> String {
    let (w, b) = dense(net, nodes);
    let w = g.reals("weights", &[net.inputs + net.nodes, nodes.len()], &w);
    let b = g.reals("bias", &[nodes.len()], &b);
    let z = g.node("MatMul", &[v, &w], None, &[]);
    let z = g.node("Add", &[&z, &b], None, &[]);
    g.sigma(&z, out)
}

/// `exported` as an ONNX model's bytes.
pub fn to_onnx(exported: &Exported) -> Vec<u8> {
    let net = &exported.net;
    let (ni, n) = (net.inputs, net.nodes);
    let real = match net.precision {
        Precision::Exact => DOUBLE,
        Precision::Fast => FLOAT,
    };
    let mut g = Graph {
        graph: Message::new(),
        counter: 0,
        real,
    };
    // Readings as vivae reads them (`Readings::read`): NaN as 0, then
    // clamped to the net's range.
    let zero = g.reals("zero", &[], &[0.0]);
    let low = g.reals("reading_low", &[], &[net.readings.low]);
    let high = g.reals("reading_high", &[], &[net.readings.high]);
    let nan = g.node("IsNaN", &["sensors"], None, &[]);
    let read = g.node("Where", &[&nan, &zero, "sensors"], None, &[]);
    let read = g.node("Clip", &[&read, &low, &high], None, &[]);
    let mut v = g.node("Concat", &[&read, "state"], None, &[("axis", 1)]);
    let next = if net.synchronous {
        update(
            &mut g,
            net,
            &v,
            &(0..n).collect::<Vec<_>>(),
            Some("next_state"),
        )
    } else {
        for nodes in levels(net) {
            let y = update(&mut g, net, &v, &nodes, None);
            // v ← v·keep + y·place: untouched entries times 1 plus exact zeros.
            let mut keep = vec![1.0; ni + n];
            let mut place = vec![0.0; nodes.len() * (ni + n)];
            for (r, &k) in nodes.iter().enumerate() {
                keep[ni + k] = 0.0;
                place[r * (ni + n) + ni + k] = 1.0;
            }
            let keep = g.reals("keep", &[ni + n], &keep);
            let place = g.reals("place", &[nodes.len(), ni + n], &place);
            let kept = g.node("Mul", &[&v, &keep], None, &[]);
            let placed = g.node("MatMul", &[&y, &place], None, &[]);
            v = g.node("Add", &[&kept, &placed], None, &[]);
        }
        let idx: Vec<i64> = (ni..ni + n).map(|i| i as i64).collect();
        let idx = g.longs("state_index", &[n], &idx);
        g.node("Gather", &[&v, &idx], Some("next_state"), &[("axis", 1)])
    };
    let no = net.outputs.len();
    let outputs: Vec<i64> = net.outputs.iter().map(|&k| k as i64).collect();
    let outputs = g.longs("output_index", &[no], &outputs);
    g.node(
        "Gather",
        &[&next, &outputs],
        Some("outputs"),
        &[("axis", 1)],
    );
    if exported.drives_wheels() {
        g.node("Identity", &["outputs"], Some("wheels"), &[]);
    }
    let mut graph = g.graph;
    graph
        .string(2, "vivae_controller_step")
        .string(10, &exported.description)
        .message(11, &value_info("sensors", ni, real))
        .message(11, &value_info("state", n, real))
        .message(12, &value_info("outputs", no, real))
        .message(12, &value_info("next_state", n, real));
    if exported.drives_wheels() {
        graph.message(12, &value_info("wheels", no, real));
    }
    model(exported, &graph)
}

/// The model around `graph`, with the geometry in its metadata.
fn model(exported: &Exported, graph: &Message) -> Vec<u8> {
    let mut opset = Message::new();
    opset.string(1, "").int(2, OPSET);
    let geometry = serde_json::to_string(&exported.sheets).expect("geometry serialises");
    let mut m = Message::new();
    m.int(1, IR_VERSION)
        .string(2, "vivae")
        .string(3, env!("CARGO_PKG_VERSION"))
        .string(6, &exported.description)
        .message(7, graph)
        .message(8, &opset);
    let wheels = exported
        .drives_wheels()
        .then_some(("wheels", exported.outputs.as_str()));
    for (key, value) in [
        ("vivae_geometry", geometry.as_str()),
        ("outputs", exported.outputs.as_str()),
        ("units", exported.units.as_str()),
        ("substrate", exported.substrate.as_str()),
        ("description", exported.description.as_str()),
    ]
    .into_iter()
    .chain(wheels)
    {
        let mut e = Message::new();
        e.string(1, key).string(2, value);
        m.message(14, &e);
    }
    m.into_bytes()
}

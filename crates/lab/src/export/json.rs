//! The JSON artifact: the step network, its activation and the sensor
//! geometry, for any program that wants to build the controller itself.

use serde::Serialize;

use super::Exported;

/// The format's name and version, the file's first keys.
pub const FORMAT: &str = "vivae-controller";
/// Version of the JSON layout.
pub const VERSION: u32 = 1;

/// The document: a header, how to run the network, then the controller.
#[derive(Serialize)]
struct Document<'a> {
    format: &'static str,
    version: u32,
    activation: &'static str,
    step: &'static str,
    #[serde(flatten)]
    exported: &'a Exported,
}

/// How a step runs, in words (the `step` key).
pub const STEP: &str = "state starts at zeros (net.nodes values). For each node k in net.order: \
s = net.bias[k]; for l in net.starts[k]..net.starts[k+1]: j = net.sources[l]; \
x = j < net.inputs ? sensors[j] : state[j - net.inputs]; s += net.weights[l] * x. \
If net.synchronous, every node reads the previous state and all new values are written \
after the loop; otherwise node k's new value replaces state[k] at once. \
The wheel commands are the new values of nodes net.wheels[0] (left) and net.wheels[1] (right). \
All in f64 when net.precision is \"exact\". When it is \"fast\" (vivae's --precision fast step), \
sensors, state, bias and weights are f32 values and so is every operation: s = fma(w, x, s) \
rounded once, and exp is vivae's f32 exp (Cephes' expf: x clamped to [-87, 88], k = round(x*log2(e)), \
r = x - k*0.6933594 - k*(-2.1219444e-4), e^r = 1 + r + r^2*P(r) with P's coefficients \
1.9875691e-4, 1.3981999e-3, 8.333452e-3, 4.1665796e-2, 1.6666666e-1, 0.5 from r^5 down, times 2^k).";

/// The activation every node applies (the `activation` key).
pub const ACTIVATION: &str = "bipolar sigmoid: 2 / (1 + exp(-4.9 * s)) - 1";

/// `exported` as pretty-printed JSON (f64s written so that they read back to the same bits).
pub fn to_json(exported: &Exported) -> String {
    let doc = Document {
        format: FORMAT,
        version: VERSION,
        activation: ACTIVATION,
        step: STEP,
        exported,
    };
    let mut s = serde_json::to_string_pretty(&doc).expect("an exported controller serialises");
    s.push('\n');
    s
}

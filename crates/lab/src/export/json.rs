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
All in f64.";

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

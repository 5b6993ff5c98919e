//! The JSON artifact: the step network, its activation and the sensor
//! geometry, for any program that wants to build the controller itself —
//! and, in `arithmetic`, every operation of the step to the bit: the sums'
//! order, the sigmoid's and vivae's portable `exp` (both precisions) with
//! their constants as exact hexadecimal floats, so that a reader that
//! follows it gets vivae's outputs (a robot's wheel commands) bit for bit.

use serde::Serialize;
use serde_json::{Value, json};

use super::{Exported, SIGMOID_SLOPE};

/// The format's name and version, the file's first keys.
pub const FORMAT: &str = "vivae-controller";
/// Version of the JSON layout (2: the `readings` and `arithmetic` keys;
/// 3: the reading range `net.readings`; 4: any number of outputs,
/// `net.outputs` and `outputs` where 3 had two, `net.wheels` and `wheels`).
pub const VERSION: u32 = 4;

/// The document: a header, how to run the network, then the controller.
#[derive(Serialize)]
struct Document<'a> {
    format: &'static str,
    version: u32,
    activation: &'static str,
    step: &'static str,
    readings: &'static str,
    arithmetic: Value,
    #[serde(flatten)]
    exported: &'a Exported,
}

/// How a step runs, in words (the `step` key).
pub const STEP: &str = "state starts at zeros (net.nodes values). For each node k in net.order: \
s = net.bias[k]; for l in net.starts[k]..net.starts[k+1]: j = net.sources[l]; \
x = j < net.inputs ? reading(sensors[j]) : state[j - net.inputs]; s += net.weights[l] * x; \
then the node's new value is sigmoid(s). \
If net.synchronous, every node reads the previous state and all new values are written \
after the loop; otherwise node k's new value replaces state[k] at once. \
The step's outputs are the new values of nodes net.outputs[0], net.outputs[1], ... in that \
order (a robot's two: its left wheel, then its right; the `outputs` key says what they mean). \
reading is the `readings` key. Every operation is IEEE 754 arithmetic as `arithmetic` says, \
in binary64 when net.precision is \"exact\" (arithmetic.exact) and in binary32 when it is \
\"fast\" (arithmetic.fast: vivae's --precision fast step, whose sums are fused multiply-adds).";

/// What an input is read as (the `readings` key).
pub const READINGS: &str = "reading(v) = 0 if v is NaN, then net.readings.high if v > \
net.readings.high; net.readings.low if v < net.readings.low; v otherwise: every input is \
clamped to the range its task declares, NaN read as 0 (then clamped), +inf as high and -inf \
as low, in every format and in vivae, so every reading is finite. A robot's sensors read \
[0, 1], which holds the simulator's own readings; a plain task's observations read every \
finite binary64 (low = -high = -1.7976931348623157e308), so a finite observation is read as it is.";

/// The activation every node applies (the `activation` key).
pub const ACTIVATION: &str = "bipolar sigmoid: 2 / (1 + exp(-4.9 * s)) - 1";

/// How the statements of `arithmetic` are evaluated (both precisions).
const EVALUATION: &str = "Each statement is evaluated with the usual precedence, left to \
right (a - b * c - d * e is (a - (b * c)) - (d * e)); every +, -, *, / is one IEEE 754 \
operation of the precision's format, rounded to nearest, ties to even: no operation is \
fused into a multiply-add unless written fma, reordered or kept in a wider format. Constants \
are exact hexadecimal floats (C99 %a: 0x1.8p+1 = 3), each a value of the precision's format; \
a name with [i] is the i-th (from 0) of a list; `for i = a .. b` runs i = a, a + 1, ..., b; \
2^k is two to the integer k, exactly.";

/// `v` as an exact C99 hexadecimal float (`%a`), e.g. `0x1.71547652b82fep+0`.
pub fn hex64(v: f64) -> String {
    let bits = v.to_bits();
    let sign = if bits >> 63 == 1 { "-" } else { "" };
    let exponent = ((bits >> 52) & 0x7ff) as i64;
    let mantissa = bits & ((1 << 52) - 1);
    hex(sign, exponent, mantissa, 1023, format!("{mantissa:013x}"))
}

/// `v` as an exact C99 hexadecimal float, e.g. `0x1.715476p+0`.
pub fn hex32(v: f32) -> String {
    let bits = v.to_bits();
    let sign = if bits >> 31 == 1 { "-" } else { "" };
    let exponent = i64::from((bits >> 23) & 0xff);
    let mantissa = u64::from(bits & ((1 << 23) - 1));
    hex(
        sign,
        exponent,
        mantissa,
        127,
        format!("{:06x}", mantissa << 1),
    )
}

/// The hexadecimal float of a finite value's fields (`digits`: the
/// mantissa's hex digits).
fn hex(sign: &str, exponent: i64, mantissa: u64, bias: i64, digits: String) -> String {
    if exponent == 0 && mantissa == 0 {
        return format!("{sign}0x0p+0");
    }
    // Subnormals: 0x0.<digits>p(1 - bias).
    let (lead, e) = if exponent == 0 {
        (0, 1 - bias)
    } else {
        (1, exponent - bias)
    };
    let digits = digits.trim_end_matches('0');
    if digits.is_empty() {
        format!("{sign}0x{lead}p{e:+}")
    } else {
        format!("{sign}0x{lead}.{digits}p{e:+}")
    }
}

/// The `arithmetic` key: the step's operations and functions in both precisions.
fn arithmetic() -> Value {
    use vivae_neat::math::exp_constants as e64;
    use vivae_neat::precision::exp_f32_constants as e32;
    let taylor: Vec<String> = std::iter::once(e64::TAYLOR_FIRST)
        .chain(e64::TAYLOR)
        .map(hex64)
        .collect();
    let p: Vec<String> = e32::P.iter().map(|&v| hex32(v)).collect();
    let sigmoid = ["t = slope * s", "e = exp(t)", "return 2 / (1 + e) - 1"];
    json!({
        "evaluation": EVALUATION,
        "exact": {
            "format": "IEEE 754 binary64 for everything: readings, state, weights, bias and every operation",
            "sum": "s = bias[k]; then for each link l of node k in order: s = s + weights[l] * x (the product rounded, then the sum)",
            "sigmoid": {
                "statements": sigmoid,
                "constants": { "slope": hex64(-SIGMOID_SLOPE) },
            },
            "exp": {
                "about": "vivae's portable exp: x = k ln2 + r with ln 2 in two parts, e^r by its Taylor series to r^12 in Horner's order, times 2^k",
                "statements": [
                    "if x is not NaN: x = min(max(x, low), high)",
                    "kf = x * log2e + shift",
                    "k = kf - shift",
                    "r = x - k * ln2_hi - k * ln2_lo",
                    "p = taylor[0]",
                    "for i = 1 .. 12: p = p * r + taylor[i]",
                    "return p * 2^k",
                ],
                "notes": "k is an integer in [-1021, 1023] after the clamp, so 2^k is an exact normal binary64 and the last statement one rounded product (vivae builds 2^k from kf's bits); a NaN x gives NaN. A step's sums are finite (readings are clamped), so NaN never reaches exp.",
                "constants": {
                    "low": hex64(-708.0),
                    "high": hex64(709.0),
                    "log2e": hex64(e64::LOG2E),
                    "shift": hex64(e64::SHIFT),
                    "ln2_hi": hex64(e64::LN2_HI),
                    "ln2_lo": hex64(e64::LN2_LO),
                    "taylor": taylor,
                },
            },
        },
        "fast": {
            "format": "IEEE 754 binary32 for everything: readings (reading(v) rounded to the nearest binary32), state, weights, bias and every operation",
            "sum": "s = bias[k]; then for each link l of node k in order: s = fma(weights[l], x, s), where fma(a, b, c) is a * b + c computed exactly and rounded once (IEEE 754 fusedMultiplyAdd)",
            "sigmoid": {
                "statements": sigmoid,
                "constants": { "slope": hex32(-SIGMOID_SLOPE as f32) },
            },
            "exp": {
                "about": "vivae's f32 exp (Cephes' expf): x = k ln2 + r with ln 2 in two parts, e^r = 1 + r + r^2 P(r) with a degree-5 P in Horner's order, times 2^k",
                "statements": [
                    "if x is not NaN: x = min(max(x, low), high)",
                    "kf = x * log2e + shift",
                    "k = kf - shift",
                    "r = x - k * ln2_hi - k * ln2_lo",
                    "q = p[0]",
                    "for i = 1 .. 5: q = q * r + p[i]",
                    "y = q * (r * r) + r + 1",
                    "return y * 2^k",
                ],
                "notes": "k is an integer in [-126, 127] after the clamp, so 2^k is an exact normal binary32 and the last statement one rounded product (vivae builds 2^k from kf's bits); a NaN x gives NaN.",
                "constants": {
                    "low": hex32(e32::LOW),
                    "high": hex32(e32::HIGH),
                    "log2e": hex32(e32::LOG2E),
                    "shift": hex32(e32::SHIFT),
                    "ln2_hi": hex32(e32::LN2_HI),
                    "ln2_lo": hex32(e32::LN2_LO),
                    "p": p,
                },
            },
        },
    })
}

/// `exported` as pretty-printed JSON (f64s written so that they read back to the same bits).
pub fn to_json(exported: &Exported) -> String {
    let doc = Document {
        format: FORMAT,
        version: VERSION,
        activation: ACTIVATION,
        step: STEP,
        readings: READINGS,
        arithmetic: arithmetic(),
        exported,
    };
    let mut s = serde_json::to_string_pretty(&doc).expect("an exported controller serialises");
    s.push('\n');
    s
}

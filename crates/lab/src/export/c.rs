//! The C artifact: one dependency-free C99 file with
//! `void vivae_step(const double *in, double *state, double *out)` and a
//! header with the sensor layout.
//!
//! The file computes vivae's step in the same f64 operations in the same
//! order, with vivae's portable `exp` written out: compiled without
//! contracting `a*b + c` into FMA (`-ffp-contract=off`; GCC and Clang do not
//! contract on plain x86-64 anyway) on an IEEE machine evaluating doubles as
//! doubles (`FLT_EVAL_METHOD == 0`: x86-64, AArch64), it gives vivae's bits.

use std::fmt::Write;

use super::{Exported, SIGMOID_SLOPE};

/// A C literal that reads back to exactly `v` (shortest round-trip decimal;
/// C compilers round decimal literals correctly).
fn lit(v: f64) -> String {
    let s = format!("{v:e}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// The header: sizes, the sensor layout, the wheels and the step's prototype.
pub fn header(e: &Exported) -> String {
    let net = &e.net;
    let mut h = String::new();
    let _ = writeln!(
        h,
        "/* Written by vivae export: {}. */",
        clean(&e.description)
    );
    h.push_str("#ifndef VIVAE_CONTROLLER_H\n#define VIVAE_CONTROLLER_H\n\n");
    let _ = writeln!(h, "/* Substrate: {}. */", e.substrate);
    let _ = writeln!(h, "#define VIVAE_INPUTS {}", net.inputs);
    let _ = writeln!(h, "#define VIVAE_STATE {}", net.nodes);
    h.push_str("#define VIVAE_OUTPUTS 2\n\n");
    let _ = writeln!(h, "/* Wheels: {}. */", e.wheels);
    let _ = writeln!(h, "/* Units: {}. */\n", e.units);
    for s in &e.sheets {
        let name = s.sensor.to_uppercase();
        let _ = writeln!(h, "/* Sheet \"{}\": {}. */", s.sensor, clean(&s.reading));
        let _ = writeln!(h, "#define VIVAE_{name}_FIRST {}", s.first_input);
        let _ = writeln!(h, "#define VIVAE_{name}_COUNT {}", s.places.len());
        let _ = writeln!(h, "#define VIVAE_{name}_RINGS {}", s.rings);
        let _ = writeln!(h, "#define VIVAE_{name}_FOV_DEG {}\n", lit(s.fov_deg));
    }
    h.push_str(
        "/* Where input i is read: sheet index, ring (0 = nearest), angle index\n   \
         (0 = leftmost), angle from straight ahead in degrees (negative = left)\n   \
         and distance from the robot's centre in px (distance rays: length). */\n\
         struct vivae_place { int sheet; int ring; int angle_index; double angle_deg; double distance; };\n\
         extern const struct vivae_place vivae_places[VIVAE_INPUTS];\n\n\
         /* One step: in[VIVAE_INPUTS] sensor readings, state[VIVAE_STATE]\n   \
         (all zero at the start; updated in place), out[2] the wheel commands. */\n\
         void vivae_step(const double *in, double *state, double *out);\n\
         /* The same step for float readings and commands (the state stays double). */\n\
         void vivae_step_f32(const float *in, double *state, float *out);\n\n\
         #endif\n",
    );
    h
}

/// Text safe inside a C comment.
fn clean(s: &str) -> String {
    s.replace("*/", "* /")
}

/// The C file, including the header named `header_name`.
pub fn source(e: &Exported, header_name: &str) -> String {
    let net = &e.net;
    let mut c = String::new();
    let _ = writeln!(
        c,
        "/* Written by vivae export: {}. */",
        clean(&e.description)
    );
    let _ = writeln!(
        c,
        "/* Compile as C99 without FMA contraction (-ffp-contract=off) for vivae's bits. */"
    );
    let _ = writeln!(
        c,
        "#include \"{header_name}\"\n#include <stdint.h>\n#include <string.h>\n"
    );
    c.push_str("#if defined(__clang__)\n#pragma STDC FP_CONTRACT OFF\n#endif\n\n");
    places(&mut c, e);
    int_table(
        &mut c,
        "starts",
        &net.starts.iter().map(|&v| v as u64).collect::<Vec<_>>(),
    );
    int_table(
        &mut c,
        "sources",
        &net.sources.iter().map(|&v| v as u64).collect::<Vec<_>>(),
    );
    int_table(
        &mut c,
        "order",
        &net.order.iter().map(|&v| v as u64).collect::<Vec<_>>(),
    );
    real_table(&mut c, "bias", &net.bias);
    real_table(&mut c, "weights", &net.weights);
    c.push_str(&exp_function());
    let _ = writeln!(
        c,
        "\n/* vivae's bipolar sigmoid. */\nstatic double sigma(double s) {{\n    \
         return 2.0 / (1.0 + vivae_exp({} * s)) - 1.0;\n}}\n",
        lit(-SIGMOID_SLOPE)
    );
    c.push_str(&step_function(net.synchronous, net.wheels));
    c
}

/// The places table.
fn places(c: &mut String, e: &Exported) {
    c.push_str("const struct vivae_place vivae_places[VIVAE_INPUTS] = {\n");
    for (k, s) in e.sheets.iter().enumerate() {
        for p in &s.places {
            let _ = writeln!(
                c,
                "    {{{k}, {}, {}, {}, {}}},",
                p.ring,
                p.angle_index,
                lit(p.angle_deg),
                lit(p.distance)
            );
        }
    }
    c.push_str("};\n\n");
}

/// A `static const int32_t` table (never empty: C has no empty arrays).
fn int_table(c: &mut String, name: &str, v: &[u64]) {
    let _ = writeln!(c, "static const int32_t {name}[{}] = {{", v.len().max(1));
    rows(c, v.iter().map(u64::to_string), 12);
    if v.is_empty() {
        c.push_str("    0\n");
    }
    c.push_str("};\n\n");
}

/// A `static const double` table (never empty).
fn real_table(c: &mut String, name: &str, v: &[f64]) {
    let _ = writeln!(c, "static const double {name}[{}] = {{", v.len().max(1));
    rows(c, v.iter().map(|&x| lit(x)), 4);
    if v.is_empty() {
        c.push_str("    0.0\n");
    }
    c.push_str("};\n\n");
}

/// Values, `per` to a line.
fn rows(c: &mut String, values: impl Iterator<Item = String>, per: usize) {
    let values: Vec<String> = values.collect();
    for chunk in values.chunks(per) {
        let _ = writeln!(c, "    {},", chunk.join(", "));
    }
}

/// vivae's portable `exp` (`vivae_neat::math::exp`), operation for operation.
fn exp_function() -> String {
    use vivae_neat::math::exp_constants::{LN2_HI, LN2_LO, LOG2E, SHIFT, TAYLOR, TAYLOR_FIRST};
    let coefficients: Vec<String> = TAYLOR.iter().map(|&v| lit(v)).collect();
    format!(
        "/* vivae's portable exp: range reduction by ln 2 split in two, Taylor to r^12. */\n\
         static double vivae_exp(double x) {{\n    \
         static const double c[12] = {{{}}};\n    \
         const double shift = {};\n    \
         if (x == x) {{\n        if (x < -708.0) x = -708.0;\n        if (x > 709.0) x = 709.0;\n    }}\n    \
         double kf = x * {} + shift;\n    \
         double k = kf - shift;\n    \
         double r = x - k * {} - k * {};\n    \
         double p = {};\n    \
         for (int i = 0; i < 12; i++) p = p * r + c[i];\n    \
         uint64_t bits;\n    memcpy(&bits, &kf, sizeof bits);\n    \
         int64_t n = (int64_t)(int32_t)(uint32_t)bits;\n    \
         uint64_t sbits = (uint64_t)(n + 1023) << 52;\n    \
         double scale;\n    memcpy(&scale, &sbits, sizeof scale);\n    \
         return p * scale;\n}}\n",
        coefficients.join(", "),
        lit(SHIFT),
        lit(LOG2E),
        lit(LN2_HI),
        lit(LN2_LO),
        lit(TAYLOR_FIRST),
    )
}

/// The step: the network's nodes in order, synchronously or in place.
fn step_function(synchronous: bool, wheels: [usize; 2]) -> String {
    let (write, finish) = if synchronous {
        (
            "next[k] = sigma(s);",
            "    memcpy(state, next, sizeof next);\n",
        )
    } else {
        ("state[k] = sigma(s);", "")
    };
    let scratch = if synchronous {
        "    double next[VIVAE_STATE];\n"
    } else {
        ""
    };
    format!(
        "void vivae_step(const double *in, double *state, double *out) {{\n\
         {scratch}    \
         for (int o = 0; o < VIVAE_STATE; o++) {{\n        \
         int32_t k = order[o];\n        \
         double s = bias[k];\n        \
         for (int32_t l = starts[k]; l < starts[k + 1]; l++) {{\n            \
         int32_t j = sources[l];\n            \
         double x = j < VIVAE_INPUTS ? in[j] : state[j - VIVAE_INPUTS];\n            \
         s += weights[l] * x;\n        }}\n        \
         {write}\n    }}\n\
         {finish}    \
         out[0] = state[{}];\n    out[1] = state[{}];\n}}\n\n\
         void vivae_step_f32(const float *in, double *state, float *out) {{\n    \
         double x[VIVAE_INPUTS], y[2];\n    \
         for (int i = 0; i < VIVAE_INPUTS; i++) x[i] = in[i];\n    \
         vivae_step(x, state, y);\n    \
         out[0] = (float)y[0];\n    out[1] = (float)y[1];\n}}\n",
        wheels[0], wheels[1]
    )
}

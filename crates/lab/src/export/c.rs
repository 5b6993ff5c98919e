//! The C artifact: one dependency-free C99 file with
//! `void vivae_step(const vivae_real *in, vivae_real *state, vivae_real *out)`
//! and a header with the sensor layout; `vivae_real` is `double` for an
//! exact controller and `float` for a fast one.
//!
//! The file computes vivae's step in the same operations in the same
//! order, with vivae's portable `exp` written out (the f32 one, and the
//! neuron sums' fused multiply-add, for a fast controller). It switches off
//! the contraction of `a*b + c` into one fused multiply-add itself (GCC's
//! `optimize("fp-contract=off")` pragma, which GCC honours where it ignores
//! the standard `FP_CONTRACT` pragma that Clang honours), so any
//! optimisation level and `-march` gives vivae's bits on an IEEE machine
//! evaluating each type in itself (`FLT_EVAL_METHOD == 0`: x86-64, AArch64,
//! Cortex-M with an FPU); `-ffast-math` and its parts, and wider
//! evaluation (x87), are compile errors that say why.

use std::fmt::Write;

use vivae_neat::Precision;

use super::{Exported, Readings, SIGMOID_SLOPE};

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

/// A C `float` literal that reads back to exactly `v`.
fn lit32(v: f32) -> String {
    format!("{v:e}f")
}

/// Whether `e` steps in f32.
fn is_fast(e: &Exported) -> bool {
    e.net.precision == Precision::Fast
}

/// The header: sizes, the sensor layout, what the outputs mean and the step's prototype.
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
    let _ = writeln!(h, "#define VIVAE_OUTPUTS {}\n", net.outputs.len());
    if is_fast(e) {
        h.push_str(
            "/* Precision: fast (vivae's --precision fast step): float readings, states\n   \
             and commands; every sum a fused multiply-add rounded once (portable code,\n   \
             or the C library's fmaf when compiled with -DVIVAE_USE_FMAF and -lm). */\n\
             #define VIVAE_FAST 1\ntypedef float vivae_real;\n\n",
        );
    } else {
        h.push_str(
            "/* Precision: exact (vivae's default step): double readings, states and commands. */\n\
             #define VIVAE_FAST 0\ntypedef double vivae_real;\n\n",
        );
    }
    let _ = writeln!(h, "/* Outputs: {}. */", clean(&e.outputs));
    let _ = writeln!(h, "/* Units: {}. */\n", e.units);
    for s in &e.sheets {
        let name = s.sensor.to_uppercase();
        let _ = writeln!(h, "/* Sheet \"{}\": {}. */", s.sensor, clean(&s.reading));
        let _ = writeln!(h, "#define VIVAE_{name}_FIRST {}", s.first_input);
        let _ = writeln!(h, "#define VIVAE_{name}_COUNT {}", s.places.len());
        let _ = writeln!(h, "#define VIVAE_{name}_RINGS {}", s.rings);
        let _ = writeln!(h, "#define VIVAE_{name}_FOV_DEG {}\n", lit(s.fov_deg));
    }
    let r = net.readings;
    let _ = writeln!(h, "/* The range every input is read in. */");
    let _ = writeln!(h, "#define VIVAE_READING_LOW {}", lit(r.low));
    let _ = writeln!(h, "#define VIVAE_READING_HIGH {}\n", lit(r.high));
    h.push_str(
        "/* Where input i is read: sheet index, ring (0 = nearest), angle index\n   \
         (0 = leftmost), angle from straight ahead in degrees (negative = left)\n   \
         and distance from the robot's centre in px (distance rays: length). */\n\
         struct vivae_place { int sheet; int ring; int angle_index; double angle_deg; double distance; };\n\
         extern const struct vivae_place vivae_places[VIVAE_INPUTS];\n\n\
         /* One step: in[VIVAE_INPUTS] readings (each read as vivae reads it:\n   \
         clamped to [VIVAE_READING_LOW, VIVAE_READING_HIGH], NaN read as 0 then\n   \
         clamped), state[VIVAE_STATE] (all zero at the start; updated in\n   \
         place), out[VIVAE_OUTPUTS] the outputs, as \"Outputs\" above says. */\n\
         void vivae_step(const vivae_real *in, vivae_real *state, vivae_real *out);\n",
    );
    if !is_fast(e) {
        h.push_str(
            "/* The same step for float readings and outputs (the state stays double). */\n\
             void vivae_step_f32(const float *in, double *state, float *out);\n",
        );
    }
    h.push_str("\n#endif\n");
    h
}

/// Text safe inside a C comment.
fn clean(s: &str) -> String {
    s.replace("*/", "* /")
}

/// What makes the file give vivae's bits under any compiler and flags, or
/// refuse to compile: the flags that change IEEE arithmetic are errors that
/// say why, and contraction into fused multiply-adds is switched off for
/// GCC (which ignores `STDC FP_CONTRACT` and contracts at `-O2` and above
/// when the CPU has FMA, e.g. `-march=native`) and Clang alike.
pub const IEEE_GUARDS: &str = "\
/* vivae's bits need IEEE 754 arithmetic, every operation rounded on its own. */
#if defined(__FAST_MATH__)
#error \"vivae controller: -ffast-math (or -Ofast) reorders and fuses the sums, flushes tiny values to zero and assumes no NaN: the step would not give vivae's bits; compile without it\"
#endif
#if defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#error \"vivae controller: -ffinite-math-only assumes no NaN, but the step reads a NaN sensor reading as 0: the step would not give vivae's bits; compile without it\"
#endif
#if defined(__ASSOCIATIVE_MATH__) || defined(__RECIPROCAL_MATH__)
#error \"vivae controller: -fassociative-math or -freciprocal-math reorders the sums or replaces divisions: the step would not give vivae's bits; compile without it\"
#endif
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD > 0
#error \"vivae controller: float and double are evaluated in wider precision here (FLT_EVAL_METHOD > 0, x87): the step would not give vivae's bits; compile for SSE2 (-msse2 -mfpmath=sse) or a 64-bit target\"
#endif
/* No a*b + c contracted into one fused multiply-add where vivae rounds the
   product on its own: Clang honours the standard pragma, GCC only its own. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize(\"fp-contract=off\")
#endif

";

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
        "#include \"{header_name}\"\n#include <float.h>\n#include <stdint.h>\n#include <string.h>\n"
    );
    if is_fast(e) {
        c.push_str("#ifdef VIVAE_USE_FMAF\n#include <math.h>\n#endif\n");
    }
    c.push_str(IEEE_GUARDS);
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
    if is_fast(e) {
        float_table(&mut c, "bias", &net.bias);
        float_table(&mut c, "weights", &net.weights);
        c.push_str(&exp_f32_function());
        c.push('\n');
        c.push_str(&fmaf_function());
        let _ = writeln!(
            c,
            "\n/* vivae's bipolar sigmoid in f32. */\nstatic float sigma(float s) {{\n    \
             return 2.0f / (1.0f + vivae_expf({} * s)) - 1.0f;\n}}\n",
            lit32(-SIGMOID_SLOPE as f32)
        );
    } else {
        real_table(&mut c, "bias", &net.bias);
        real_table(&mut c, "weights", &net.weights);
        c.push_str(&exp_function());
        let _ = writeln!(
            c,
            "\n/* vivae's bipolar sigmoid. */\nstatic double sigma(double s) {{\n    \
             return 2.0 / (1.0 + vivae_exp({} * s)) - 1.0;\n}}\n",
            lit(-SIGMOID_SLOPE)
        );
    }
    c.push_str(&step_function(
        net.synchronous,
        &net.outputs,
        net.readings,
        is_fast(e),
    ));
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

/// A `static const float` table (never empty) of values that are f32 values.
fn float_table(c: &mut String, name: &str, v: &[f64]) {
    let _ = writeln!(c, "static const float {name}[{}] = {{", v.len().max(1));
    rows(c, v.iter().map(|&x| lit32(x as f32)), 4);
    if v.is_empty() {
        c.push_str("    0.0f\n");
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

/// vivae's f32 `exp` (`vivae_neat::precision::exp_f32`), operation for operation.
fn exp_f32_function() -> String {
    use vivae_neat::precision::exp_f32_constants::{
        HIGH, LN2_HI, LN2_LO, LOG2E, LOW, P, SHIFT, SHIFT_BITS,
    };
    let coefficients: Vec<String> = P.iter().map(|&v| lit32(v)).collect();
    format!(
        "/* vivae's f32 exp (Cephes' expf): range reduction by ln 2 split in two,\n   \
         e^r = 1 + r + r^2 P(r) with a degree-5 P, times 2^k from the exponent bits. */\n\
         static float vivae_expf(float x) {{\n    \
         static const float p[6] = {{{}}};\n    \
         const float shift = {};\n    \
         if (x == x) {{\n        if (x < {low}) x = {low};\n        if (x > {high}) x = {high};\n    }}\n    \
         float kf = x * {} + shift;\n    \
         float k = kf - shift;\n    \
         float r = x - k * {} - k * {};\n    \
         float q = p[0];\n    \
         for (int i = 1; i < 6; i++) q = q * r + p[i];\n    \
         float y = q * (r * r) + r + 1.0f;\n    \
         uint32_t bits;\n    memcpy(&bits, &kf, sizeof bits);\n    \
         uint32_t sbits = (uint32_t)(bits - {}u) << 23;\n    \
         float scale;\n    memcpy(&scale, &sbits, sizeof scale);\n    \
         return y * scale;\n}}\n",
        coefficients.join(", "),
        lit32(SHIFT),
        lit32(LOG2E),
        lit32(LN2_HI),
        lit32(LN2_LO),
        SHIFT_BITS,
        low = lit32(LOW),
        high = lit32(HIGH),
    )
}

/// `x·y + z` rounded once to f32 (`vivae_neat::precision::fma_f32`, the
/// fast step's sums): with double operations and no library, or the C
/// library's `fmaf` under `VIVAE_USE_FMAF`; the same bits either way.
pub fn fmaf_function() -> String {
    format!(
        "/* x*y + z rounded once to float (IEEE fusedMultiplyAdd): the product of two\n   \
         floats is exact in double, so the double sum is off by less than half a\n   \
         double ulp and rounds right unless it lies on a float midpoint, where the\n   \
         sum's exact error (TwoSum) decides. */\n\
         #ifdef VIVAE_USE_FMAF\n\
         static float vivae_fmaf(float x, float y, float z) {{\n    \
         return fmaf(x, y, z);\n}}\n\
         #else\n\
         static int vivae_isinf32(float v) {{\n    \
         uint32_t b;\n    memcpy(&b, &v, sizeof b);\n    \
         return (b & 0x7fffffffu) == 0x7f800000u;\n}}\n\n\
         static int vivae_isinf64(double v) {{\n    \
         uint64_t b;\n    memcpy(&b, &v, sizeof b);\n    \
         return (b & 0x7fffffffffffffffu) == 0x7ff0000000000000u;\n}}\n\n\
         /* The next float above a finite v. */\n\
         static float vivae_next_up(float v) {{\n    \
         uint32_t b;\n    memcpy(&b, &v, sizeof b);\n    \
         if ((b & 0x7fffffffu) == 0) b = 1u;\n    \
         else if (b >> 31) b -= 1u;\n    \
         else b += 1u;\n    \
         memcpy(&v, &b, sizeof v);\n    return v;\n}}\n\n\
         static float vivae_fmaf(float x, float y, float z) {{\n    \
         const double two128 = {two128};\n    \
         double xy = (double)x * (double)y;\n    \
         double zw = (double)z;\n    \
         double s = xy + zw;\n    \
         float r = (float)s;\n    \
         double r64 = (double)r;\n    \
         if (r64 == s || s != s) return r;\n    \
         int r_inf = vivae_isinf32(r);\n    \
         float other;\n    double other64, lo, hi;\n    \
         if (r_inf) {{\n        other = r < 0.0f ? -{max} : {max};\n        other64 = (double)other;\n    \
         }} else if (s > r64) {{\n        other = vivae_next_up(r);\n        \
         other64 = vivae_isinf32(other) ? two128 : (double)other;\n    \
         }} else {{\n        other = -vivae_next_up(-r);\n        \
         other64 = vivae_isinf32(other) ? -two128 : (double)other;\n    }}\n    \
         if (r_inf) {{\n        lo = other64;\n        hi = s < 0.0 ? -two128 : two128;\n    \
         }} else {{\n        lo = r64;\n        hi = other64;\n    }}\n    \
         if (s != (lo + hi) * 0.5 || vivae_isinf64(s)) return r;\n    \
         double b = s - xy;\n    \
         double err = (xy - (s - b)) + (zw - b);\n    \
         if (err == 0.0) return r;\n    \
         int toward_other = r_inf ? ((err < 0.0) == (s > 0.0)) : ((err > 0.0) == (other64 > r64));\n    \
         return toward_other ? other : r;\n}}\n\
         #endif\n",
        two128 = lit(2f64.powi(128)),
        max = lit32(f32::MAX),
    )
}

/// The step: the network's nodes in order, synchronously or in place, in
/// f64 or (fast) in f32 with fused sums.
fn step_function(synchronous: bool, outputs: &[usize], r: Readings, fast: bool) -> String {
    let (write, finish) = if synchronous {
        (
            "next[k] = sigma(s);",
            "    memcpy(state, next, sizeof next);\n",
        )
    } else {
        ("state[k] = sigma(s);", "")
    };
    let scratch = if synchronous {
        "    vivae_real next[VIVAE_STATE];\n"
    } else {
        ""
    };
    let sum = if fast {
        "s = vivae_fmaf(weights[l], x, s);"
    } else {
        "s += weights[l] * x;"
    };
    let (low, high, nan) = if fast {
        let l = |v: f64| lit32(v as f32);
        (l(r.low), l(r.high), l(r.read(f64::NAN)))
    } else {
        (lit(r.low), lit(r.high), lit(r.read(f64::NAN)))
    };
    let mut c = format!(
        "/* An input as the step reads it (as vivae does): clamped to the\n   \
         range [VIVAE_READING_LOW, VIVAE_READING_HIGH], NaN read as 0 (then\n   \
         clamped), so every reading is finite. */\n\
         static vivae_real vivae_reading(vivae_real v) {{\n    \
         if (v != v) return {nan};\n    \
         if (v > {high}) return {high};\n    \
         return v < {low} ? {low} : v;\n}}\n\n\
         void vivae_step(const vivae_real *in, vivae_real *state, vivae_real *out) {{\n\
         {scratch}    \
         for (int o = 0; o < VIVAE_STATE; o++) {{\n        \
         int32_t k = order[o];\n        \
         vivae_real s = bias[k];\n        \
         for (int32_t l = starts[k]; l < starts[k + 1]; l++) {{\n            \
         int32_t j = sources[l];\n            \
         vivae_real x = j < VIVAE_INPUTS ? vivae_reading(in[j]) : state[j - VIVAE_INPUTS];\n            \
         {sum}\n        }}\n        \
         {write}\n    }}\n\
         {finish}",
    );
    for (o, k) in outputs.iter().enumerate() {
        let _ = writeln!(c, "    out[{o}] = state[{k}];");
    }
    c.push_str("}\n");
    if !fast {
        c.push_str(
            "\nvoid vivae_step_f32(const float *in, double *state, float *out) {\n    \
             double x[VIVAE_INPUTS], y[VIVAE_OUTPUTS];\n    \
             for (int i = 0; i < VIVAE_INPUTS; i++) x[i] = in[i];\n    \
             vivae_step(x, state, y);\n    \
             for (int o = 0; o < VIVAE_OUTPUTS; o++) out[o] = (float)y[o];\n}\n",
        );
    }
    c
}

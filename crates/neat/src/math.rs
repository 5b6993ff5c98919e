//! Portable floating-point functions: the same bits on every machine.
//!
//! The platform's libm may pick different code paths per CPU (glibc
//! dispatches between FMA and non-FMA variants of `sin`, `cos`, `log`, …),
//! which can change a last bit and with it a whole evolutionary run. Every
//! transcendental function whose result reaches a fitness, a weight or a
//! random draw comes from here: `exp` is our own (plain IEEE arithmetic,
//! branch-free so blocks of neurons vectorise, cheaper than a libm call); the
//! others are the `libm` crate's (a port of musl's, compiled from Rust source,
//! so no runtime dispatch). `sqrt` needs no wrapper: IEEE 754 makes it exact.

/// The constants of [`exp`], for code that must compute it the same way
/// (the C export writes them out).
pub mod exp_constants {
    /// log2(e).
    pub const LOG2E: f64 = std::f64::consts::LOG2_E;
    /// ln 2's high part: k·LN2_HI is exact for |k| < 2^11.
    pub const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    /// ln 2's low part.
    pub const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    /// 1.5·2^52: adding it rounds to an integer held in the low mantissa bits.
    pub const SHIFT: f64 = 6_755_399_441_055_744.0;
    /// The Taylor series' leading coefficient, 1/12!.
    pub const TAYLOR_FIRST: f64 = 1.0 / 479_001_600.0;
    /// The Taylor series' other coefficients, 1/11! down to 1/0!, in Horner order.
    pub const TAYLOR: [f64; 12] = [
        1.0 / 39_916_800.0,
        1.0 / 3_628_800.0,
        1.0 / 362_880.0,
        1.0 / 40_320.0,
        1.0 / 5040.0,
        1.0 / 720.0,
        1.0 / 120.0,
        1.0 / 24.0,
        1.0 / 6.0,
        0.5,
        1.0,
        1.0,
    ];
}

/// `e^x` within a few ULP, computed the same way on every machine.
///
/// The platform's libm may pick different code paths per CPU (glibc has an
/// FMA variant), which could change the last bit between machines; this one
/// is plain IEEE arithmetic, branch-free (so blocks of neurons vectorise) and
/// cheaper than a libm call. Saturates to 0 below −708 and to `e^709` above 709.
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    // One definition: a block of one value is the same code as the scalar chain.
    let mut x = [x];
    exp_block(&mut x);
    x[0]
}

/// [`exp`] of each of `N` values in place: the same bits as `exp` on each.
///
/// Each statement runs across the whole block before the next, so a
/// vectorised block is several independent chains in program order: the
/// CPU overlaps them instead of filling its scheduler with one long chain.
#[inline(always)]
pub fn exp_block<const N: usize>(x: &mut [f64; N]) {
    use exp_constants::{LN2_HI, LN2_LO, LOG2E, SHIFT, TAYLOR, TAYLOR_FIRST};
    for v in x.iter_mut() {
        *v = if v.is_nan() {
            *v
        } else {
            v.clamp(-708.0, 709.0)
        };
    }
    let kf: [f64; N] = std::array::from_fn(|i| x[i] * LOG2E + SHIFT);
    let r: [f64; N] = std::array::from_fn(|i| {
        let k = kf[i] - SHIFT;
        x[i] - k * LN2_HI - k * LN2_LO
    });
    // Taylor series to r^12 on |r| ≤ ln2/2: truncation error < 2e-16 relative.
    let mut p = [TAYLOR_FIRST; N];
    for c in TAYLOR {
        for (p, r) in p.iter_mut().zip(&r) {
            *p = *p * r + c;
        }
    }
    // 2^k from the integer k in kf's low bits: the shift keeps only the low
    // 12 bits of k + 1023 (in [1, 2046] after the clamp), so adding the
    // bias to the raw bits gives the same exponent as extracting k first, in
    // 64-bit integer operations every vector level has.
    for ((v, p), kf) in x.iter_mut().zip(&p).zip(&kf) {
        *v = p * f64::from_bits(kf.to_bits().wrapping_add(1023) << 52);
    }
}

/// `sin x`, the same bits on every machine.
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// `cos x`, the same bits on every machine.
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// `(sin x, cos x)`, the same bits on every machine.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// Natural logarithm, the same bits on every machine.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// `atan2(y, x)`, the same bits on every machine.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// The remainder of `x / y` with `x`'s sign (C's `fmod`), the same bits on every machine.
#[inline]
pub fn fmod(x: f64, y: f64) -> f64 {
    libm::fmod(x, y)
}

/// `tanh x`, the same bits on every machine.
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

/// `sin` of every element, in place: exactly the bits of [`sin`].
///
/// When every |x| < 2²⁰·π/2 (always, for CPPN sums of coordinates), a
/// branch-free copy of musl's `sin` runs over the slice, so the loop
/// vectorises: every branch of the scalar code is computed and the one the
/// scalar code takes is selected, with the same operations in the same
/// order, so the bits are the same. Otherwise the slice goes to [`sin`].
#[inline(always)]
pub fn sin_in_place(xs: &mut [f64]) {
    if xs.iter().fold(true, |ok, &x| ok & lane_range(x)) {
        for x in xs.iter_mut() {
            *x = sin_lane(*x);
        }
    } else {
        for x in xs.iter_mut() {
            *x = sin(*x);
        }
    }
}

/// `cos` of every element, in place: exactly the bits of [`cos`] (as [`sin_in_place`]).
#[inline(always)]
pub fn cos_in_place(xs: &mut [f64]) {
    if xs.iter().fold(true, |ok, &x| ok & lane_range(x)) {
        for x in xs.iter_mut() {
            *x = cos_lane(*x);
        }
    } else {
        for x in xs.iter_mut() {
            *x = cos(*x);
        }
    }
}

/// `(sin x, cos x)` of every element of `xs` into `sin` and `cos`: exactly
/// the bits of [`sin_cos`].
///
/// When every |x| ≤ π/4 (always, for a balanced pole's angle) a branch-free
/// copy of the libm crate's `sincos` for that range — its tiny-argument
/// case and its two kernels, selected, not branched — runs over the slice,
/// so the loop vectorises; otherwise each element goes to [`sin_cos`] (the
/// lane-wise `sin` and `cos` of [`sin_in_place`], which compute every
/// branch, were slower for a failing pole's few large angles).
#[inline(always)]
pub fn sin_cos_in_place(xs: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    if xs
        .iter()
        .fold(true, |ok, &x| ok & (high_word(x) <= 0x3fe9_21fb))
    {
        for ((&x, s), c) in xs.iter().zip(sin).zip(cos) {
            let tiny = high_word(x) < 0x3e46_a09e;
            let (ks, kc) = (k_sin(x, 0.0, false), k_cos(x, 0.0));
            *s = if tiny { x } else { ks };
            *c = if tiny { 1.0 } else { kc };
        }
    } else {
        for ((&x, s), c) in xs.iter().zip(sin).zip(cos) {
            (*s, *c) = sin_cos(x);
        }
    }
}

/// High word of |x|, as musl's trigonometric functions test it.
#[inline(always)]
fn high_word(x: f64) -> u32 {
    ((x.to_bits() >> 32) as u32) & 0x7fff_ffff
}

/// Whether `x` is in the range of [`sin_lane`] / [`cos_lane`]: |x| ≲ 2²⁰·π/2
/// (musl's small and medium argument reductions; no NaN, no infinity).
#[inline(always)]
fn lane_range(x: f64) -> bool {
    high_word(x) < 0x4139_21fb
}

// musl's constants (libm crate: rem_pio2.rs, k_sin.rs, k_cos.rs).
const TO_INT: f64 = 1.5 / f64::EPSILON;
const INV_PIO2: f64 = f64::from_bits(0x3fe4_5f30_6dc9_c883); // 6.36619772367581382433e-1
const PIO2_1: f64 = f64::from_bits(0x3ff9_21fb_5440_0000); // 1.57079632673412561417e0
const PIO2_1T: f64 = f64::from_bits(0x3dd0_b461_1a62_6331); // 6.07710050650619224932e-11
const PIO2_2: f64 = f64::from_bits(0x3dd0_b461_1a60_0000); // 6.07710050630396597660e-11
const PIO2_2T: f64 = f64::from_bits(0x3ba3_198a_2e03_7073); // 2.02226624879595063154e-21
const PIO2_3: f64 = f64::from_bits(0x3ba3_198a_2e00_0000); // 2.02226624871116645580e-21
const PIO2_3T: f64 = f64::from_bits(0x397b_839a_2520_49c1); // 8.47842766036889956997e-32
const S1: f64 = f64::from_bits(0xbfc5_5555_5555_5549); // -1.66666666666666324348e-1
const S2: f64 = f64::from_bits(0x3f81_1111_1110_f8a6); // 8.33333333332248946124e-3
const S3: f64 = f64::from_bits(0xbf2a_01a0_19c1_61d5); // -1.98412698298579493134e-4
const S4: f64 = f64::from_bits(0x3ec7_1de3_57b1_fe7d); // 2.75573137070700676789e-6
const S5: f64 = f64::from_bits(0xbe5a_e5e6_8a2b_9ceb); // -2.50507602534068634195e-8
const S6: f64 = f64::from_bits(0x3de5_d93a_5acf_d57c); // 1.58969099521155010221e-10
const C1: f64 = f64::from_bits(0x3fa5_5555_5555_554c); // 4.16666666666666019037e-2
const C2: f64 = f64::from_bits(0xbf56_c16c_16c1_5177); // -1.38888888888741095749e-3
const C3: f64 = f64::from_bits(0x3efa_01a0_19cb_1590); // 2.48015872894767294178e-5
const C4: f64 = f64::from_bits(0xbe92_7e4f_809c_52ad); // -2.75573143513906633035e-7
const C5: f64 = f64::from_bits(0x3e21_ee9e_bdb4_b1c4); // 2.08757232129817482790e-9
const C6: f64 = f64::from_bits(0xbda8_fae9_be88_38d4); // -1.13596475577881948265e-11

/// musl's `__sin(x, y, iy)`.
#[inline(always)]
fn k_sin(x: f64, y: f64, iy: bool) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    if iy {
        x - ((z * (0.5 * y - v * r) - y) - v * S1)
    } else {
        x + v * (S1 + z * r)
    }
}

/// musl's `__cos(x, y)`.
#[inline(always)]
fn k_cos(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// musl's `__rem_pio2` for π/4 < |x| < 2²⁰·π/2, branch-free: `(n mod 4, y0, y1)`
/// with x ≈ n·π/2 + y0 + y1.
#[inline(always)]
fn rem_pio2_lane(x: f64) -> (u64, f64, f64) {
    let ix = high_word(x);
    // |x| ≤ 9π/4: x − k·π/2 for the k musl picks (signed like x).
    let k = if ix <= 0x4002_d97c {
        1.0
    } else if ix <= 0x400f_6a7a {
        2.0
    } else if ix <= 0x4015_fdbc {
        3.0
    } else {
        4.0
    };
    // x + c equals x − (−c) and (−k)·c equals −(k·c) in IEEE arithmetic, so
    // one formula covers musl's separate branches for either sign.
    let nf = if x.is_sign_negative() { -k } else { k };
    let z = x - nf * PIO2_1;
    let small_y0 = z - nf * PIO2_1T;
    let small_y1 = (z - small_y0) - nf * PIO2_1T;
    // n mod 4 from the low bits of n + 1.5·2⁵² (two's complement, so negative n too).
    let small_n = (nf + TO_INT).to_bits() & 3;
    // Medium: Cody–Waite with up to three rounds.
    let tmp = x * INV_PIO2 + TO_INT;
    let f_n = tmp - TO_INT;
    let medium_n = tmp.to_bits() & 3;
    let r1 = x - f_n * PIO2_1;
    let w1 = f_n * PIO2_1T;
    let y0_1 = r1 - w1;
    let ex = (ix >> 20) as i32;
    let exponent = |y: f64| ((y.to_bits() >> 52) & 0x7ff) as i32;
    let w2 = f_n * PIO2_2;
    let r2 = r1 - w2;
    let w2 = f_n * PIO2_2T - ((r1 - r2) - w2);
    let y0_2 = r2 - w2;
    let w3 = f_n * PIO2_3;
    let r3 = r2 - w3;
    let w3 = f_n * PIO2_3T - ((r2 - r3) - w3);
    let y0_3 = r3 - w3;
    let second = ex - exponent(y0_1) > 16;
    let third = second & (ex - exponent(y0_2) > 49);
    let (r, w, y0) = if third {
        (r3, w3, y0_3)
    } else if second {
        (r2, w2, y0_2)
    } else {
        (r1, w1, y0_1)
    };
    let medium_y1 = (r - y0) - w;
    let medium = (ix > 0x401c_463b)
        | ((ix <= 0x400f_6a7a) & ((ix & 0xfffff) == 0x921fb))
        | (ix == 0x4012_d97c)
        | (ix == 0x4019_21fb);
    if medium {
        (medium_n, y0, medium_y1)
    } else {
        (small_n, small_y0, small_y1)
    }
}

/// musl's `sin` for |x| < 2²⁰·π/2, branch-free (the same bits as [`sin`]).
#[inline(always)]
fn sin_lane(x: f64) -> f64 {
    let ix = high_word(x);
    let tiny = x;
    let small = k_sin(x, 0.0, false);
    let (n, y0, y1) = rem_pio2_lane(x);
    let s = k_sin(y0, y1, true);
    let c = k_cos(y0, y1);
    // n = 0, 1, 2, 3 → s, c, −s, −c (selects, not a switch, so it vectorises).
    let odd = if n & 1 == 0 { s } else { c };
    let reduced = if n & 2 == 0 { odd } else { -odd };
    if ix < 0x3e50_0000 {
        tiny
    } else if ix <= 0x3fe9_21fb {
        small
    } else {
        reduced
    }
}

/// musl's `cos` for |x| < 2²⁰·π/2, branch-free (the same bits as [`cos`]).
#[inline(always)]
fn cos_lane(x: f64) -> f64 {
    let ix = high_word(x);
    // musl returns 1 when also `x as i32 == 0`, always true for such tiny x.
    let small = k_cos(x, 0.0);
    let (n, y0, y1) = rem_pio2_lane(x);
    let s = k_sin(y0, y1, true);
    let c = k_cos(y0, y1);
    // n = 0, 1, 2, 3 → c, −s, −c, s (selects, not a switch, so it vectorises).
    let odd = if n & 1 == 0 { c } else { s };
    let reduced = if (n + 1) & 2 == 0 { odd } else { -odd };
    if ix < 0x3e46_a09e {
        1.0
    } else if ix <= 0x3fe9_21fb {
        small
    } else {
        reduced
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_give_the_bits_of_one_value_at_a_time() {
        let specials = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            708.5,
            -708.5,
            709.5,
            -1e5,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::NAN,
            -f64::NAN,
            1e-300,
            144.6,
        ];
        let mut state = 0xb10c_u64;
        for round in 0..50_000 {
            let xs: [f64; 16] = if round == 0 {
                specials
            } else {
                // Half every exponent, half the sigmoid's working range.
                std::array::from_fn(|i| {
                    state = state
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    let v = f64::from_bits(state);
                    if i % 2 == 0 { v } else { v % 200.0 }
                })
            };
            let (mut e, mut s) = (xs, xs);
            exp_block(&mut e);
            crate::activation::bipolar_sigmoid_block(&mut s);
            for (i, &x) in xs.iter().enumerate() {
                let (want_e, want_s) = (exp(x), crate::activation::bipolar_sigmoid(x));
                assert!(e[i].to_bits() == want_e.to_bits() || e[i].is_nan() && want_e.is_nan());
                assert!(s[i].to_bits() == want_s.to_bits() || s[i].is_nan() && want_s.is_nan());
            }
        }
    }

    #[test]
    fn sin_cos_in_place_gives_the_bits_of_sin_cos() {
        let mut xs: Vec<f64> = (0..200_001)
            .map(|i| (i as f64 - 100_000.0) * (0.8 / 100_000.0))
            .collect();
        // Around the tiny and the π/4 thresholds, and beyond them.
        for b in [0x3e46_a09e_0000_0000u64, 0x3fe9_21fb_0000_0000] {
            for d in 0..2000u64 {
                let x = f64::from_bits(b - 1000 * 0x1_0000_0000 + d * 0x1_0000_0000);
                xs.extend([x, -x]);
            }
        }
        xs.extend((0..4000).map(|i| (i as f64 - 2000.0) * 0.37));
        xs.extend([
            0.0,
            -0.0,
            1e-300,
            5e-324,
            3.0,
            -100.0,
            f64::NAN,
            f64::INFINITY,
        ]);
        for chunk in xs.chunks(8) {
            let (mut s, mut c) = (vec![0.0; chunk.len()], vec![0.0; chunk.len()]);
            sin_cos_in_place(chunk, &mut s, &mut c);
            for ((&x, s), c) in chunk.iter().zip(s).zip(c) {
                let (ws, wc) = sin_cos(x);
                assert_eq!(
                    (s.to_bits(), c.to_bits()),
                    (ws.to_bits(), wc.to_bits()),
                    "{x:e}"
                );
            }
        }
    }

    #[test]
    fn portable_exp_matches_libm_within_a_few_ulp() {
        let mut x = -700.0;
        while x < 700.0 {
            let (ours, libm) = (exp(x), x.exp());
            let ulp = (libm.to_bits() as i64 - ours.to_bits() as i64).abs();
            assert!(ulp <= 4, "exp({x}) = {ours}, libm {libm}: {ulp} ulp apart");
            x += 0.013_7;
        }
        for x in [0.0f64, 1.0, -1.0, 1e-300, -1e-300, 0.5, -0.5] {
            let ulp = (x.exp().to_bits() as i64 - exp(x).to_bits() as i64).abs();
            assert!(ulp <= 2, "exp({x}): {ulp} ulp");
        }
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-1e6), exp(-708.0));
        assert!(exp(-708.0) > 0.0 && exp(-708.0) < 1e-307);
        assert!(exp(1e6).is_finite());
        assert!(exp(f64::NAN).is_nan());
    }

    /// The bits of `exp` recorded before it became a block of one value
    /// (FNV-1a over a sweep of the whole clamped range and the specials):
    /// the one definition still gives every bit it gave.
    #[test]
    fn exp_gives_the_bits_it_always_gave() {
        let mut h = 0xcbf2_9ce4_8422_2325_u64;
        let mut x = -720.0;
        let specials = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e-300,
        ];
        for v in (0..=400_000)
            .map(|_| {
                x += 0.003_6;
                x
            })
            .chain(specials)
        {
            for b in exp(v).to_bits().to_le_bytes() {
                h = (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
            }
        }
        assert_eq!(h, 0x9401_98dc_df46_dc1c, "exp's bits changed: {h:#018x}");
    }

    /// `exp` as it was written before its scale came from the raw bits.
    fn exp_extracting_k(x: f64) -> f64 {
        use exp_constants::{LN2_HI, LN2_LO, LOG2E, SHIFT, TAYLOR, TAYLOR_FIRST};
        let x = if x.is_nan() {
            x
        } else {
            x.clamp(-708.0, 709.0)
        };
        let kf = x * LOG2E + SHIFT;
        let k = kf - SHIFT;
        let r = x - k * LN2_HI - k * LN2_LO;
        let mut p = TAYLOR_FIRST;
        for c in TAYLOR {
            p = p * r + c;
        }
        let k_int = i64::from(kf.to_bits() as i32);
        p * f64::from_bits(((k_int + 1023) as u64) << 52)
    }

    #[test]
    fn exp_scale_from_raw_bits_is_the_extracted_ks() {
        let mut bits = 0x9e37_79b9_7f4a_7c15u64;
        let check = |x: f64| {
            assert_eq!(exp(x).to_bits(), exp_extracting_k(x).to_bits(), "exp({x})");
        };
        for x in [
            0.0,
            -0.0,
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
        ] {
            check(x);
        }
        for x in [-708.0, 709.0, -707.9, 708.9, f64::MAX, f64::MIN, 1e-310] {
            check(x);
        }
        for _ in 0..2_000_000 {
            // xorshift: arguments over the whole clamped range and beyond.
            bits ^= bits << 13;
            bits ^= bits >> 7;
            bits ^= bits << 17;
            check((bits >> 11) as f64 / (1u64 << 53) as f64 * 1500.0 - 750.0);
        }
    }

    #[test]
    fn pinned_bit_patterns() {
        // These exact bits are what every machine must compute; a change here
        // changes every run that uses the function.
        assert_eq!(exp(1.0).to_bits(), 0x4005_bf0a_8b14_576a);
        assert_eq!(sin(1.0).to_bits(), 0x3fea_ed54_8f09_0cee);
        assert_eq!(cos(1.0).to_bits(), 0x3fe1_4a28_0fb5_068c);
        assert_eq!(ln(10.0).to_bits(), 0x4002_6bb1_bbb5_5516);
        assert_eq!(sin_cos(0.5), (sin(0.5), cos(0.5)));
    }

    #[test]
    fn libm_functions_agree_with_std_within_one_ulp() {
        let mut x = -50.0f64;
        while x < 50.0 {
            for (ours, std) in [(sin(x), x.sin()), (cos(x), x.cos())] {
                let ulp = (ours.to_bits() as i64 - std.to_bits() as i64).abs();
                assert!(ulp <= 1, "{x}: {ours} vs {std}");
            }
            if x > 0.0 {
                let ulp = (ln(x).to_bits() as i64 - x.ln().to_bits() as i64).abs();
                assert!(ulp <= 1, "ln {x}");
            }
            x += 0.0371;
        }
    }

    /// Inputs that reach every branch of musl's sin/cos and their edges.
    fn trig_inputs() -> Vec<f64> {
        let mut xs = vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            1e-300,
            1e-9,
            -1e-8,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e300,
            -1e22,
            1e7,
            1.7e6,
            -1.6e6,
            f64::MAX,
        ];
        // Dense sweeps.
        let mut x = -40.0;
        while x < 40.0 {
            xs.push(x);
            x += 0.000_731;
        }
        // Near multiples of π/4 up to large n, a few ULP either side.
        for k in -400i64..=400 {
            let c = k as f64 * std::f64::consts::FRAC_PI_4;
            for d in -3i64..=3 {
                xs.push(f64::from_bits((c.to_bits() as i64 + d) as u64));
            }
        }
        // musl's branch thresholds (high words) with several low words, both signs.
        for hi in [
            0x3e46_a09e_u64,
            0x3e50_0000,
            0x3fe9_21fb,
            0x4002_d97c,
            0x400f_6a7a,
            0x4012_d97c,
            0x4015_fdbc,
            0x4019_21fb,
            0x401c_463b,
            0x4139_21fb,
            0x3ff9_21fb,
            0x4009_21fb,
            0x4029_21fb,
        ] {
            for h in [hi - 1, hi, hi + 1] {
                for lo in [0u64, 1, 0x5444_2d18, 0x8000_0000, 0xffff_ffff] {
                    let bits = (h << 32) | lo;
                    xs.push(f64::from_bits(bits));
                    xs.push(-f64::from_bits(bits));
                }
            }
        }
        // Random bit patterns over all exponents below the medium limit.
        let mut s = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let exponent = 900 + (s >> 53) % 150; // 2^-123 .. 2^26
            xs.push(f64::from_bits(
                (s & 0x800f_ffff_ffff_ffff) | (exponent << 52),
            ));
        }
        xs
    }

    #[test]
    fn lane_wise_sin_and_cos_equal_libm_bit_for_bit() {
        let xs = trig_inputs();
        let mut lanes = 0;
        for &x in &xs {
            if lane_range(x) {
                lanes += 1;
                assert_eq!(sin_lane(x).to_bits(), sin(x).to_bits(), "sin({x:e})");
                assert_eq!(cos_lane(x).to_bits(), cos(x).to_bits(), "cos({x:e})");
            }
        }
        assert!(lanes > 200_000, "{lanes}");
        // The slice versions, with and without out-of-range values in the slice.
        for chunk in xs.chunks(37) {
            let (mut s, mut c) = (chunk.to_vec(), chunk.to_vec());
            sin_in_place(&mut s);
            cos_in_place(&mut c);
            for ((&x, s), c) in chunk.iter().zip(&s).zip(&c) {
                assert_eq!(s.to_bits(), sin(x).to_bits(), "sin({x:e})");
                assert_eq!(c.to_bits(), cos(x).to_bits(), "cos({x:e})");
            }
        }
    }
}

//! The arithmetic precision of the controller step, and the portable single
//! precision functions of the fast one.
//!
//! [`Precision::Exact`] (the default) is f64 with the project's portable
//! [`math::exp`](crate::math::exp): every bit of every run ever recorded.
//! [`Precision::Fast`] stores the controller's weights, biases and states as
//! f32 and squashes with [`bipolar_sigmoid_f32`]: twice the lanes per
//! vector and half the bytes per weight, at a stated loss of accuracy (see
//! [`exp_f32`] and [`bipolar_sigmoid_f32`]). Both are portable: separately
//! rounded IEEE add, multiply and divide, and in fast precision the neuron
//! sums' fused multiply-add ([`fma_f32`]: rounded once, so the instruction
//! and the software give the same bits); no platform libm, the same
//! operations lane by lane at every vector width, so a fast run gives the
//! same bits on every CPU and at every
//! [`SimdLevel`](crate::simd::SimdLevel) — only different bits from an
//! exact run.

use serde::{Deserialize, Serialize};

/// The arithmetic precision of a controller's step.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    /// f64 weights and states, the portable f64 `exp`: the reference bits.
    #[default]
    Exact,
    /// f32 weights and states and the polynomial [`exp_f32`]: faster, other bits.
    Fast,
}

impl Precision {
    /// Whether this is the default, [`Precision::Exact`].
    pub fn is_exact(&self) -> bool {
        *self == Precision::Exact
    }

    /// The name used in configs and on the command line (`exact`, `fast`).
    pub fn name(self) -> &'static str {
        match self {
            Precision::Exact => "exact",
            Precision::Fast => "fast",
        }
    }

    /// The precision named `name` (`exact` or `fast`), if any.
    pub fn from_name(name: &str) -> Option<Precision> {
        match name {
            "exact" => Some(Precision::Exact),
            "fast" => Some(Precision::Fast),
            _ => None,
        }
    }
}

impl std::str::FromStr for Precision {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Precision::from_name(s).ok_or_else(|| format!("'{s}': expected exact or fast"))
    }
}

impl std::fmt::Display for Precision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The constants of [`exp_f32`] (Cephes' `expf`), for code that must
/// compute it the same way.
pub mod exp_f32_constants {
    /// Arguments are clamped to `[LOW, HIGH]`: `e^LOW` is still a normal
    /// f32 (no subnormal slow paths), `e^HIGH` is finite.
    pub const LOW: f32 = -87.0;
    /// See [`LOW`].
    pub const HIGH: f32 = 88.0;
    /// log2(e).
    pub const LOG2E: f32 = std::f32::consts::LOG2_E;
    /// ln 2's high part, 355/512: k·LN2_HI is exact for |k| < 2^15.
    pub const LN2_HI: f32 = 0.693_359_4;
    /// ln 2 − [`LN2_HI`].
    pub const LN2_LO: f32 = -2.121_944_4e-4;
    /// 1.5·2^23: adding it rounds to an integer held in the low mantissa bits.
    pub const SHIFT: f32 = 12_582_912.0;
    /// The bits of [`SHIFT`] less the exponent bias: `bits(x + SHIFT) −
    /// SHIFT_BITS` is the biased exponent of 2^round(x).
    pub const SHIFT_BITS: u32 = 0x4b40_0000 - 127;
    /// The minimax polynomial's coefficients, r^5 down to r^0, in Horner
    /// order: `e^r ≈ 1 + r + r²·P(r)` on |r| ≤ ln2/2.
    pub const P: [f32; 6] = [
        1.987_569_1e-4,
        1.398_199_9e-3,
        8.333_452e-3,
        4.166_579_6e-2,
        1.666_666_5e-1,
        0.5, // Cephes writes 5.0000001201e-1, which rounds to 0.5 in f32
    ];
}

/// `e^x` in single precision, the same bits on every machine.
///
/// Cephes' `expf`: `x = k·ln2 + r` with |r| ≤ ln2/2 (ln 2 in two parts),
/// `e^r ≈ 1 + r + r²·P(r)` with a degree-5 polynomial, times 2^k built from
/// the exponent bits. Branch-free (lanes of a vector loop compute it
/// alike), separately rounded f32 operations only. Arguments are clamped to
/// [−87, 88]; NaN stays NaN.
///
/// **Maximum error**: 1.0e-7 relative (measured: 8.0e-8 at x = 69.66,
/// under 1.4 ULP) against the exact `e^x` over the whole clamped range,
/// checked by this module's test `exp_f32_is_within_its_stated_error` on
/// 4 million arguments.
#[inline(always)]
pub fn exp_f32(x: f32) -> f32 {
    // One definition: a block of one value is the same code as the scalar chain.
    let mut x = [x];
    exp_f32_block(&mut x);
    x[0]
}

/// `x·y + z` rounded once to f32 (IEEE 754 fusedMultiplyAdd, to nearest,
/// ties to even): the bits of the CPU's fused multiply-add instruction,
/// computed with f64 operations where there is none (the scalar level).
///
/// Why it is exact: `x·y` of two f32 is exact in f64 (48 significant bits),
/// and the f64 sum `s` differs from the true `x·y + z` by less than half an
/// f64 ULP, so rounding `s` to f32 is right unless `s` lies exactly halfway
/// between two f32 (f64 holds every such midpoint); there the sum's exact
/// rounding error (Knuth's TwoSum) says on which side the true value lies.
/// The fast precision's neuron sums use it; the test
/// `fma_f32_gives_the_fused_instructions_bits` compares it with the
/// instruction on millions of arguments, halfway cases included.
#[inline(always)]
pub fn fma_f32(x: f32, y: f32, z: f32) -> f32 {
    let s = f64::from(x) * f64::from(y) + f64::from(z);
    let r = s as f32;
    // The common cases, inline. Every f32 midpoint (normal, subnormal, or
    // the overflow threshold 2^128 − 2^103) has its low 28 f64 mantissa bits
    // zero, so an `s` with any of them set is no midpoint, and rounding it
    // once more rounds as the exact value would (rounding to f64 is
    // monotone and keeps every midpoint where it is). An `s` that is an
    // f32 (zero, say) needs no rounding at all.
    if s.to_bits() & 0x0fff_ffff != 0 || f64::from(r) == s {
        return r;
    }
    fma_f32_rare(x, y, z)
}

/// [`fma_f32`] where the f64 sum may lie on an f32 midpoint (or is
/// infinite or NaN): out of line, so the common cases stay small.
#[cold]
#[inline(never)]
fn fma_f32_rare(x: f32, y: f32, z: f32) -> f32 {
    let xy = f64::from(x) * f64::from(y);
    let zw = f64::from(z);
    let s = xy + zw;
    let r = s as f32;
    let r64 = f64::from(r);
    if r64 == s || s.is_nan() {
        return r;
    }
    // The other f32 next to `s` (beyond f32::MAX: 2^128, where f32 rounds to infinity).
    let (other, other64) = if r.is_infinite() {
        let max = f32::MAX.copysign(r);
        (max, f64::from(max))
    } else if s > r64 {
        let up = r.next_up();
        (
            up,
            if up.is_infinite() {
                2f64.powi(128)
            } else {
                f64::from(up)
            },
        )
    } else {
        let down = r.next_down();
        (
            down,
            if down.is_infinite() {
                -(2f64.powi(128))
            } else {
                f64::from(down)
            },
        )
    };
    let (lo, hi) = if r.is_infinite() {
        (other64, 2f64.powi(128).copysign(s))
    } else {
        (r64, other64)
    };
    if s != (lo + hi) * 0.5 || s.is_infinite() {
        return r;
    }
    // `s` is a midpoint, where `as f32` broke the tie to even: the exact
    // error of the f64 sum decides instead.
    let b = s - xy;
    let err = (xy - (s - b)) + (zw - b);
    if err == 0.0 {
        return r;
    }
    let toward_other = if r.is_infinite() {
        (err < 0.0) == (s > 0.0)
    } else {
        (err > 0.0) == (other64 > r64)
    };
    if toward_other { other } else { r }
}

/// The bipolar sigmoid `2/(1+e^(−4.9x)) − 1` in single precision, the same
/// bits on every machine (from [`exp_f32`] and one IEEE division).
///
/// **Maximum error**: 2.0e-7 absolute (measured: 1.9e-7 at x = 0.519, about
/// 3 ULP of the output there; the outputs lie in [−1, 1]) against the exact
/// f64 function of the same argument, over every argument (it saturates to
/// ±1 beyond |x| ≈ 3.5), checked by this module's test
/// `bipolar_sigmoid_f32_is_within_its_stated_error` on 4 million arguments.
#[inline(always)]
pub fn bipolar_sigmoid_f32(x: f32) -> f32 {
    // Not the block function of one value: see `activation::bipolar_sigmoid`.
    2.0 / (1.0 + exp_f32(-4.9 * x)) - 1.0
}

/// [`exp_f32`] of each of `N` values in place: the same bits as `exp_f32`
/// on each, statement by statement across the block (see
/// [`crate::math::exp_block`]).
#[inline(always)]
pub fn exp_f32_block<const N: usize>(x: &mut [f32; N]) {
    use exp_f32_constants::{HIGH, LN2_HI, LN2_LO, LOG2E, LOW, P, SHIFT, SHIFT_BITS};
    for v in x.iter_mut() {
        *v = if v.is_nan() { *v } else { v.clamp(LOW, HIGH) };
    }
    let kf: [f32; N] = std::array::from_fn(|i| x[i] * LOG2E + SHIFT);
    let r: [f32; N] = std::array::from_fn(|i| {
        let k = kf[i] - SHIFT;
        x[i] - k * LN2_HI - k * LN2_LO
    });
    let mut p = [P[0]; N];
    for c in &P[1..] {
        for (p, r) in p.iter_mut().zip(&r) {
            *p = *p * r + c;
        }
    }
    // 2^k: k + 127 into the exponent field (k ∈ [−126, 127] after the clamp).
    for (((v, p), r), kf) in x.iter_mut().zip(&p).zip(&r).zip(&kf) {
        let y = p * (r * r) + r + 1.0;
        *v = y * f32::from_bits(kf.to_bits().wrapping_sub(SHIFT_BITS) << 23);
    }
}

/// [`bipolar_sigmoid_f32`] of each of `N` values in place, the same bits on
/// each (statement by statement across the block).
#[inline(always)]
pub fn bipolar_sigmoid_f32_block<const N: usize>(xs: &mut [f32; N]) {
    let mut e: [f32; N] = std::array::from_fn(|i| -4.9 * xs[i]);
    exp_f32_block(&mut e);
    for (x, e) in xs.iter_mut().zip(&e) {
        *x = 2.0 / (1.0 + e) - 1.0;
    }
}

/// The constants of [`sin_f32`] and [`cos_f32`] (Cephes' `sinf`/`cosf`
/// polynomials with a round-to-nearest quadrant reduction).
pub mod trig_f32_constants {
    /// The lane (polynomial) path serves |x| ≤ `LANE_MAX`; larger
    /// arguments, infinities and NaN go through the f64 portable libm.
    pub const LANE_MAX: f32 = 8192.0;
    /// 2/π.
    pub const FRAC_2_PI: f32 = std::f32::consts::FRAC_2_PI;
    /// 1.5·2^23: adding it rounds to an integer held in the low mantissa bits.
    pub const SHIFT: f32 = 12_582_912.0;
    /// π/2 in three parts (Cephes' DP1..DP3 doubled): n·A and n·B are
    /// exact for |n| < 2^13, so the reduction loses nothing up to [`LANE_MAX`].
    pub const PIO2_A: f32 = 1.570_312_5;
    /// See [`PIO2_A`].
    pub const PIO2_B: f32 = 4.837_513e-4;
    /// See [`PIO2_A`].
    pub const PIO2_C: f32 = 7.549_79e-8;
    /// `sin r ≈ r + r³·(S0 + S1·r² + S2·r⁴)` on |r| ≤ π/4, Horner order.
    pub const SIN: [f32; 3] = [-1.951_529_6e-4, 8.332_161e-3, -1.666_665_5e-1];
    /// `cos r ≈ 1 − r²/2 + r⁴·(C0 + C1·r² + C2·r⁴)` on |r| ≤ π/4, Horner order.
    pub const COS: [f32; 3] = [2.443_315_7e-5, -1.388_731_6e-3, 4.166_664_6e-2];
}

/// `sin x` in single precision, the same bits on every machine.
///
/// For |x| ≤ 8192: `x = n·π/2 + r` with n the nearest integer to x·2/π
/// (π/2 in three parts, so the reduction is exact), Cephes' degree-7 sine
/// or degree-8 cosine polynomial of r chosen by n mod 4 — branch-free
/// selects, separately rounded f32 operations only, so lanes of a vector
/// loop compute it alike. Larger arguments, infinities and NaN take the
/// portable f64 [`math::sin`](crate::math::sin), rounded to f32.
///
/// **Maximum error**: 1.0e-7 absolute (measured: 7.8e-8 at x = −1204.02) against the exact
/// `sin` of the same f32 argument over [−8192, 8192], checked by this
/// module's test `sin_cos_f32_are_within_their_stated_error` on 8 million
/// arguments.
#[inline(always)]
pub fn sin_f32(x: f32) -> f32 {
    if x.abs() <= trig_f32_constants::LANE_MAX {
        trig_f32_lane(x, 0)
    } else {
        crate::math::sin(f64::from(x)) as f32
    }
}

/// `cos x` in single precision, the same bits on every machine (as
/// [`sin_f32`], a quarter turn on; the same stated error).
#[inline(always)]
pub fn cos_f32(x: f32) -> f32 {
    if x.abs() <= trig_f32_constants::LANE_MAX {
        trig_f32_lane(x, 1)
    } else {
        crate::math::cos(f64::from(x)) as f32
    }
}

/// [`sin_f32`] (`quarter` 0) or [`cos_f32`] (`quarter` 1) of every
/// element, in place: a vectorisable loop when every |x| ≤ 8192 (always,
/// for CPPN sums of coordinates), element by element otherwise — the same
/// bits either way.
#[inline(always)]
fn trig_f32_in_place(xs: &mut [f32], quarter: u32) {
    let max = trig_f32_constants::LANE_MAX;
    if xs.iter().fold(true, |ok, &x| ok & (x.abs() <= max)) {
        for x in xs.iter_mut() {
            *x = trig_f32_lane(*x, quarter);
        }
    } else if quarter == 0 {
        xs.iter_mut().for_each(|x| *x = sin_f32(*x));
    } else {
        xs.iter_mut().for_each(|x| *x = cos_f32(*x));
    }
}

/// [`sin_f32`] of every element, in place (the same bits).
#[inline(always)]
pub fn sin_f32_in_place(xs: &mut [f32]) {
    trig_f32_in_place(xs, 0);
}

/// [`cos_f32`] of every element, in place (the same bits).
#[inline(always)]
pub fn cos_f32_in_place(xs: &mut [f32]) {
    trig_f32_in_place(xs, 1);
}

/// `sin(x + quarter·π/2)` for |x| ≤ 8192, branch-free.
#[inline(always)]
fn trig_f32_lane(x: f32, quarter: u32) -> f32 {
    use trig_f32_constants::{COS, FRAC_2_PI, PIO2_A, PIO2_B, PIO2_C, SHIFT, SIN};
    let t = x * FRAC_2_PI + SHIFT;
    let n = t - SHIFT;
    // SHIFT's mantissa is a multiple of 4, so t's low bits are n mod 4.
    let q = t.to_bits().wrapping_add(quarter);
    let r = x - n * PIO2_A - n * PIO2_B - n * PIO2_C;
    let z = r * r;
    let s = ((SIN[0] * z + SIN[1]) * z + SIN[2]) * z * r + r;
    let c = ((COS[0] * z + COS[1]) * z + COS[2]) * z * z - 0.5 * z + 1.0;
    let v = if q & 1 == 0 { s } else { c };
    if q & 2 == 0 { v } else { -v }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fused multiply-add instruction's result (None on a CPU without one).
    fn hardware_fma(x: f32, y: f32, z: f32) -> Option<f32> {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::*;
            #[target_feature(enable = "fma")]
            unsafe fn fused(x: f32, y: f32, z: f32) -> f32 {
                _mm_cvtss_f32(_mm_fmadd_ss(_mm_set_ss(x), _mm_set_ss(y), _mm_set_ss(z)))
            }
            if is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports FMA (checked just above).
                return Some(unsafe { fused(x, y, z) });
            }
        }
        let _ = (x, y, z);
        None
    }

    /// Random f32 of every exponent and sign, NaN excluded (a NaN's payload
    /// is not part of the fast precision's promise).
    fn random_f32(state: &mut u64) -> f32 {
        loop {
            *state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let v = f32::from_bits((*state >> 32) as u32);
            if !v.is_nan() {
                return v;
            }
        }
    }

    #[test]
    fn blocks_give_the_bits_of_one_value_at_a_time() {
        let specials = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            87.0,
            -87.0,
            88.5,
            -100.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN_POSITIVE,
            f32::NAN,
            -f32::NAN,
            1e-30,
            17.9,
        ];
        let mut state = 0xb10c_u64;
        for round in 0..50_000 {
            let xs: [f32; 16] = if round == 0 {
                specials
            } else {
                // Half every exponent, half the sigmoid's working range.
                std::array::from_fn(|i| {
                    let v = random_f32(&mut state);
                    if i % 2 == 0 { v } else { v % 20.0 }
                })
            };
            let (mut e, mut s) = (xs, xs);
            exp_f32_block(&mut e);
            bipolar_sigmoid_f32_block(&mut s);
            for (i, &x) in xs.iter().enumerate() {
                let (want_e, want_s) = (exp_f32(x), bipolar_sigmoid_f32(x));
                assert!(e[i].to_bits() == want_e.to_bits() || e[i].is_nan() && want_e.is_nan());
                assert!(s[i].to_bits() == want_s.to_bits() || s[i].is_nan() && want_s.is_nan());
            }
        }
    }

    #[test]
    fn fma_f32_rounds_subnormal_midpoints_once() {
        // x·y = 2^-150 − 2^-196, so x·y + z lies just below the midpoint
        // z + 2^-150 of two subnormal f32 and its f64 sum lands on that
        // midpoint: rounding the sum once more would break the tie to even.
        let x = f32::from_bits(0x1a00_0001); // 2^-75 (1 + 2^-23)
        let y = f32::from_bits(0x19ff_fffe); // 2^-75 (1 − 2^-23)
        for k in [1u32, 3, 1001, (1 << 22) + 1, (1 << 23) - 3] {
            for z in [f32::from_bits(k), -f32::from_bits(k)] {
                let (got, want) = (fma_f32(x, y, z), fma_f32(-x, -y, z));
                assert_eq!(got.to_bits(), want.to_bits());
                if let Some(hw) = hardware_fma(x, y, z) {
                    assert_eq!(got.to_bits(), hw.to_bits(), "z = {z:e}");
                }
            }
        }
    }

    #[test]
    fn fma_f32_gives_the_fused_instructions_bits() {
        let mut state = 0x5eed_u64;
        let mut checked = 0usize;
        let mut double_roundings = 0usize;
        let mut check = |x: f32, y: f32, z: f32| {
            let got = fma_f32(x, y, z);
            let Some(want) = hardware_fma(x, y, z) else {
                return;
            };
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "fma_f32({x:e}, {y:e}, {z:e}) = {got:e}, the instruction gives {want:e}"
            );
            checked += 1;
            let naive = (f64::from(x) * f64::from(y) + f64::from(z)) as f32;
            if naive.to_bits() != want.to_bits() && !want.is_nan() {
                double_roundings += 1;
            }
        };
        // Random bit patterns: every exponent, overflow, underflow, infinities.
        for _ in 0..1_000_000 {
            let (x, y, z) = (
                random_f32(&mut state),
                random_f32(&mut state),
                random_f32(&mut state),
            );
            check(x, y, z);
        }
        // Sums of the size the controller makes, with cancellation.
        for _ in 0..1_000_000 {
            let f = |s: &mut u64| (random_f32(s).to_bits() % 2_000_000) as f32 / 1e6 - 1.0;
            let (x, y) = (f(&mut state), f(&mut state));
            let z = -(x * y) + f(&mut state) * 1e-6;
            check(x, y, z);
        }
        // The double-rounding cases: x·y = 2^(e−24)·(1 − 2^−2k) or
        // (1 + 2^−k)², z of odd or even significand, so that the f64 sum
        // lands on an f32 midpoint and the tie must not break to even.
        for k in 12..=23 {
            let small = 2f32.powi(-k);
            for bits in (0x3f80_0000u32..0x3f80_0000 + 4096).chain(0x3fff_f000..0x4000_0000) {
                let z = f32::from_bits(bits);
                for e in [-30, -10, 0, 20, 60] {
                    let z = z * 2f32.powi(e);
                    let unit = 2f32.powi(e - 24);
                    for (a, b) in [(1.0 + small, 1.0 - small), (1.0 + small, 1.0 + small)] {
                        for sign in [1.0f32, -1.0] {
                            check(a * unit * sign, b, z);
                            check(a * unit * sign, b, -z);
                        }
                    }
                }
            }
        }
        if hardware_fma(1.0, 1.0, 1.0).is_some() {
            assert!(checked > 3_000_000, "{checked}");
            assert!(
                double_roundings > 1000,
                "the midpoint cases were not reached: {double_roundings}"
            );
        } else {
            eprintln!("note: no FMA instruction on this CPU; fma_f32 was not compared");
        }
    }

    /// `count` arguments evenly over `[lo, hi]`, plus every f32 in `[lo, hi]`
    /// at a stride of `stride` bit patterns (dense near 0, where f32s are).
    fn arguments(lo: f32, hi: f32, count: usize, stride: usize) -> Vec<f32> {
        let mut xs: Vec<f32> = (0..=count)
            .map(|i| lo + (hi - lo) * (i as f32 / count as f32))
            .collect();
        for sign in [0u32, 0x8000_0000] {
            let top = if sign == 0 { hi } else { -lo };
            xs.extend(
                (0..top.to_bits())
                    .step_by(stride)
                    .map(|b| f32::from_bits(b | sign)),
            );
        }
        xs
    }

    /// The bits of `exp_f32` recorded before it became a block of one value
    /// (FNV-1a over a sweep of the whole clamped range and the specials):
    /// the one definition still gives every bit it gave.
    #[test]
    fn exp_f32_gives_the_bits_it_always_gave() {
        let mut h = 0xcbf2_9ce4_8422_2325_u64;
        let specials = [0.0, -0.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, 1e-30];
        for v in arguments(-90.0, 90.0, 400_000, 20_000)
            .into_iter()
            .chain(specials)
        {
            for b in exp_f32(v).to_bits().to_le_bytes() {
                h = (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
            }
        }
        assert_eq!(
            h, 0xdae4_247f_e3af_243f,
            "exp_f32's bits changed: {h:#018x}"
        );
    }

    #[test]
    fn exp_f32_is_within_its_stated_error() {
        let mut worst = (0.0f64, 0.0f32);
        let xs = arguments(-87.0, 88.0, 2_000_000, 1_000);
        assert!(xs.len() > 4_000_000);
        for x in xs {
            let want = crate::math::exp(f64::from(x));
            let rel = ((f64::from(exp_f32(x)) - want) / want).abs();
            if rel > worst.0 {
                worst = (rel, x);
            }
        }
        assert!(
            worst.0 < 1.0e-7,
            "relative error {:e} at {}",
            worst.0,
            worst.1
        );
        // Clamped outside, saturating rather than overflowing.
        assert_eq!(exp_f32(-1000.0), exp_f32(-87.0));
        assert_eq!(exp_f32(1000.0), exp_f32(88.0));
        assert!(exp_f32(88.0).is_finite() && exp_f32(-87.0).is_normal());
        assert!(exp_f32(f32::NAN).is_nan());
        assert_eq!(exp_f32(0.0), 1.0);
    }

    #[test]
    fn bipolar_sigmoid_f32_is_within_its_stated_error() {
        let mut worst = (0.0f64, 0.0f32);
        for x in arguments(-20.0, 20.0, 2_000_000, 500) {
            let want = crate::activation::bipolar_sigmoid(f64::from(x));
            let err = (f64::from(bipolar_sigmoid_f32(x)) - want).abs();
            if err > worst.0 {
                worst = (err, x);
            }
        }
        assert!(
            worst.0 < 2.0e-7,
            "absolute error {:e} at {}",
            worst.0,
            worst.1
        );
        assert_eq!(bipolar_sigmoid_f32(0.0), 0.0);
        assert_eq!(bipolar_sigmoid_f32(1e30), 1.0);
        assert_eq!(bipolar_sigmoid_f32(-1e30), -1.0);
        assert_eq!(bipolar_sigmoid_f32(f32::INFINITY), 1.0);
    }

    #[test]
    fn sin_cos_f32_are_within_their_stated_error() {
        let mut worst = (0.0f64, 0.0f32);
        let xs = arguments(-8192.0, 8192.0, 4_000_000, 250);
        assert!(xs.len() > 8_000_000, "{}", xs.len());
        for &x in &xs {
            let x64 = f64::from(x);
            for (got, want) in [
                (sin_f32(x), crate::math::sin(x64)),
                (cos_f32(x), crate::math::cos(x64)),
            ] {
                let err = (f64::from(got) - want).abs();
                if err > worst.0 {
                    worst = (err, x);
                }
            }
        }
        assert!(
            worst.0 < 1.0e-7,
            "absolute error {:e} at {}",
            worst.0,
            worst.1
        );
        // Exact values and the f64 fallback beyond the lane range.
        assert_eq!(sin_f32(0.0), 0.0);
        assert_eq!(cos_f32(0.0), 1.0);
        assert!(sin_f32(f32::NAN).is_nan() && cos_f32(f32::INFINITY).is_nan());
        assert_eq!(sin_f32(1.0e6), crate::math::sin(1.0e6) as f32);
        // The slice versions give each element's bits, in and out of range.
        for ys in [&xs[..1000], &[0.5, -3.0, 9000.0, f32::NAN][..]] {
            let mut s = ys.to_vec();
            let mut c = ys.to_vec();
            sin_f32_in_place(&mut s);
            cos_f32_in_place(&mut c);
            for ((&x, s), c) in ys.iter().zip(s).zip(c) {
                assert_eq!(s.to_bits(), sin_f32(x).to_bits(), "sin {x}");
                assert_eq!(c.to_bits(), cos_f32(x).to_bits(), "cos {x}");
            }
        }
    }

    #[test]
    fn precision_names_round_trip() {
        for p in [Precision::Exact, Precision::Fast] {
            assert_eq!(Precision::from_name(p.name()), Some(p));
            assert_eq!(serde_json::to_string(&p).unwrap(), format!("\"{p}\""));
        }
        assert_eq!(Precision::from_name("single"), None);
        assert_eq!(Precision::default(), Precision::Exact);
    }
}

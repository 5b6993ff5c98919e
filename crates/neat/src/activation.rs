//! Node activation functions (the paper's Table I plus the plain sigmoid).

use serde::{Deserialize, Serialize};

use crate::math;
pub use crate::math::exp;

/// An activation function of a network node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activation {
    /// Bipolar sigmoid `2/(1+e^(−4.9x)) − 1`, range (−1, 1).
    BipolarSigmoid,
    /// Identity `x`.
    Linear,
    /// Gaussian `e^(−2.5x²)`.
    Gaussian,
    /// Absolute value `|x|`.
    Abs,
    /// Sine `sin x`.
    Sine,
    /// Cosine `cos x`.
    Cosine,
    /// Plain (Stanley's steepened) sigmoid `1/(1+e^(−4.9x))`, range (0, 1).
    Sigmoid,
}

impl Activation {
    /// The six CPPN hidden-node functions of the paper's Table I.
    pub const CPPN_SET: [Activation; 6] = [
        Activation::BipolarSigmoid,
        Activation::Linear,
        Activation::Gaussian,
        Activation::Abs,
        Activation::Sine,
        Activation::Cosine,
    ];

    /// Applies the function to `x`.
    #[inline(always)]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::BipolarSigmoid => bipolar_sigmoid(x),
            Activation::Linear => x,
            Activation::Gaussian => exp(-2.5 * x * x),
            Activation::Abs => x.abs(),
            Activation::Sine => math::sin(x),
            Activation::Cosine => math::cos(x),
            Activation::Sigmoid => 1.0 / (1.0 + exp(-4.9 * x)),
        }
    }
}

/// The bipolar sigmoid `2/(1+e^(−4.9x)) − 1` used by CPPN outputs and controllers.
#[inline(always)]
pub fn bipolar_sigmoid(x: f64) -> f64 {
    // Not `bipolar_sigmoid_block` of one value, as `exp` is `exp_block` of
    // one: that measured 25–35 % slower in the `cppn_activate` bench.
    2.0 / (1.0 + exp(-4.9 * x)) - 1.0
}

/// [`bipolar_sigmoid`] of each of `N` values in place, the same bits on
/// each (statement by statement across the block, as [`crate::math::exp_block`]).
#[inline(always)]
pub fn bipolar_sigmoid_block<const N: usize>(xs: &mut [f64; N]) {
    let mut e: [f64; N] = std::array::from_fn(|i| -4.9 * xs[i]);
    crate::math::exp_block(&mut e);
    for (x, e) in xs.iter_mut().zip(&e) {
        *x = 2.0 / (1.0 + e) - 1.0;
    }
}

/// Values per pass of [`apply_all`]: two SSE2 vectors, one AVX2 vector.
const PASS: usize = 4;

/// Applies `acts[k]` to `xs[k]` in place for every `k`: the same bits as
/// [`Activation::apply`] on each, with the exponentials of a pass computed
/// together as vector lanes.
///
/// One `exp` is a chain of about 30 dependent operations; computed one node
/// at a time (a match per node) they cannot share vector instructions, here
/// each pass selects every node's argument, takes one lane-wise `exp` of all
/// of them and selects each node's result, without a branch (a pass of four
/// sigmoids of one kind needs no selects and divides as one vector). Sine
/// and cosine nodes, which need the portable libm, are finished one by one
/// afterwards.
/// With AVX2 (at or below [`simd::level`](crate::simd::level)) a pass is one
/// vector; no fused multiply-add, so every level gives the same bits.
pub fn apply_all(acts: &[Activation], xs: &mut [f64]) {
    // Fewer than a pass (a network's one or two output nodes): one by one,
    // as the body would, without choosing an instruction level.
    if xs.len() < PASS && acts.len() == xs.len() {
        for (&a, x) in acts.iter().zip(xs) {
            *x = a.apply(*x);
        }
        return;
    }
    apply_all_at(crate::simd::level(), acts, xs);
}

/// [`apply_all`] at instruction level `level` (tests hold every level to the same bits).
fn apply_all_at(level: crate::simd::SimdLevel, acts: &[Activation], xs: &mut [f64]) {
    assert_eq!(acts.len(), xs.len(), "one activation per value");
    #[cfg(target_arch = "x86_64")]
    if level >= crate::simd::SimdLevel::Avx2
        && let Some(t) = crate::simd::x86::Avx2::new()
    {
        // SAFETY: the token `t` exists only when this CPU supports AVX2.
        return unsafe { apply_all_avx2(t, acts, xs) };
    }
    apply_all_body(acts, xs, |e| *e = e.map(exp));
}

/// [`apply_all_body`] compiled with AVX2 (and without FMA).
///
/// # Safety
/// The CPU must support AVX2 (the token proves it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn apply_all_avx2(_: crate::simd::x86::Avx2, acts: &[Activation], xs: &mut [f64]) {
    apply_all_body(acts, xs, |e| {
        // SAFETY: this function runs only where AVX2 is supported.
        *e = unsafe { exp_avx2(*e) }
    })
}

/// [`exp`] of four values as one AVX2 vector: the same operations in the
/// same order (no fused multiply-add), so the same bits. Written out
/// because the compiler keeps the scalar chain otherwise: the portable
/// [`crate::math::exp_block`] of a pass, compiled with AVX2, measured
/// 10–20 % slower on the recurrent-network, sine and prey benches.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn exp_avx2(x: [f64; PASS]) -> [f64; PASS] {
    use crate::math::exp_constants::{LN2_HI, LN2_LO, LOG2E, SHIFT, TAYLOR, TAYLOR_FIRST};
    use std::arch::x86_64::*;
    // SAFETY: `x` holds the four values the unaligned load reads.
    let x = unsafe { _mm256_loadu_pd(x.as_ptr()) };
    // `clamp` for numbers, NaN kept (as `exp` does).
    let clamped = _mm256_min_pd(
        _mm256_max_pd(x, _mm256_set1_pd(-708.0)),
        _mm256_set1_pd(709.0),
    );
    let x = _mm256_blendv_pd(clamped, x, _mm256_cmp_pd::<_CMP_UNORD_Q>(x, x));
    let shift = _mm256_set1_pd(SHIFT);
    let kf = _mm256_add_pd(_mm256_mul_pd(x, _mm256_set1_pd(LOG2E)), shift);
    let k = _mm256_sub_pd(kf, shift);
    let r = _mm256_sub_pd(x, _mm256_mul_pd(k, _mm256_set1_pd(LN2_HI)));
    let r = _mm256_sub_pd(r, _mm256_mul_pd(k, _mm256_set1_pd(LN2_LO)));
    let mut p = _mm256_set1_pd(TAYLOR_FIRST);
    for c in TAYLOR {
        p = _mm256_add_pd(_mm256_mul_pd(p, r), _mm256_set1_pd(c));
    }
    let bits = _mm256_add_epi64(_mm256_castpd_si256(kf), _mm256_set1_epi64x(1023));
    let scale = _mm256_castsi256_pd(_mm256_slli_epi64::<52>(bits));
    let mut out = [0.0; PASS];
    // SAFETY: `out` has room for the four values the unaligned store writes.
    unsafe { _mm256_storeu_pd(out.as_mut_ptr(), _mm256_mul_pd(p, scale)) };
    out
}

/// The body of [`apply_all`], compiled once per instruction level.
#[inline(always)]
fn apply_all_body(acts: &[Activation], xs: &mut [f64], exp_pass: impl Fn(&mut [f64; PASS])) {
    let whole = xs.len() / PASS * PASS;
    let (acts, tail_acts) = acts.split_at(whole);
    let (xs, tail) = xs.split_at_mut(whole);
    // A partial pass would cost a whole one: the rest go one by one.
    for (&a, x) in tail_acts.iter().zip(tail) {
        *x = a.apply(*x);
    }
    let mut trig = false;
    for (a, x) in acts.chunks_exact(PASS).zip(xs.chunks_exact_mut(PASS)) {
        let mut e = [0.0; PASS];
        // A pass of one sigmoid kind (most of a plain NEAT network): the
        // same operations without the per-node selects, so the division is
        // one vector instruction rather than one per node.
        let bipolar = a == [Activation::BipolarSigmoid; PASS];
        if bipolar || a == [Activation::Sigmoid; PASS] {
            for (e, &x) in e.iter_mut().zip(x.iter()) {
                *e = -4.9 * x;
            }
            exp_pass(&mut e);
            let numerator = if bipolar { 2.0 } else { 1.0 };
            let minus = if bipolar { 1.0 } else { 0.0 };
            for (x, &e) in x.iter_mut().zip(&e) {
                // q − 0 is q, bit for bit (−0 stays −0: q is never −0).
                *x = numerator / (1.0 + e) - minus;
            }
            continue;
        }
        for ((e, &a), &x) in e.iter_mut().zip(a).zip(x.iter()) {
            trig |= matches!(a, Activation::Sine | Activation::Cosine);
            // The arguments `apply` gives `exp`, in the same operation order.
            let sigmoid = -4.9 * x;
            let gaussian = -2.5 * x * x;
            *e = match a {
                Activation::BipolarSigmoid | Activation::Sigmoid => sigmoid,
                Activation::Gaussian => gaussian,
                _ => 0.0,
            };
        }
        // No branch: one vectorised `exp` for the pass.
        exp_pass(&mut e);
        for ((x, &a), &e) in x.iter_mut().zip(a).zip(&e) {
            let numerator = if a == Activation::BipolarSigmoid {
                2.0
            } else {
                1.0
            };
            let q = numerator / (1.0 + e);
            *x = match a {
                Activation::BipolarSigmoid => q - 1.0,
                Activation::Sigmoid => q,
                Activation::Gaussian => e,
                Activation::Abs => x.abs(),
                _ => *x,
            };
        }
    }
    if trig {
        for (&a, x) in acts.iter().zip(xs.iter_mut()) {
            match a {
                Activation::Sine => *x = math::sin(*x),
                Activation::Cosine => *x = math::cos(*x),
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_one_values() {
        assert_eq!(Activation::BipolarSigmoid.apply(0.0), 0.0);
        assert!((Activation::BipolarSigmoid.apply(10.0) - 1.0).abs() < 1e-9);
        assert_eq!(Activation::Gaussian.apply(0.0), 1.0);
        assert!((Activation::Gaussian.apply(1.0) - (-2.5f64).exp()).abs() < 1e-15);
        assert_eq!(Activation::Abs.apply(-2.0), 2.0);
        assert_eq!(Activation::Sigmoid.apply(0.0), 0.5);
        assert_eq!(Activation::Linear.apply(-3.5), -3.5);
    }

    #[test]
    fn apply_all_gives_the_bits_of_apply() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let all: Vec<Activation> = (Activation::CPPN_SET.into_iter())
            .chain([Activation::Sigmoid])
            .collect();
        let specials = [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            1e300,
            -800.0,
        ];
        for n in 0..120 {
            // Mixed kinds, then passes of one kind only (the sigmoids' own
            // path), then one kind with an odd one out.
            let one = all[n % all.len()];
            let acts: Vec<Activation> = (0..n % 40)
                .map(|k| match n / 40 {
                    0 => all[rng.random_range(0..all.len())],
                    1 => one,
                    _ if k == 5 => Activation::Gaussian,
                    _ => one,
                })
                .collect();
            let n = acts.len();
            let xs: Vec<f64> = (0..n)
                .map(|k| match rng.random_range(0..8) {
                    0 => specials[k % specials.len()],
                    _ => rng.random::<f64>() * 20.0 - 10.0,
                })
                .collect();
            for level in crate::simd::available() {
                let mut got = xs.clone();
                apply_all_at(level, &acts, &mut got);
                for ((&a, &x), &y) in acts.iter().zip(&xs).zip(&got) {
                    assert_eq!(y.to_bits(), a.apply(x).to_bits(), "{a:?}({x}) at {level:?}");
                }
            }
        }
    }
}

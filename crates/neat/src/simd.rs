//! Which vector instructions the library's hot loops may use (chosen at run time).
//!
//! The batched controller step ([`SubstrateController::activate_batch`]) and
//! the batched CPPN queries of decoding have one safe, generic body each,
//! compiled three times: for the baseline x86_64 (SSE2), with AVX2 and with
//! AVX-512F enabled. All three perform the same IEEE operations in the same
//! order per value (vectorised only across independent neurons, robots or
//! queries; no separate multiply and add is ever fused, and the one fused
//! operation, the fast precision's neuron-sum multiply-add ([`fma_f32`] in
//! software), is fused at every level), so they give the same bits; the
//! level only changes speed. The active level starts as the best the CPU
//! supports and can be lowered (e.g. to test that the bits really agree).
//! The levels and the CPU detection are vivae-simd's, shared with vivae-sim.
//!
//! [`SubstrateController::activate_batch`]: crate::hyperneat::SubstrateController::activate_batch

use vivae_simd::LevelSetting;

use crate::precision::fma_f32;
pub use vivae_simd::{SimdLevel, available, detected};

/// This library's level (vivae-sim keeps its own).
static LEVEL: LevelSetting = LevelSetting::new();

/// The level the hot loops use now (initially [`detected`]).
#[inline]
pub fn level() -> SimdLevel {
    LEVEL.get()
}

/// Makes `wanted` the active level for the whole process, clamped to what
/// the CPU supports ([`detected`]); returns the level now active.
pub fn set_level(wanted: SimdLevel) -> SimdLevel {
    LEVEL.set(wanted)
}

/// Vector operations of one instruction level on elements `E` (f64 for the
/// exact precision, f32 for the fast one), as used by the hot loops.
///
/// Implemented by zero-sized tokens: a token of a level above the baseline
/// can only be made on a CPU that supports it, which is what makes its
/// (safe) methods sound. `mul` and `add` are separately rounded; the one
/// fused operation, [`Simd::accumulate`] in f32, is the IEEE 754 fused
/// multiply-add at every level (the instruction, or `fma_f32` in software),
/// so every level computes the same bits.
pub(crate) trait Simd<E = f64>: Copy {
    /// A vector of `LANES` elements.
    type V: Copy;
    /// Elements per vector.
    const LANES: usize;
    /// Robots per tile of the batched controller step (sums kept in registers).
    const MAX_TILE: usize;
    /// Vectors of half this level's width where one costs half a whole one
    /// (AVX2's under AVX-512, whose 512-bit operations take both 256-bit
    /// pipes on Zen 4), else this level itself: a column's last vector, when
    /// at most half of it is neurons, is summed at this width.
    type Half: Simd<E>;
    /// The token of [`Simd::Half`].
    fn half(self) -> Self::Half;
    /// All lanes `x`.
    fn splat(self, x: E) -> Self::V;
    /// The first `LANES` values of `s` (panics when `s` is shorter).
    fn load(self, s: &[E]) -> Self::V;
    /// Writes `v` to the first `LANES` values of `s` (panics when shorter).
    fn store(self, v: Self::V, s: &mut [E]);
    /// Lane-wise `a + b`.
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    /// Lane-wise `a · b`.
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    /// Lane-wise `acc + w · v` by the element type's accumulation rule:
    /// separately rounded in f64 (the exact precision's bits), fused — one
    /// rounding, IEEE 754 fusedMultiplyAdd — in f32 (the fast precision).
    #[inline(always)]
    fn accumulate(self, acc: Self::V, w: Self::V, v: Self::V) -> Self::V {
        self.add(acc, self.mul(w, v))
    }
    /// [`Simd::accumulate`] with `v` = all lanes `*x`.
    #[inline(always)]
    fn accumulate_from(self, acc: Self::V, w: Self::V, x: &E) -> Self::V
    where
        E: Copy,
    {
        self.accumulate(acc, w, self.splat(*x))
    }
}

/// The baseline level: SSE2 on x86_64 (part of the architecture), plain
/// pairs of f64 elsewhere.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Baseline;

#[cfg(target_arch = "x86_64")]
impl Simd for Baseline {
    type V = std::arch::x86_64::__m128d;
    const LANES: usize = 2;
    const MAX_TILE: usize = 6;
    type Half = Baseline;
    #[inline(always)]
    fn half(self) -> Baseline {
        self
    }
    #[inline(always)]
    fn splat(self, x: f64) -> Self::V {
        // SAFETY: SSE2 is part of the x86_64 baseline.
        unsafe { std::arch::x86_64::_mm_set1_pd(x) }
    }
    #[inline(always)]
    fn load(self, s: &[f64]) -> Self::V {
        let s = &s[..2];
        // SAFETY: `s` holds 2 f64 (checked above); the load is unaligned.
        unsafe { std::arch::x86_64::_mm_loadu_pd(s.as_ptr()) }
    }
    #[inline(always)]
    fn store(self, v: Self::V, s: &mut [f64]) {
        let s = &mut s[..2];
        // SAFETY: `s` holds 2 f64 (checked above); the store is unaligned.
        unsafe { std::arch::x86_64::_mm_storeu_pd(s.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        // SAFETY: SSE2 is part of the x86_64 baseline.
        unsafe { std::arch::x86_64::_mm_add_pd(a, b) }
    }
    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        // SAFETY: SSE2 is part of the x86_64 baseline.
        unsafe { std::arch::x86_64::_mm_mul_pd(a, b) }
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl Simd for Baseline {
    type V = [f64; 2];
    const LANES: usize = 2;
    const MAX_TILE: usize = 6;
    type Half = Baseline;
    #[inline(always)]
    fn half(self) -> Baseline {
        self
    }
    #[inline(always)]
    fn splat(self, x: f64) -> Self::V {
        [x; 2]
    }
    #[inline(always)]
    fn load(self, s: &[f64]) -> Self::V {
        [s[0], s[1]]
    }
    #[inline(always)]
    fn store(self, v: Self::V, s: &mut [f64]) {
        s[..2].copy_from_slice(&v);
    }
    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] + b[0], a[1] + b[1]]
    }
    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] * b[0], a[1] * b[1]]
    }
}

/// Defines `Simd<f32>` for an x86 token from the intrinsics of its vector
/// type (the f32 lanes of the fast precision), one definition per level.
#[cfg(target_arch = "x86_64")]
macro_rules! x86_f32 {
    ($token:ty, $v:ty, $lanes:literal, $tile:literal, $half:ty, $to_half:path, $feature:literal,
     $set1:ident, $loadu:ident, $storeu:ident, $add:ident, $mul:ident, $fused:path) => {
        // SAFETY (every `unsafe` block of this impl): the token exists only
        // when the CPU supports `$feature` (the baseline's SSE2 always);
        // loads and stores go through slices checked to hold `$lanes` f32.
        impl Simd<f32> for $token {
            type V = $v;
            const LANES: usize = $lanes;
            const MAX_TILE: usize = $tile;
            type Half = $half;
            #[inline(always)]
            fn half(self) -> $half {
                $to_half(self)
            }
            #[inline(always)]
            fn splat(self, x: f32) -> $v {
                // SAFETY: see the impl: the level's instructions are supported.
                unsafe { std::arch::x86_64::$set1(x) }
            }
            #[inline(always)]
            fn load(self, s: &[f32]) -> $v {
                let s = &s[..$lanes];
                // SAFETY: see the impl; `s` holds `$lanes` f32, the load is unaligned.
                unsafe { std::arch::x86_64::$loadu(s.as_ptr()) }
            }
            #[inline(always)]
            fn store(self, v: $v, s: &mut [f32]) {
                let s = &mut s[..$lanes];
                // SAFETY: see the impl; `s` holds `$lanes` f32, the store is unaligned.
                unsafe { std::arch::x86_64::$storeu(s.as_mut_ptr(), v) }
            }
            #[inline(always)]
            fn add(self, a: $v, b: $v) -> $v {
                // SAFETY: see the impl: the level's instructions are supported.
                unsafe { std::arch::x86_64::$add(a, b) }
            }
            #[inline(always)]
            fn mul(self, a: $v, b: $v) -> $v {
                // SAFETY: see the impl: the level's instructions are supported.
                unsafe { std::arch::x86_64::$mul(a, b) }
            }
            #[inline(always)]
            fn accumulate(self, acc: $v, w: $v, v: $v) -> $v {
                // SAFETY: see the impl: the level's instructions are supported.
                unsafe { $fused(w, v, acc) }
            }
        }
    };
}

/// `a · b + c` in four f32 lanes with one rounding each ([`fma_f32`]): SSE2
/// has no fused multiply-add.
///
/// # Safety
/// None beyond SSE2, part of x86_64 (the signature matches the intrinsics').
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn fused_sse2(
    a: std::arch::x86_64::__m128,
    b: std::arch::x86_64::__m128,
    c: std::arch::x86_64::__m128,
) -> std::arch::x86_64::__m128 {
    use std::arch::x86_64::*;
    let (mut x, mut y, mut z) = ([0.0f32; 4], [0.0f32; 4], [0.0f32; 4]);
    // SAFETY: each array holds 4 f32; SSE2 is part of x86_64.
    unsafe {
        _mm_storeu_ps(x.as_mut_ptr(), a);
        _mm_storeu_ps(y.as_mut_ptr(), b);
        _mm_storeu_ps(z.as_mut_ptr(), c);
    }
    let mut r = [0.0f32; 4];
    for i in 0..4 {
        r[i] = fma_f32(x[i], y[i], z[i]);
    }
    // SAFETY: as above.
    unsafe { _mm_loadu_ps(r.as_ptr()) }
}

#[cfg(target_arch = "x86_64")]
x86_f32!(
    Baseline,
    std::arch::x86_64::__m128,
    4,
    6,
    Baseline,
    std::convert::identity,
    "sse2",
    _mm_set1_ps,
    _mm_loadu_ps,
    _mm_storeu_ps,
    _mm_add_ps,
    _mm_mul_ps,
    fused_sse2
);

#[cfg(not(target_arch = "x86_64"))]
impl Simd<f32> for Baseline {
    type V = [f32; 4];
    const LANES: usize = 4;
    const MAX_TILE: usize = 6;
    type Half = Baseline;
    #[inline(always)]
    fn half(self) -> Baseline {
        self
    }
    #[inline(always)]
    fn splat(self, x: f32) -> Self::V {
        [x; 4]
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> Self::V {
        [s[0], s[1], s[2], s[3]]
    }
    #[inline(always)]
    fn store(self, v: Self::V, s: &mut [f32]) {
        s[..4].copy_from_slice(&v);
    }
    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        std::array::from_fn(|i| a[i] + b[i])
    }
    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        std::array::from_fn(|i| a[i] * b[i])
    }
    #[inline(always)]
    fn accumulate(self, acc: Self::V, w: Self::V, v: Self::V) -> Self::V {
        std::array::from_fn(|i| fma_f32(w[i], v[i], acc[i]))
    }
}

/// The AVX2 and AVX-512F tokens.
#[cfg(target_arch = "x86_64")]
pub(crate) mod x86 {
    use std::arch::x86_64::*;

    use super::Simd;

    /// Proof that the CPU supports AVX2 (made only by [`Avx2::new`]).
    #[derive(Debug, Clone, Copy)]
    pub(crate) struct Avx2(());

    impl Avx2 {
        /// The token, if this CPU supports AVX2 and FMA (every AVX2 CPU of
        /// Intel and AMD has both; the fast precision's sums need the FMA).
        #[inline]
        pub(crate) fn new() -> Option<Avx2> {
            (is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"))
                .then_some(Avx2(()))
        }
    }

    // SAFETY (every `unsafe` block of this impl): an `Avx2` token exists only
    // when `is_x86_feature_detected!("avx2")` (and "fma") held, so the AVX intrinsics are
    // supported; loads and stores go through slices checked to hold 4 f64.
    impl Simd for Avx2 {
        type V = __m256d;
        const LANES: usize = 4;
        const MAX_TILE: usize = 6;
        type Half = Avx2;
        #[inline(always)]
        fn half(self) -> Avx2 {
            self
        }
        #[inline(always)]
        fn splat(self, x: f64) -> __m256d {
            // SAFETY: see the impl: AVX is supported.
            unsafe { _mm256_set1_pd(x) }
        }
        #[inline(always)]
        fn load(self, s: &[f64]) -> __m256d {
            let s = &s[..4];
            // SAFETY: see the impl: AVX is supported, `s` holds 4 f64.
            unsafe { _mm256_loadu_pd(s.as_ptr()) }
        }
        #[inline(always)]
        fn store(self, v: __m256d, s: &mut [f64]) {
            let s = &mut s[..4];
            // SAFETY: see the impl: AVX is supported, `s` holds 4 f64.
            unsafe { _mm256_storeu_pd(s.as_mut_ptr(), v) }
        }
        #[inline(always)]
        fn add(self, a: __m256d, b: __m256d) -> __m256d {
            // SAFETY: see the impl: AVX is supported.
            unsafe { _mm256_add_pd(a, b) }
        }
        #[inline(always)]
        fn mul(self, a: __m256d, b: __m256d) -> __m256d {
            // SAFETY: see the impl: AVX is supported.
            unsafe { _mm256_mul_pd(a, b) }
        }
    }

    /// Proof that the CPU supports AVX-512F (made only by [`Avx512::new`]).
    #[derive(Debug, Clone, Copy)]
    pub(crate) struct Avx512(());

    impl Avx512 {
        /// The token, if this CPU supports AVX-512F (and AVX2 and FMA, as
        /// every AVX-512 CPU does: its half-width vectors are AVX2's).
        #[inline]
        pub(crate) fn new() -> Option<Avx512> {
            (is_x86_feature_detected!("avx512f")
                && is_x86_feature_detected!("avx2")
                && is_x86_feature_detected!("fma"))
            .then_some(Avx512(()))
        }

        /// The AVX2 token, which an AVX-512 one implies (see [`Avx512::new`]).
        #[inline(always)]
        pub(crate) fn avx2(self) -> Avx2 {
            Avx2(())
        }
    }

    // SAFETY (every `unsafe` block of this impl): an `Avx512` token exists
    // only when `is_x86_feature_detected!("avx512f")` held, so the AVX-512F
    // intrinsics are supported; loads and stores go through slices checked to
    // hold 8 f64.
    impl Simd for Avx512 {
        type V = __m512d;
        const LANES: usize = 8;
        const MAX_TILE: usize = 8;
        type Half = Avx2;
        #[inline(always)]
        fn half(self) -> Avx2 {
            self.avx2()
        }
        #[inline(always)]
        fn splat(self, x: f64) -> __m512d {
            // SAFETY: see the impl: AVX-512F is supported.
            unsafe { _mm512_set1_pd(x) }
        }
        #[inline(always)]
        fn load(self, s: &[f64]) -> __m512d {
            let s = &s[..8];
            // SAFETY: see the impl: AVX-512F is supported, `s` holds 8 f64.
            unsafe { _mm512_loadu_pd(s.as_ptr()) }
        }
        #[inline(always)]
        fn store(self, v: __m512d, s: &mut [f64]) {
            let s = &mut s[..8];
            // SAFETY: see the impl: AVX-512F is supported, `s` holds 8 f64.
            unsafe { _mm512_storeu_pd(s.as_mut_ptr(), v) }
        }
        #[inline(always)]
        fn add(self, a: __m512d, b: __m512d) -> __m512d {
            // SAFETY: see the impl: AVX-512F is supported.
            unsafe { _mm512_add_pd(a, b) }
        }
        #[inline(always)]
        fn mul(self, a: __m512d, b: __m512d) -> __m512d {
            // SAFETY: see the impl: AVX-512F is supported.
            unsafe { _mm512_mul_pd(a, b) }
        }
        /// The multiply reads `x` itself, broadcast, whatever the compiler
        /// would do with a shared broadcast register (the same IEEE product).
        #[inline(always)]
        fn accumulate_from(self, acc: __m512d, w: __m512d, x: &f64) -> __m512d {
            // SAFETY: see the impl: AVX-512F is supported; `x` is a live f64.
            unsafe { _mm512_add_pd(acc, mul_broadcast(w, x)) }
        }
    }

    /// `w · (all lanes *x)` with the broadcast folded into the multiply
    /// (`vmulpd zmm, zmm, m64{1to8}`). Written in assembly because LLVM
    /// keeps one broadcast register for a value used by several multiplies.
    #[target_feature(enable = "avx512f")]
    #[inline]
    unsafe fn mul_broadcast(w: __m512d, x: &f64) -> __m512d {
        let t: __m512d;
        // SAFETY: AVX-512F is enabled here; `x` is a live f64.
        unsafe {
            std::arch::asm!(
                "vmulpd {t}, {w}, qword ptr [{p}]{{1to8}}",
                t = out(zmm_reg) t,
                w = in(zmm_reg) w,
                p = in(reg) x as *const f64,
                options(pure, readonly, nostack, preserves_flags)
            );
        }
        t
    }

    x86_f32!(
        Avx2,
        __m256,
        8,
        6,
        Avx2,
        std::convert::identity,
        "avx2",
        _mm256_set1_ps,
        _mm256_loadu_ps,
        _mm256_storeu_ps,
        _mm256_add_ps,
        _mm256_mul_ps,
        _mm256_fmadd_ps
    );
    x86_f32!(
        Avx512,
        __m512,
        16,
        8,
        Avx2,
        Avx512::avx2,
        "avx512f",
        _mm512_set1_ps,
        _mm512_loadu_ps,
        _mm512_storeu_ps,
        _mm512_add_ps,
        _mm512_mul_ps,
        _mm512_fmadd_ps
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_level_clamps_to_the_cpu_and_round_trips() {
        let before = level();
        assert!(before <= detected());
        assert_eq!(set_level(SimdLevel::Scalar), SimdLevel::Scalar);
        assert_eq!(level(), SimdLevel::Scalar);
        assert_eq!(set_level(SimdLevel::Avx512), detected());
        assert_eq!(level(), detected());
        assert_eq!(available().first(), Some(&SimdLevel::Scalar));
        assert_eq!(available().last(), Some(&detected()));
        set_level(before);
    }
}

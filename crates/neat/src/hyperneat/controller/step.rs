//! One synchronous update of the controller for a batch of robots: neuron
//! sums in the update equation's order, vectorised across neurons and tiled
//! across robots, compiled once per instruction level (same bits at each)
//! and once per element type (f64 for the exact precision, f32 for the fast one).

use crate::activation::{bipolar_sigmoid, bipolar_sigmoid_block};
use crate::precision::{bipolar_sigmoid_f32, bipolar_sigmoid_f32_block};
use crate::simd::{Baseline, Simd, SimdLevel};

/// An element type of the controller step: its column padding and panel
/// width, its squashing function, and the step at every level.
pub(super) trait Element: Copy + Default + 'static {
    /// Neuron columns are padded to a multiple of this many lanes (one
    /// AVX-512 vector), so every vector loop runs on whole vectors.
    const PAD: usize;
    /// Neurons per weight panel (two AVX-512 vectors).
    const PANEL: usize;
    /// The bipolar sigmoid in this precision.
    fn squash(a: Self) -> Self;
    /// [`Element::squash`] of each of a block's values, the same bits.
    fn squash_block<const N: usize>(a: &mut [Self; N]);
    /// [`Kernel::step`] at `level` (see there).
    fn step_at(
        level: SimdLevel,
        k: &Kernel<Self>,
        robots: usize,
        x: &[Self],
        y: &mut [Self],
        acc: &mut [Self],
    );
}

/// Implements [`Element`] for `$e`: the best token the CPU has at or below
/// `level` runs [`step_body`] compiled for it.
macro_rules! element {
    ($e:ty, $pad:expr, $squash:path, $block:path) => {
        impl Element for $e {
            const PAD: usize = $pad;
            const PANEL: usize = 2 * $pad;
            #[inline(always)]
            fn squash(a: $e) -> $e {
                $squash(a)
            }
            #[inline(always)]
            fn squash_block<const N: usize>(a: &mut [$e; N]) {
                $block(a)
            }
            fn step_at(
                level: SimdLevel,
                k: &Kernel<$e>,
                robots: usize,
                x: &[$e],
                y: &mut [$e],
                acc: &mut [$e],
            ) {
                #[cfg(target_arch = "x86_64")]
                {
                    use crate::simd::x86::{Avx2, Avx512};
                    if level >= SimdLevel::Avx512
                        && let Some(t) = Avx512::new()
                    {
                        // SAFETY: the token `t` exists only when this CPU supports AVX-512F.
                        return unsafe { step_avx512(t, k, robots, x, y, acc) };
                    }
                    if level >= SimdLevel::Avx2
                        && let Some(t) = Avx2::new()
                    {
                        // SAFETY: the token `t` exists only when this CPU supports AVX2.
                        return unsafe { step_avx2(t, k, robots, x, y, acc) };
                    }
                }
                let _ = level;
                step_body(Baseline, k, robots, x, y, acc);
            }
        }
    };
}

element!(f64, super::PAD, bipolar_sigmoid, bipolar_sigmoid_block);
element!(
    f32,
    2 * super::PAD,
    bipolar_sigmoid_f32,
    bipolar_sigmoid_f32_block
);

/// Values squashed together: two AVX-512 vectors of f64, one of f32. (Blocks
/// of 32 or 48 measured slower on the default run: their constants and
/// chains no longer fit the 32 vector registers.)
const SQUASH_BLOCK: usize = 16;

/// The read-only parts of a controller one step needs.
pub(super) struct Kernel<'a, E> {
    /// Inputs per robot.
    pub(super) ni: usize,
    /// Neurons.
    pub(super) n: usize,
    /// Padded column length (a multiple of [`PAD`]).
    pub(super) stride: usize,
    /// Padded biases.
    pub(super) bias: &'a [E],
    /// Padded, panelled weights (see [`SubstrateController::at`]).
    pub(super) weights: &'a [E],
}

impl<E: Element> Kernel<'_, E> {
    /// Updates `state` (robots × stride) from `inputs` (robots × ni), using `acc` as scratch.
    pub(super) fn step(
        &self,
        level: SimdLevel,
        robots: usize,
        inputs: &[E],
        state: &mut [E],
        acc: &mut [E],
    ) {
        assert!(
            inputs.len() == robots * self.ni
                && state.len() == robots * self.stride
                && acc.len() == state.len()
                && self.bias.len() == self.stride
                && self.weights.len() == (self.ni + self.n) * self.stride
                && self.stride.is_multiple_of(E::PAD)
        );
        E::step_at(level, self, robots, inputs, state, acc);
    }
}

/// Defines `$name`: [`step_body`] compiled with the target feature
/// `$feature` for the token `$token` (the f64 sums separately rounded, the
/// f32 ones fused: the same bits as the baseline), one definition for every
/// level above the baseline.
macro_rules! step_at_level {
    ($name:ident, $feature:literal, $token:ident) => {
        #[doc = concat!("[`step_body`] compiled with ", $feature, ".")]
        ///
        /// # Safety
        #[doc = concat!("The CPU must support ", $feature, " (the token proves it).")]
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $feature)]
        unsafe fn $name<E: Element>(
            t: crate::simd::x86::$token,
            k: &Kernel<E>,
            robots: usize,
            x: &[E],
            y: &mut [E],
            acc: &mut [E],
        ) where
            crate::simd::x86::$token: Simd<E>,
        {
            step_body(t, k, robots, x, y, acc)
        }
    };
}

step_at_level!(step_avx512, "avx512f", Avx512);
step_at_level!(step_avx2, "avx2,fma", Avx2);

/// One step of all robots: neuron groups of two vectors (one for the last
/// vector of a column, summed at half width when at most half of it is
/// neurons), robots in tiles of up to `S::MAX_TILE`.
///
/// Every neuron's sum is `bias`, then `+= w·x` for each input in order, then
/// for each neuron in order — the update equation's order, whatever the
/// vector width or the tiling, so every level gives the same bits (each
/// `+= w·x` separately rounded in f64, one fused multiply-add in f32).
#[inline(always)]
fn step_body<E: Element, S: Simd<E>>(
    s: S,
    k: &Kernel<E>,
    robots: usize,
    x: &[E],
    y: &mut [E],
    acc: &mut [E],
) {
    // Lanes past `live` hold only padding neurons: they are not summed (their
    // state stays 0 and no neuron reads it), which spares a quarter of the
    // work for 9 neurons on 4-lane vectors.
    let live = k.n.next_multiple_of(S::LANES);
    // A last vector at most half of whose lanes are neurons is summed at
    // half width where that costs half (AVX-512 on Zen 4: 81 neurons are 5
    // vectors of 16 f32 and one of 8, the fast camera step 8 % less work).
    // Its lanes are independent sums, so the width changes no bit.
    let half = <S::Half as Simd<E>>::LANES;
    let halve_last = half < S::LANES && k.n + S::LANES - live <= half;
    let mut r0 = 0;
    while r0 < robots {
        let rt = (robots - r0).min(S::MAX_TILE);
        let m = k.ni + k.n;
        for p0 in (0..k.stride).step_by(E::PANEL) {
            let width = E::PANEL.min(k.stride - p0);
            let panel = Panel {
                p0,
                width,
                weights: &k.weights[p0 * m..][..m * width],
            };
            // p0 < n always (stride − n < PAD ≤ PANEL), so this is at least one vector.
            let needed = width.min(live - p0);
            let mut sub = 0;
            while sub < needed {
                let left = needed - sub;
                if halve_last && p0 + needed == live && left <= 2 * S::LANES {
                    // The column's last group: its last vector at half width.
                    if left == 2 * S::LANES {
                        tile_rt::<E, S, 1, true>(s, k, &panel, rt, r0, sub, x, y, acc);
                    } else {
                        tile_rt::<E, S, 0, true>(s, k, &panel, rt, r0, sub, x, y, acc);
                    }
                    sub = needed;
                } else if left >= 2 * S::LANES {
                    tile_rt::<E, S, 2, false>(s, k, &panel, rt, r0, sub, x, y, acc);
                    sub += 2 * S::LANES;
                } else {
                    tile_rt::<E, S, 1, false>(s, k, &panel, rt, r0, sub, x, y, acc);
                    sub += S::LANES;
                }
            }
        }
        r0 += rt;
    }
    squash_packed::<E, S>(s, k, robots, y, acc);
}

/// `y = σ(acc)` for every robot's `n` neurons, the sums first packed robot
/// after robot so that no vector is spent on padding lanes: 9 neurons of 5
/// robots are 6 vectors of 8 lanes (3 of 16) instead of 10 (5). σ is
/// computed lane by lane, so packing does not change a bit; the padding
/// lanes of `y` are never written and stay 0.
#[inline(always)]
fn squash_packed<E: Element, S: Simd<E>>(
    s: S,
    k: &Kernel<E>,
    robots: usize,
    y: &mut [E],
    acc: &mut [E],
) {
    let n = k.n;
    let live = n.next_multiple_of(S::LANES);
    // Robot r's sums move down from r·stride to r·n, whole vectors in
    // ascending order: a store ends at r·n + live ≤ (r + 1)·stride, before the
    // sums of the next robot, and the lanes it writes past r·n + n are the
    // next robot's to overwrite (or the tail's, zeroed below).
    for r in 1..robots {
        for v in (0..live).step_by(S::LANES) {
            let x = s.load(&acc[r * k.stride + v..]);
            s.store(x, &mut acc[r * n + v..]);
        }
    }
    // Whole vectors only (robots · stride is a multiple of the vector width,
    // so they fit); the tail past the last sum is zeroed, not left stale.
    let packed = (robots * n).next_multiple_of(S::LANES);
    acc[robots * n..packed].fill(E::default());
    // Blocks whose statements run across the block: whole vectors at every
    // level, their chains overlapping. (A loop over `S::LANES`-chunks was left
    // to the SLP vectoriser, which gave up on the f32 sigmoid with AVX2 and ran
    // it one lane at a time: the fast precision slower than the exact one.)
    let mut blocks = acc[..packed].chunks_exact_mut(SQUASH_BLOCK);
    for b in &mut blocks {
        E::squash_block::<SQUASH_BLOCK>(b.try_into().expect("a whole block"));
    }
    for v in blocks.into_remainder() {
        *v = E::squash(*v);
    }
    for (r, y) in y.chunks_exact_mut(k.stride).enumerate() {
        crate::compile::copy_short(&mut y[..n], &acc[r * n..][..n]);
    }
}

/// Dispatches a tile of `rt` robots to the kernel compiled for that count.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tile_rt<E: Element, S: Simd<E>, const NB: usize, const HALF: bool>(
    s: S,
    k: &Kernel<E>,
    panel: &Panel<E>,
    rt: usize,
    r0: usize,
    sub: usize,
    x: &[E],
    y: &[E],
    acc: &mut [E],
) {
    macro_rules! tiles {
        ($($n:literal),*) => {
            match rt {
                $($n => tile::<E, S, $n, NB, HALF>(s, k, panel, r0, sub, x, y, acc),)*
                _ => unreachable!("robot tile of {rt}"),
            }
        };
    }
    tiles!(1, 2, 3, 4, 5, 6, 7, 8);
}

/// One panel of weights: neurons `p0..p0 + width`, every source.
struct Panel<'a, E> {
    /// First neuron.
    p0: usize,
    /// Neurons in the panel.
    width: usize,
    /// `(ni + n) × width` weights, source-major.
    weights: &'a [E],
}

/// Sums of the `NB` vectors of neurons from `panel.p0 + sub` (and, when
/// `HALF`, of one half-width vector after them) of robots `r0..r0 + RT`
/// into `acc`: the sums stay in registers while the panel's columns stream
/// by once.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tile<E: Element, S: Simd<E>, const RT: usize, const NB: usize, const HALF: bool>(
    s: S,
    k: &Kernel<E>,
    panel: &Panel<E>,
    r0: usize,
    sub: usize,
    x: &[E],
    y: &[E],
    acc: &mut [E],
) {
    let group = NB * S::LANES;
    let i0 = panel.p0 + sub;
    let h = s.half();
    let load = |column: &[E], from: usize| -> [S::V; NB] {
        let column = &column[from..from + group];
        std::array::from_fn(|b| s.load(&column[b * S::LANES..]))
    };
    // The half-width vector after the group (unused, and optimised out, unless HALF).
    let load_half = |column: &[E], from: usize| h.load(&column[from + group..]);
    let mut sum = [load(k.bias, i0); RT];
    let mut sum_half = [if HALF {
        load_half(k.bias, i0)
    } else {
        h.splat(E::default())
    }; RT];
    let xs: [&[E]; RT] = std::array::from_fn(|r| &x[(r0 + r) * k.ni..][..k.ni]);
    let ys: [&[E]; RT] = std::array::from_fn(|r| &y[(r0 + r) * k.stride..][..k.n]);
    let (w_in, w_rec) = panel.weights.split_at(k.ni * panel.width);
    // Each product takes its input from memory (`accumulate_from`): with
    // AVX-512 the broadcast folds into the multiply instead of being an
    // instruction of its own whose register the NB products share (exact
    // step 232 → 205 ns on Zen 4).
    // One pass over the columns of `$weights`, whose source `j` is
    // `$sources[r][j]` for robot `r`. A macro, not a loop over the two
    // passes: that loop cost the paper's fast evaluation 5 % on Zen 4.
    macro_rules! pass {
        ($weights:expr, $sources:expr) => {
            for (j, column) in $weights.chunks_exact(panel.width).enumerate() {
                let w = load(column, sub);
                let wh = if HALF {
                    load_half(column, sub)
                } else {
                    sum_half[0]
                };
                for r in 0..RT {
                    for b in 0..NB {
                        sum[r][b] = s.accumulate_from(sum[r][b], w[b], &$sources[r][j]);
                    }
                    if HALF {
                        sum_half[r] = h.accumulate_from(sum_half[r], wh, &$sources[r][j]);
                    }
                }
            }
        };
    }
    pass!(w_in, xs);
    pass!(w_rec, ys);
    for (r, sums) in sum.iter().enumerate() {
        let out = &mut acc[(r0 + r) * k.stride + i0..][..group];
        for (b, &v) in sums.iter().enumerate() {
            s.store(v, &mut out[b * S::LANES..]);
        }
        if HALF {
            h.store(sum_half[r], &mut acc[(r0 + r) * k.stride + i0 + group..]);
        }
    }
}

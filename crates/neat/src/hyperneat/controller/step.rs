//! One synchronous update of the controller for a batch of robots: neuron
//! sums in the update equation's order, vectorised across neurons and tiled
//! across robots, compiled once per instruction level (same bits at each).

use super::{PAD, PANEL};
use crate::activation::bipolar_sigmoid;
use crate::simd::{Simd, SimdLevel};

/// The read-only parts of a controller one step needs.
pub(super) struct Kernel<'a> {
    /// Inputs per robot.
    pub(super) ni: usize,
    /// Neurons.
    pub(super) n: usize,
    /// Padded column length (a multiple of [`PAD`]).
    pub(super) stride: usize,
    /// Padded biases.
    pub(super) bias: &'a [f64],
    /// Padded, panelled weights (see [`SubstrateController::at`]).
    pub(super) weights: &'a [f64],
}

impl Kernel<'_> {
    /// Updates `state` (robots × stride) from `inputs` (robots × ni), using `acc` as scratch.
    pub(super) fn step(
        &self,
        level: SimdLevel,
        robots: usize,
        inputs: &[f64],
        state: &mut [f64],
        acc: &mut [f64],
    ) {
        assert!(
            inputs.len() == robots * self.ni
                && state.len() == robots * self.stride
                && acc.len() == state.len()
                && self.bias.len() == self.stride
                && self.weights.len() == (self.ni + self.n) * self.stride
                && self.stride.is_multiple_of(PAD)
        );
        #[cfg(target_arch = "x86_64")]
        {
            use crate::simd::x86::{Avx2, Avx512};
            if level >= SimdLevel::Avx512
                && let Some(t) = Avx512::new()
            {
                // SAFETY: the token `t` exists only when this CPU supports AVX-512F.
                return unsafe { step_avx512(t, self, robots, inputs, state, acc) };
            }
            if level >= SimdLevel::Avx2
                && let Some(t) = Avx2::new()
            {
                // SAFETY: the token `t` exists only when this CPU supports AVX2.
                return unsafe { step_avx2(t, self, robots, inputs, state, acc) };
            }
        }
        step_body(crate::simd::Baseline, self, robots, inputs, state, acc);
    }
}

/// Defines `$name`: [`step_body`] compiled with the target feature
/// `$feature` for the token `$token` (no FMA: the same bits as the baseline),
/// one definition for every level above the baseline.
macro_rules! step_at_level {
    ($name:ident, $feature:literal, $token:ident) => {
        #[doc = concat!("[`step_body`] compiled with ", $feature, ".")]
        ///
        /// # Safety
        #[doc = concat!("The CPU must support ", $feature, " (the token proves it).")]
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $feature)]
        unsafe fn $name(
            t: crate::simd::x86::$token,
            k: &Kernel,
            robots: usize,
            x: &[f64],
            y: &mut [f64],
            acc: &mut [f64],
        ) {
            step_body(t, k, robots, x, y, acc)
        }
    };
}

step_at_level!(step_avx512, "avx512f", Avx512);
step_at_level!(step_avx2, "avx2", Avx2);

/// One step of all robots: neuron groups of two vectors (one for the last
/// vector of a column), robots in tiles of up to `S::MAX_TILE`.
///
/// Every neuron's sum is `bias`, then `+= w·x` for each input in order, then
/// for each neuron in order — the update equation's order, whatever the
/// vector width or the tiling, so every level gives the same bits.
#[inline(always)]
fn step_body<S: Simd>(s: S, k: &Kernel, robots: usize, x: &[f64], y: &mut [f64], acc: &mut [f64]) {
    // Lanes past `live` hold only padding neurons: they are neither summed nor
    // squashed (their state stays 0 and no neuron reads it), which spares a
    // quarter of the work for 9 neurons on 4-lane vectors.
    let live = k.n.next_multiple_of(S::LANES);
    let mut r0 = 0;
    while r0 < robots {
        let rt = (robots - r0).min(S::MAX_TILE);
        let m = k.ni + k.n;
        for p0 in (0..k.stride).step_by(PANEL) {
            let width = PANEL.min(k.stride - p0);
            let panel = Panel {
                p0,
                width,
                weights: &k.weights[p0 * m..][..m * width],
            };
            // p0 < n always (stride − n < PAD ≤ PANEL), so this is at least one vector.
            let needed = width.min(live - p0);
            let mut sub = 0;
            while sub < needed {
                if needed - sub >= 2 * S::LANES {
                    tile_rt::<S, 2>(s, k, &panel, rt, r0, sub, x, y, acc);
                    sub += 2 * S::LANES;
                } else {
                    tile_rt::<S, 1>(s, k, &panel, rt, r0, sub, x, y, acc);
                    sub += S::LANES;
                }
            }
        }
        r0 += rt;
    }
    // σ over the live lanes of every robot (live padding lanes: σ(0) = 0).
    for (y, a) in y.chunks_exact_mut(k.stride).zip(acc.chunks_exact(k.stride)) {
        for (y, &a) in y[..live].iter_mut().zip(&a[..live]) {
            *y = bipolar_sigmoid(a);
        }
    }
}

/// Dispatches a tile of `rt` robots to the kernel compiled for that count.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tile_rt<S: Simd, const NB: usize>(
    s: S,
    k: &Kernel,
    panel: &Panel,
    rt: usize,
    r0: usize,
    sub: usize,
    x: &[f64],
    y: &[f64],
    acc: &mut [f64],
) {
    macro_rules! tiles {
        ($($n:literal),*) => {
            match rt {
                $($n => tile::<S, $n, NB>(s, k, panel, r0, sub, x, y, acc),)*
                _ => unreachable!("robot tile of {rt}"),
            }
        };
    }
    tiles!(1, 2, 3, 4, 5, 6, 7, 8);
}

/// One panel of weights: neurons `p0..p0 + width`, every source.
struct Panel<'a> {
    /// First neuron.
    p0: usize,
    /// Neurons in the panel.
    width: usize,
    /// `(ni + n) × width` weights, source-major.
    weights: &'a [f64],
}

/// Sums of the `NB` vectors of neurons from `panel.p0 + sub` of robots
/// `r0..r0 + RT` into `acc`: the `RT × NB` sums stay in registers while the
/// panel's columns stream by once.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tile<S: Simd, const RT: usize, const NB: usize>(
    s: S,
    k: &Kernel,
    panel: &Panel,
    r0: usize,
    sub: usize,
    x: &[f64],
    y: &[f64],
    acc: &mut [f64],
) {
    let group = NB * S::LANES;
    let i0 = panel.p0 + sub;
    let load = |column: &[f64], from: usize| -> [S::V; NB] {
        let column = &column[from..from + group];
        std::array::from_fn(|b| s.load(&column[b * S::LANES..]))
    };
    let mut sum = [load(k.bias, i0); RT];
    let xs: [&[f64]; RT] = std::array::from_fn(|r| &x[(r0 + r) * k.ni..][..k.ni]);
    let ys: [&[f64]; RT] = std::array::from_fn(|r| &y[(r0 + r) * k.stride..][..k.n]);
    let (w_in, w_rec) = panel.weights.split_at(k.ni * panel.width);
    for (j, column) in w_in.chunks_exact(panel.width).enumerate() {
        let w = load(column, sub);
        for r in 0..RT {
            let v = s.splat(xs[r][j]);
            for b in 0..NB {
                sum[r][b] = s.add(sum[r][b], s.mul(w[b], v));
            }
        }
    }
    for (j, column) in w_rec.chunks_exact(panel.width).enumerate() {
        let w = load(column, sub);
        for r in 0..RT {
            let v = s.splat(ys[r][j]);
            for b in 0..NB {
                sum[r][b] = s.add(sum[r][b], s.mul(w[b], v));
            }
        }
    }
    for (r, sums) in sum.iter().enumerate() {
        let out = &mut acc[(r0 + r) * k.stride + i0..][..group];
        for (b, &v) in sums.iter().enumerate() {
            s.store(v, &mut out[b * S::LANES..]);
        }
    }
}

//! `libm::sincos` of eight angles at once, bit for bit: the same operations
//! in the same order (libm 0.2's FreeBSD kernels) in lanes, so the compiler
//! can vectorise it. Lanes outside the two cheap ranges that headings in
//! (−π, π] almost always fall in are handed to `libm::sincos` itself.

use crate::simd::SimdLevel;

/// Angles per batch.
pub(crate) const LANES: usize = 8;

// libm's constants, by their bits (as its comments give them).
const S1: f64 = f64::from_bits(0xbfc55555_55555549); // -1.66666666666666324348e-01
const S2: f64 = f64::from_bits(0x3f811111_1110f8a6); // 8.33333333332248946124e-03
const S3: f64 = f64::from_bits(0xbf2a01a0_19c161d5); // -1.98412698298579493134e-04
const S4: f64 = f64::from_bits(0x3ec71de3_57b1fe7d); // 2.75573137070700676789e-06
const S5: f64 = f64::from_bits(0xbe5ae5e6_8a2b9ceb); // -2.50507602534068634195e-08
const S6: f64 = f64::from_bits(0x3de5d93a_5acfd57c); // 1.58969099521155010221e-10
const C1: f64 = f64::from_bits(0x3fa55555_5555554c); // 4.16666666666666019037e-02
const C2: f64 = f64::from_bits(0xbf56c16c_16c15177); // -1.38888888888741095749e-03
const C3: f64 = f64::from_bits(0x3efa01a0_19cb1590); // 2.48015872894767294178e-05
const C4: f64 = f64::from_bits(0xbe927e4f_809c52ad); // -2.75573143513906633035e-07
const C5: f64 = f64::from_bits(0x3e21ee9e_bdb4b1c4); // 2.08757232129817482790e-09
const C6: f64 = f64::from_bits(0xbda8fae9_be8838d4); // -1.13596475577881948265e-11
const PIO2_1: f64 = f64::from_bits(0x3ff921fb_54400000); // 1.57079632673412561417e+00
const PIO2_1T: f64 = f64::from_bits(0x3dd0b461_1a626331); // 6.07710050650619224932e-11

/// (sin, cos) of each lane of `x`, identical in bits to `libm::sincos`.
#[inline(always)]
pub(crate) fn sincos_lanes(x: &[f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
    let mut s = [0.0; LANES];
    let mut c = [0.0; LANES];
    let mut slow = [false; LANES];
    for k in 0..LANES {
        let bits = x[k].to_bits();
        let ix = (bits >> 32) as u32 & 0x7fff_ffff;
        let neg = bits >> 63 != 0;
        // sincos: |x| ~< π/4 (but not tiny) goes straight to the kernels (iy = 0).
        let direct = (0x3e46_a09e..=0x3fe9_21fb).contains(&ix);
        // rem_pio2: |x| ~<= 3π/4 is n = ±1, ~<= 5π/4 is n = ±2, except near
        // multiples of π/2 (its "medium" case), which are left to libm.
        let one = ix > 0x3fe9_21fb && ix <= 0x4002_d97c && ix & 0xfffff != 0x921fb;
        let two = ix > 0x4002_d97c && ix <= 0x400f_6a7a && ix & 0xfffff != 0x921fb;
        slow[k] = !(direct | one | two);
        // rem_pio2's one-round reduction, for n = ±1 and n = ±2.
        let (p1, p1t) = if two {
            (2.0 * PIO2_1, 2.0 * PIO2_1T)
        } else {
            (PIO2_1, PIO2_1T)
        };
        let (y0, y1) = if neg {
            let z = x[k] + p1;
            let y0 = z + p1t;
            (y0, (z - y0) + p1t)
        } else {
            let z = x[k] - p1;
            let y0 = z - p1t;
            (y0, (z - y0) - p1t)
        };
        let (xa, ya) = if direct { (x[k], 0.0) } else { (y0, y1) };
        // k_sin(xa, ya, iy) with iy = 0 for `direct`, 1 otherwise.
        let z = xa * xa;
        let w = z * z;
        let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
        let v = z * xa;
        let sn = if direct {
            xa + v * (S1 + z * r)
        } else {
            xa - ((z * (0.5 * ya - v * r) - ya) - v * S1)
        };
        // k_cos(xa, ya).
        let rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
        let hz = 0.5 * z;
        let wc = 1.0 - hz;
        let cs = wc + (((1.0 - wc) - hz) + (z * rc - xa * ya));
        // The quadrant n & 3: 0 (direct), 1 (n = 1), 2 (n = ±2), 3 (n = −1).
        (s[k], c[k]) = if direct {
            (sn, cs)
        } else if two {
            (-sn, -cs)
        } else if neg {
            (-cs, sn)
        } else {
            (cs, -sn)
        };
    }
    for k in 0..LANES {
        if slow[k] {
            (s[k], c[k]) = libm::sincos(x[k]);
        }
    }
    (s, c)
}

/// `sincos_lanes` compiled for AVX2 (no FMA).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sincos_avx2(x: &[f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
    sincos_lanes(x)
}

/// `sincos_lanes` compiled for AVX-512F. LLVM's avx512f implies FMA, but Rust
/// never fuses a separate multiply and add, so the bits stay libm's.
///
/// # Safety
/// The CPU must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn sincos_avx512(x: &[f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
    sincos_lanes(x)
}

/// `sincos_lanes` at `level`, which must not exceed `simd::detected()`.
#[inline]
fn sincos_at(x: &[f64; LANES], level: SimdLevel) -> ([f64; LANES], [f64; LANES]) {
    debug_assert!(level <= crate::simd::detected());
    match level {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: callers pass a level up to `detected()`, which saw AVX-512F.
        SimdLevel::Avx512 => unsafe { sincos_avx512(x) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above, with AVX2.
        SimdLevel::Avx2 => unsafe { sincos_avx2(x) },
        _ => sincos_lanes(x),
    }
}

/// (sin, cos) of each lane of `x` at the process's SIMD level (same bits at any).
#[inline]
pub(crate) fn sincos(x: &[f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
    sincos_at(x, crate::simd::level())
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn check(x: [f64; LANES]) {
        for level in [SimdLevel::Scalar, SimdLevel::Avx2, SimdLevel::Avx512] {
            if level <= crate::simd::detected() {
                check_at(x, level);
            }
        }
    }

    fn check_at(x: [f64; LANES], level: SimdLevel) {
        let (s, c) = sincos_at(&x, level);
        for k in 0..LANES {
            let (ws, wc) = libm::sincos(x[k]);
            assert_eq!(
                (s[k].to_bits(), c[k].to_bits()),
                (ws.to_bits(), wc.to_bits()),
                "{level:?} sincos({:e}) = {:e}, {:e}, not {ws:e}, {wc:e}",
                x[k],
                s[k],
                c[k]
            );
        }
    }

    #[test]
    fn edges_match_libm_bit_for_bit() {
        use std::f64::consts::*;
        let mut v = vec![
            0.0,
            -0.0,
            1e-300,
            -5e-324,
            1e-9,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e6,
            -123456.7,
            f64::MAX,
        ];
        for m in [
            FRAC_PI_4,
            FRAC_PI_2,
            3.0 * FRAC_PI_4,
            PI,
            5.0 * FRAC_PI_4,
            TAU,
        ] {
            for sign in [1.0, -1.0] {
                let x: f64 = sign * m;
                for d in -4i64..=4 {
                    v.push(f64::from_bits((x.to_bits() as i64 + d) as u64));
                }
            }
        }
        // Every boundary of the high word the ranges test, and its neighbours.
        for hw in [
            0x3e46_a09eu64,
            0x3fe9_21fb,
            0x4002_d97c,
            0x400f_6a7a,
            0x3ff9_21fb,
            0x4009_21fb,
        ] {
            for d in [-1i64, 0, 1] {
                for lo in [0u64, 1, 0x8000_0000, 0xffff_ffff] {
                    let b = (((hw as i64 + d) as u64) << 32) | lo;
                    v.push(f64::from_bits(b));
                    v.push(-f64::from_bits(b));
                }
            }
        }
        for chunk in v.chunks(LANES) {
            let mut x = [1.0; LANES];
            x[..chunk.len()].copy_from_slice(chunk);
            check(x);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn headings_match_libm_bit_for_bit(x in prop::array::uniform8(-3.2f64..3.2)) {
            check(x);
        }

        #[test]
        fn any_angle_matches_libm_bit_for_bit(x in prop::array::uniform8(any::<f64>())) {
            check(x);
        }

        #[test]
        fn near_quadrant_edges_match_libm_bit_for_bit(
            q in prop::array::uniform8(-5i32..=5), d in prop::array::uniform8(-1e-6f64..1e-6),
        ) {
            check(std::array::from_fn(|k| q[k] as f64 * std::f64::consts::FRAC_PI_4 + d[k]));
        }
    }
}

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

/// `e^x` within a few ULP, computed the same way on every machine.
///
/// The platform's libm may pick different code paths per CPU (glibc has an
/// FMA variant), which could change the last bit between machines; this one
/// is plain IEEE arithmetic, branch-free (so blocks of neurons vectorise) and
/// cheaper than a libm call. Saturates to 0 below −708 and to `e^709` above 709.
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    const LOG2E: f64 = std::f64::consts::LOG2_E;
    // ln 2 split so that k·LN2_HI is exact for |k| < 2^11.
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    // 1.5·2^52: adding it rounds to an integer held in the low mantissa bits.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let x = if x.is_nan() {
        x
    } else {
        x.clamp(-708.0, 709.0)
    };
    let kf = x * LOG2E + SHIFT;
    let k = kf - SHIFT;
    let r = x - k * LN2_HI - k * LN2_LO;
    // Taylor series to r^12 on |r| ≤ ln2/2: truncation error < 2e-16 relative.
    let mut p = 1.0 / 479_001_600.0;
    for c in [
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
    ] {
        p = p * r + c;
    }
    // 2^k from the integer in kf's low bits.
    let k_int = i64::from(kf.to_bits() as i32);
    let scale = f64::from_bits(((k_int + 1023) as u64) << 52);
    p * scale
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

/// `tanh x`, the same bits on every machine.
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

#[cfg(test)]
mod tests {
    use super::*;

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
}

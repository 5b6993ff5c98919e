//! Node activation functions (the paper's Table I plus the plain sigmoid).

use serde::{Deserialize, Serialize};

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
    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::BipolarSigmoid => bipolar_sigmoid(x),
            Activation::Linear => x,
            Activation::Gaussian => exp(-2.5 * x * x),
            Activation::Abs => x.abs(),
            Activation::Sine => x.sin(),
            Activation::Cosine => x.cos(),
            Activation::Sigmoid => 1.0 / (1.0 + exp(-4.9 * x)),
        }
    }
}

/// The bipolar sigmoid `2/(1+e^(−4.9x)) − 1` used by CPPN outputs and controllers.
#[inline]
pub fn bipolar_sigmoid(x: f64) -> f64 {
    2.0 / (1.0 + exp(-4.9 * x)) - 1.0
}

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
    fn table_one_values() {
        assert_eq!(Activation::BipolarSigmoid.apply(0.0), 0.0);
        assert!((Activation::BipolarSigmoid.apply(10.0) - 1.0).abs() < 1e-9);
        assert_eq!(Activation::Gaussian.apply(0.0), 1.0);
        assert!((Activation::Gaussian.apply(1.0) - (-2.5f64).exp()).abs() < 1e-15);
        assert_eq!(Activation::Abs.apply(-2.0), 2.0);
        assert_eq!(Activation::Sigmoid.apply(0.0), 0.5);
        assert_eq!(Activation::Linear.apply(-3.5), -3.5);
    }
}

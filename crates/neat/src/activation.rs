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
    2.0 / (1.0 + exp(-4.9 * x)) - 1.0
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
}

//! The range a controller reads its inputs in, as its task declares it: the
//! robot sensors' [0, 1], or any finite value for a task whose network reads
//! raw observations (the classic-control tasks). vivae's exported step and
//! every export format (C, ONNX, JSON) read an input the same way through it.

use serde::Serialize;

/// The range an input is read in: a value above `high` is read as `high`,
/// one below `low` as `low`, NaN as 0 (then clamped), so every reading is
/// finite and a NaN sensor cannot make the state NaN for good.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Readings {
    /// The least value read.
    pub low: f64,
    /// The greatest value read.
    pub high: f64,
}

impl Readings {
    /// The robot sensors' range, [0, 1]: the simulator's own readings are
    /// in it, so reading through it changes none of their bits.
    pub const SENSORS: Readings = Readings {
        low: 0.0,
        high: 1.0,
    };

    /// Every finite binary64: an observation is read as it is (the identity
    /// on finite values), ±∞ as the largest finite value of its sign.
    pub const UNBOUNDED: Readings = Readings {
        low: -f64::MAX,
        high: f64::MAX,
    };

    /// `x` as a controller reads it.
    #[inline]
    pub fn read(self, x: f64) -> f64 {
        let x = if x.is_nan() { 0.0 } else { x };
        if x > self.high {
            self.high
        } else if x < self.low {
            self.low
        } else {
            x
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Readings;

    #[test]
    fn a_reading_is_clamped_to_its_range_nan_as_zero() {
        let s = Readings::SENSORS;
        for (x, want) in [
            (0.25, 0.25),
            (-0.0, -0.0),
            (2.0, 1.0),
            (-3.0, 0.0),
            (f64::NAN, 0.0),
            (f64::INFINITY, 1.0),
            (f64::NEG_INFINITY, 0.0),
        ] {
            assert_eq!(s.read(x).to_bits(), f64::to_bits(want), "{x}");
        }
        let u = Readings::UNBOUNDED;
        for (x, want) in [
            (-2.5e300, -2.5e300),
            (7.0, 7.0),
            (-0.0, -0.0),
            (f64::NAN, 0.0),
            (f64::INFINITY, f64::MAX),
            (f64::NEG_INFINITY, -f64::MAX),
        ] {
            assert_eq!(u.read(x).to_bits(), f64::to_bits(want), "{x}");
        }
        // NaN is read as 0 clamped into a range without 0.
        let above = Readings {
            low: 2.0,
            high: 3.0,
        };
        assert_eq!(above.read(f64::NAN), 2.0);
    }
}

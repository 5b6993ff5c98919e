//! Expression parameters: which CPPN outputs become links, and their weights.

use serde::{Deserialize, Serialize};

use super::error::HyperError;

/// HyperNEAT expression parameters (DESIGN §7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HyperParams {
    /// Expression threshold `t`: CPPN outputs with `|o| <= t` express no connection.
    ///
    /// Paper: 0.2.
    pub threshold: f64,
    /// Largest controller weight: an output `o` maps to `sign(o)·(|o| − t)/(1 − t)·amplitude`.
    ///
    /// Paper: 3.0.
    pub amplitude: f64,
}

impl Default for HyperParams {
    fn default() -> Self {
        HyperParams {
            threshold: 0.2,
            amplitude: 3.0,
        }
    }
}

impl HyperParams {
    /// Checks that `0 ≤ threshold < 1` and `amplitude` is finite and positive.
    pub fn validate(&self) -> Result<(), HyperError> {
        if !(self.threshold >= 0.0 && self.threshold < 1.0) {
            return Err(HyperError::InvalidParam {
                field: "threshold",
                value: self.threshold,
                reason: "must satisfy 0 <= threshold < 1",
            });
        }
        if !(self.amplitude.is_finite() && self.amplitude > 0.0) {
            return Err(HyperError::InvalidParam {
                field: "amplitude",
                value: self.amplitude,
                reason: "must be finite and > 0",
            });
        }
        Ok(())
    }

    /// Maps a CPPN output to a connection weight, `None` when not expressed.
    ///
    /// Outputs beyond ±1 (possible only if a CPPN output is not a bipolar
    /// sigmoid) are clamped so weights never exceed the amplitude; a NaN
    /// output expresses nothing.
    #[inline]
    pub fn express(&self, o: f64) -> Option<f64> {
        let w = self.weight_or_zero(o);
        if w == 0.0 { None } else { Some(w) }
    }

    /// As [`HyperParams::express`], with 0 for "no connection" (an expressed
    /// weight is never exactly 0, since `|o| − t > 0`).
    #[inline(always)]
    pub(super) fn weight_or_zero(&self, o: f64) -> f64 {
        let a = o.abs();
        let scaled = (a.min(1.0) - self.threshold) / (1.0 - self.threshold) * self.amplitude;
        // Guard against underflow to 0 turning an expressed link into "none".
        let scaled = scaled.max(f64::MIN_POSITIVE);
        let w = if o < 0.0 { -scaled } else { scaled };
        // Branch-free (selects), so that loops over many outputs vectorise.
        // NaN fails `a > t` and so expresses nothing.
        if a > self.threshold { w } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperneat::test_util::close;

    #[test]
    fn threshold_and_scaling_formula() {
        let p = HyperParams::default();
        assert_eq!(p.express(0.0), None);
        assert_eq!(p.express(0.2), None);
        assert_eq!(p.express(-0.2), None);
        assert_eq!(p.express(f64::NAN), None);
        assert!(close(p.express(0.6).unwrap(), 0.4 / 0.8 * 3.0));
        assert!(close(p.express(-0.6).unwrap(), -1.5));
        assert!(close(p.express(1.0).unwrap(), 3.0));
        assert!(close(p.express(-1.0).unwrap(), -3.0));
        // Just above the threshold: a tiny, but present, link.
        let w = p.express(0.2 + 1e-12).unwrap();
        assert!(w > 0.0 && w < 1e-10);
        // Outputs beyond ±1 are clamped to the amplitude.
        assert!(close(p.express(7.0).unwrap(), 3.0));
        let q = HyperParams {
            threshold: 0.0,
            amplitude: 5.0,
        };
        assert!(close(q.express(0.5).unwrap(), 2.5));
    }

    #[test]
    fn params_validate_names_the_field() {
        let bad = HyperParams {
            threshold: 1.0,
            ..Default::default()
        };
        assert!(matches!(
            bad.validate(),
            Err(HyperError::InvalidParam {
                field: "threshold",
                ..
            })
        ));
        let bad = HyperParams {
            amplitude: f64::NAN,
            ..Default::default()
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("amplitude")
        );
        assert!(HyperParams::default().validate().is_ok());
    }

    #[test]
    fn params_serde_defaults_and_unknown_fields() {
        let p: HyperParams = serde_json::from_str(r#"{"threshold": 0.3}"#).unwrap();
        assert_eq!(p.threshold, 0.3);
        assert_eq!(p.amplitude, 3.0);
        assert!(serde_json::from_str::<HyperParams>(r#"{"treshold": 0.3}"#).is_err());
    }
}

//! ES-HyperNEAT parameters: quadtree depths, thresholds, iteration level.

use serde::{Deserialize, Serialize};

use crate::hyperneat::error::HyperError;
use crate::hyperneat::params::HyperParams;

/// ES-HyperNEAT parameters (Risi & Stanley 2012), named as in the paper and
/// in PUREPLES / MultiNEAT.
///
/// Depths count quadtree levels from the root square `[−1, 1]²` at level 1,
/// as PUREPLES and MultiNEAT do: the root is always cut into four squares of
/// level 2, and a square of level `l` that is divided (every `l <
/// initial_depth`; up to `l < max_depth` where the variance calls for it)
/// has its four children cut too. The finest squares of a tree divided to
/// depth `d` thus lie at level `d + 1`, a `2^d × 2^d` grid (depth 3: 8×8,
/// the paper's initial resolution). Variance and band thresholds apply to
/// the raw CPPN weight output (in `[−1, 1]`), before any scaling.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EsParams {
    /// Every square of a level below this is divided. Default 3.
    pub initial_depth: u32,
    /// No square of this level or deeper is divided. Default 3.
    pub max_depth: u32,
    /// A square is divided further (up to `max_depth`) when the variance of
    /// its four children exceeds this. Default 0.03.
    pub division_threshold: f64,
    /// Pruning descends into a square whose leaves' variance exceeds this. Default 0.03.
    pub variance_threshold: f64,
    /// A point expresses a link when its band level (how much it differs from
    /// its neighbours on both sides along x or along y) exceeds this. Default 0.3.
    pub band_threshold: f64,
    /// Rounds of exploring outward from newly found hidden nodes. Default 1.
    pub iteration_level: u32,
    /// Whether links may go in any direction (a recurrent network); when
    /// false, every link goes strictly one way along y ([`EsParams::flow`]),
    /// which makes the network acyclic. Default false.
    pub recurrent: bool,
    /// Which way a feed-forward network's links go along y: upward (the
    /// paper's, inputs at the bottom), or downward for a layout whose
    /// outputs sit below its inputs. Not read when `recurrent`. Default upward.
    #[serde(skip_serializing_if = "Flow::is_upward")]
    pub flow: Flow,
    /// Weight expression: threshold and amplitude as in plain HyperNEAT.
    pub expression: HyperParams,
}

impl Default for EsParams {
    fn default() -> Self {
        EsParams {
            initial_depth: 3,
            max_depth: 3,
            division_threshold: 0.03,
            variance_threshold: 0.03,
            band_threshold: 0.3,
            iteration_level: 1,
            recurrent: false,
            flow: Flow::Upward,
            expression: HyperParams::default(),
        }
    }
}

/// The direction of a feed-forward ES network's links along the plane's y.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Flow {
    /// Source y < target y: the outputs sit above the inputs (the paper's layout).
    #[default]
    Upward,
    /// Source y > target y: the outputs sit below the inputs.
    Downward,
}

impl Flow {
    /// Whether this is the default, [`Flow::Upward`].
    pub fn is_upward(&self) -> bool {
        *self == Flow::Upward
    }

    /// Whether a feed-forward link may go from `source` to `target`.
    pub fn allows(self, source: [f64; 2], target: [f64; 2]) -> bool {
        match self {
            Flow::Upward => source[1] < target[1],
            Flow::Downward => source[1] > target[1],
        }
    }
}

/// Deepest accepted `max_depth`: a depth-10 tree already has 4^9 ≈ 262 000
/// squares per explored node.
pub const MAX_DEPTH: u32 = 10;

/// Largest accepted `iteration_level`.
pub const MAX_ITERATION_LEVEL: u32 = 16;

impl EsParams {
    /// Checks depths (`1 ≤ initial_depth ≤ max_depth ≤ 10`), thresholds
    /// (finite, ≥ 0), the iteration level (≤ 16) and the expression.
    pub fn validate(&self) -> Result<(), HyperError> {
        let bad = |field, value: f64, reason| {
            Err(HyperError::InvalidParam {
                field,
                value,
                reason,
            })
        };
        if self.max_depth > MAX_DEPTH {
            return bad("max_depth", self.max_depth.into(), "must be at most 10");
        }
        if self.initial_depth > self.max_depth {
            return bad(
                "initial_depth",
                self.initial_depth.into(),
                "must not exceed max_depth",
            );
        }
        if self.iteration_level > MAX_ITERATION_LEVEL {
            return bad(
                "iteration_level",
                self.iteration_level.into(),
                "must be at most 16",
            );
        }
        for (field, v) in [
            ("division_threshold", self.division_threshold),
            ("variance_threshold", self.variance_threshold),
            ("band_threshold", self.band_threshold),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(field, v, "must be finite and >= 0");
            }
        }
        self.expression.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_bad_values_name_the_field() {
        assert!(EsParams::default().validate().is_ok());
        let p = EsParams {
            initial_depth: 4,
            ..Default::default()
        };
        assert!(
            p.validate()
                .unwrap_err()
                .to_string()
                .contains("initial_depth")
        );
        let p = EsParams {
            max_depth: 11,
            initial_depth: 1,
            ..Default::default()
        };
        assert!(p.validate().unwrap_err().to_string().contains("max_depth"));
        let p = EsParams {
            band_threshold: f64::NAN,
            ..Default::default()
        };
        assert!(
            p.validate()
                .unwrap_err()
                .to_string()
                .contains("band_threshold")
        );
    }

    #[test]
    fn serde_fills_defaults_and_refuses_unknown_fields() {
        let p: EsParams = serde_json::from_str(r#"{"max_depth": 5}"#).unwrap();
        assert_eq!(p.max_depth, 5);
        assert_eq!(p.band_threshold, 0.3);
        assert!(serde_json::from_str::<EsParams>(r#"{"maxdepth": 5}"#).is_err());
        // The default flow is not written, so earlier files keep their bytes.
        let text = serde_json::to_string(&EsParams::default()).unwrap();
        assert!(!text.contains("flow"), "{text}");
        let p: EsParams = serde_json::from_str(r#"{"flow": "downward"}"#).unwrap();
        assert_eq!(p.flow, Flow::Downward);
    }
}

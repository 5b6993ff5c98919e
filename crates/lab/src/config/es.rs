//! The substrate kind and the ES-HyperNEAT keys of a run's config
//! (`substrate.kind`, `[substrate.es]`); what they build is
//! [`crate::controller::es`].

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::hyperneat::es::{EsParams, Flow};
use vivae_neat::hyperneat::{HyperError, HyperParams};

use crate::polar::CoordMode;

/// Which substrate a run's CPPNs are decoded into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SubstrateKind {
    /// The dense polar neuron sheet (the paper's).
    #[default]
    Polar,
    /// ES-HyperNEAT: hidden neurons placed by the CPPN between sensors and wheels.
    EsHyperneat,
}

impl SubstrateKind {
    /// Whether this is the default, [`SubstrateKind::Polar`].
    pub fn is_polar(&self) -> bool {
        *self == SubstrateKind::Polar
    }
}

impl std::str::FromStr for SubstrateKind {
    type Err = String;

    fn from_str(s: &str) -> Result<SubstrateKind, String> {
        match s {
            "polar" => Ok(SubstrateKind::Polar),
            "es-hyperneat" => Ok(SubstrateKind::EsHyperneat),
            other => Err(format!("'{other}': expected polar or es-hyperneat")),
        }
    }
}

/// The CPPN output that expresses ES links with `substrate.es.leo` (on the
/// dense sheet it paints neuron → neuron weights; ES does not read it otherwise).
pub const ES_LEO_OUTPUT: usize = crate::polar::RECURRENT_OUTPUT;

/// Refuses a feed-forward ES net (`recurrent` false) in polar coordinates,
/// saying what to change. In the `(ρ, φ/π)` plane the left wheel neuron
/// (y = −3/4) lies below every sensor of a field of view under 270° and the
/// right one (y = 3/4) above them: no one direction of links along y reaches
/// both. In the cartesian plane both lie behind (below) the sensors.
pub fn check_feed_forward(recurrent: bool, mode: CoordMode) -> Result<(), String> {
    if recurrent || mode == CoordMode::Cartesian {
        return Ok(());
    }
    Err(
        "substrate.es.recurrent = false needs substrate.coordinates = \"cartesian\": \
         in polar coordinates the wheel neurons lie on both sides of the sensors along y, \
         so no feed-forward link direction reaches both; \
         set substrate.coordinates = \"cartesian\" or remove substrate.es.recurrent"
            .into(),
    )
}

/// ES-HyperNEAT parameters of a run (`[substrate.es]`); the weight
/// expression (threshold, amplitude) is `[hyperneat]`'s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EsConfig {
    /// Quadtree levels every square is divided to around each explored node
    /// (3: an 8×8 grid, the paper's initial resolution).
    ///
    /// Paper: 3 (Risi & Stanley 2012, as PUREPLES and MultiNEAT read it).
    pub initial_depth: u32,
    /// Deepest quadtree level a square with varying weights is divided to (at most 10).
    ///
    /// Paper: 3.
    pub max_depth: u32,
    /// A square is divided further (up to `max_depth`) when the variance of its
    /// four children's CPPN weights exceeds this.
    ///
    /// Paper: 0.03.
    pub division_threshold: f64,
    /// Pruning descends into a square whose leaves' weight variance exceeds this.
    ///
    /// Paper: 0.03.
    pub variance_threshold: f64,
    /// A point becomes a hidden neuron (and expresses a link) when its weight
    /// differs from its neighbours' on both sides, along x or y, by more than this.
    ///
    /// Paper: 0.3.
    pub band_threshold: f64,
    /// Rounds of discovery outward from the hidden neurons just found (at most 16).
    ///
    /// Paper: 1.
    pub iteration_level: u32,
    /// Whether links may run in any direction (a recurrent controller, like the
    /// dense sheet, the default); `false` keeps only links going from ahead to
    /// behind (source y > target y, from the sensors towards the wheel
    /// neurons behind them), a feed-forward net as in the paper's tasks.
    /// Needs `substrate.coordinates = "cartesian"`.
    ///
    /// Example: false.
    pub recurrent: bool,
    /// Whether a link exists by HyperNEAT-LEO (Verbancsics & Stanley 2011)
    /// instead of the weight threshold: CPPN output 2 (on the dense sheet
    /// the neuron → neuron weights, unused by ES) becomes the link
    /// expression output, a link exists iff it is > 0, and its weight is
    /// output 0 clamped to [−1, 1] times `hyperneat.amplitude`. The CPPN
    /// keeps its outputs, so a run without it keeps its bits. Needs
    /// `substrate.kind = "es-hyperneat"`.
    ///
    /// Example: true.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub leo: bool,
    /// Whether generation 0 starts from LEO's Gaussian locality seed instead of
    /// minimal CPPNs: a Gaussian hidden node of `Δx = x1 − x2` feeds output 2,
    /// so at first only links between points less than about 0.53 apart along
    /// the plane's x are expressed. With `substrate.coordinates = "cartesian"`
    /// x is `ρ·sin φ`, the left–right offset (links stay on one side of the
    /// robot); with `"polar"` x is `ρ`, the ring (links stay between nearby
    /// rings). Needs `leo = true`, a strategy that starts from given genomes
    /// (NEAT's does) and no `experiment.init_population`.
    ///
    /// Example: true.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub leo_seed: bool,
}

impl Default for EsConfig {
    fn default() -> Self {
        let p = EsParams::default();
        EsConfig {
            initial_depth: p.initial_depth,
            max_depth: p.max_depth,
            division_threshold: p.division_threshold,
            variance_threshold: p.variance_threshold,
            band_threshold: p.band_threshold,
            iteration_level: p.iteration_level,
            recurrent: true,
            leo: false,
            leo_seed: false,
        }
    }
}

impl EsConfig {
    /// Whether every key has its default (the section is then not written).
    pub fn is_default(&self) -> bool {
        *self == EsConfig::default()
    }

    /// The library's parameters, weights expressed by `expression`.
    pub fn params(&self, expression: HyperParams) -> EsParams {
        EsParams {
            initial_depth: self.initial_depth,
            max_depth: self.max_depth,
            division_threshold: self.division_threshold,
            variance_threshold: self.variance_threshold,
            band_threshold: self.band_threshold,
            iteration_level: self.iteration_level,
            recurrent: self.recurrent,
            // The wheel neurons sit behind the sensors (y < 0 in the
            // cartesian plane), so a feed-forward net's links run downward.
            flow: Flow::Downward,
            expression,
        }
    }

    /// Checks every key; the message names it (`substrate.es.KEY = V: why`).
    pub fn validate(&self) -> Result<(), String> {
        if self.leo_seed && !self.leo {
            return Err(
                "substrate.es.leo_seed = true: the locality seed feeds the LEO output, set substrate.es.leo = true"
                    .into(),
            );
        }
        match self.params(HyperParams::default()).validate() {
            Ok(()) => Ok(()),
            Err(HyperError::InvalidParam {
                field,
                value,
                reason,
            }) => Err(format!("substrate.es.{field} = {value}: {reason}")),
            Err(other) => Err(format!("substrate.es: {other}")),
        }
    }
}

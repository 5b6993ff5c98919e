//! The geometry of polar sheets: grids, nodes and their CPPN coordinates,
//! the wheel neurons, and which CPPN output paints which sheet (the layout
//! itself is described in [`crate::controller::substrate`]).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// CPPN output painting surface sensor → neuron weights.
pub const SURFACE_OUTPUT: usize = 0;
/// CPPN output giving neuron biases.
pub const BIAS_OUTPUT: usize = 1;
/// CPPN output painting neuron → neuron weights.
pub const RECURRENT_OUTPUT: usize = 2;
/// CPPN output painting distance sensor → neuron weights (only with distance sensors).
pub const DISTANCE_OUTPUT: usize = 3;
/// CPPN output painting opponent radar → neuron weights (only with the opponent radar).
pub const OPPONENT_OUTPUT: usize = 4;
/// The radius the wheel neurons sit nearest to: the middle ring of a 3-ring sheet.
pub const WHEEL_RADIUS: f64 = 2.0 / 3.0;
/// Largest number of rings or angles a grid may have.
pub const MAX_GRID_SIDE: usize = 10_000;

/// Errors in a substrate description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SubstrateError {
    /// A grid string is not of the form `RxA`.
    #[error("invalid grid {input:?}: {reason} (expected RINGSxANGLES, e.g. \"3x5\")")]
    Parse {
        /// The text that failed to parse.
        input: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A grid dimension is out of range.
    #[error("invalid grid {rings}x{angles}: rings and angles must be in 1..={max}", max = MAX_GRID_SIDE)]
    GridSize {
        /// Rings requested.
        rings: usize,
        /// Angles requested.
        angles: usize,
    },
    /// The neuron sheet cannot hold two distinct wheel neurons.
    #[error("the neuron sheet {0} has one angle; wheel neurons L and R need at least 2 angles")]
    OneAngle(PolarGrid),
    /// A field of view is out of range.
    #[error("invalid {field} = {value}°: {reason}")]
    Fov {
        /// Which field.
        field: &'static str,
        /// The rejected value in degrees.
        value: f64,
        /// The valid range.
        reason: &'static str,
    },
    /// Distance sensors requested with zero rays.
    #[error("distance_rays must be at least 1 when given (omit it for no distance sensors)")]
    NoRays,
}

/// A polar grid of `rings × angles` nodes; parses from and prints as `"RxA"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct PolarGrid {
    /// Number of rings (radii).
    pub rings: usize,
    /// Number of angles per ring.
    pub angles: usize,
}

impl PolarGrid {
    /// A grid of `rings × angles`, both in `1..=MAX_GRID_SIDE`.
    pub fn new(rings: usize, angles: usize) -> Result<PolarGrid, SubstrateError> {
        if (1..=MAX_GRID_SIDE).contains(&rings) && (1..=MAX_GRID_SIDE).contains(&angles) {
            Ok(PolarGrid { rings, angles })
        } else {
            Err(SubstrateError::GridSize { rings, angles })
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.rings * self.angles
    }

    /// Whether the grid has no nodes (never true for a validated grid).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index of the node on ring `ring` at angle `angle` (ring-major).
    pub fn index(&self, ring: usize, angle: usize) -> usize {
        ring * self.angles + angle
    }

    /// Radius of ring `ring`: `(ring + 1)/rings`.
    pub fn radius(&self, ring: usize) -> f64 {
        (ring + 1) as f64 / self.rings as f64
    }

    /// The grid's nodes, ring-major, left to right, with angles over `fov_deg`.
    pub fn nodes(&self, fov_deg: f64) -> Vec<PolarNode> {
        let angles: Vec<f64> = vivae_sim::spread(self.angles, fov_deg).collect();
        (0..self.rings)
            .flat_map(|ring| {
                let rho = self.radius(ring);
                angles
                    .iter()
                    .enumerate()
                    .map(move |(angle_index, &phi)| PolarNode {
                        ring,
                        angle_index,
                        rho,
                        phi,
                    })
            })
            .collect()
    }

    /// The wheel neurons of this grid used as the neuron sheet.
    pub fn wheel_neurons(&self) -> Result<WheelNeurons, SubstrateError> {
        if self.angles < 2 {
            return Err(SubstrateError::OneAngle(*self));
        }
        let ring = (0..self.rings)
            .min_by(|&a, &b| {
                let da = (self.radius(a) - WHEEL_RADIUS).abs();
                let db = (self.radius(b) - WHEEL_RADIUS).abs();
                da.total_cmp(&db)
            })
            .unwrap_or(0);
        Ok(WheelNeurons {
            left: self.index(ring, 0),
            right: self.index(ring, self.angles - 1),
        })
    }
}

impl fmt::Display for PolarGrid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.rings, self.angles)
    }
}

impl FromStr for PolarGrid {
    type Err = SubstrateError;

    fn from_str(s: &str) -> Result<PolarGrid, SubstrateError> {
        let err = |reason: &str| SubstrateError::Parse {
            input: s.to_string(),
            reason: reason.to_string(),
        };
        let t = s.trim();
        let mut parts = t.split(['x', 'X', '×']);
        let (Some(r), Some(a), None) = (parts.next(), parts.next(), parts.next()) else {
            return Err(err("expected exactly one 'x' between two numbers"));
        };
        let number = |part: &str, what: &str| -> Result<usize, SubstrateError> {
            let part = part.trim();
            if part.is_empty() {
                return Err(err(&format!("the number of {what} is missing")));
            }
            part.parse::<usize>().map_err(|_| {
                err(&format!(
                    "the number of {what} {part:?} is not a whole number"
                ))
            })
        };
        let rings = number(r, "rings")?;
        let angles = number(a, "angles")?;
        PolarGrid::new(rings, angles)
    }
}

impl TryFrom<String> for PolarGrid {
    type Error = SubstrateError;

    fn try_from(s: String) -> Result<PolarGrid, SubstrateError> {
        s.parse()
    }
}

impl From<PolarGrid> for String {
    fn from(g: PolarGrid) -> String {
        g.to_string()
    }
}

/// One node of a polar sheet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarNode {
    /// Ring index (0 = innermost).
    pub ring: usize,
    /// Angle index (0 = leftmost).
    pub angle_index: usize,
    /// Radius `(ring+1)/rings`, in (0, 1].
    pub rho: f64,
    /// Angle in radians, 0 ahead, negative to the left.
    pub phi: f64,
}

impl PolarNode {
    /// The node's position in the drawing plane: `(ρ·sin φ, ρ·cos φ)`, x right, y ahead.
    pub fn cartesian(&self) -> [f64; 2] {
        let (sin, cos) = vivae_neat::math::sin_cos(self.phi);
        [self.rho * sin, self.rho * cos]
    }

    /// The node's CPPN coordinates in the given mode.
    pub fn coords(&self, mode: CoordMode) -> [f64; 2] {
        match mode {
            CoordMode::Cartesian => self.cartesian(),
            CoordMode::Polar => [self.rho, self.phi / std::f64::consts::PI],
        }
    }
}

/// How node positions are fed to the CPPN.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum CoordMode {
    /// `(ρ·sin φ, ρ·cos φ)` (DESIGN §7 default).
    #[default]
    Cartesian,
    /// The raw polar pair `(ρ, φ/π)`.
    Polar,
}

/// Indices of the two wheel neurons in the neuron sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct WheelNeurons {
    /// The left wheel's neuron (leftmost angle of the wheel ring).
    pub left: usize,
    /// The right wheel's neuron (rightmost angle of the wheel ring).
    pub right: usize,
}

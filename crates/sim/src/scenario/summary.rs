//! A serialisable overview of a scenario (`vivae scenario info`).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{Scenario, SurfaceKind};

/// Arena size in a summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArenaSummary {
    /// Width in px.
    pub width: f64,
    /// Height in px.
    pub height: f64,
}

/// A robot start in a summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RobotSummary {
    /// Element id.
    pub id: String,
    /// Position x in px.
    pub x: f64,
    /// Position y in px.
    pub y: f64,
    /// Heading in degrees in [0, 360), 0 = up, clockwise.
    pub heading_deg: f64,
    /// Its team (`data-team`); absent for a robot of no team.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub team: String,
}

/// What `vivae scenario info` prints: a serialisable overview of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScenarioSummary {
    /// Arena size.
    pub arena: ArenaSummary,
    /// Robot starts.
    pub robots: Vec<RobotSummary>,
    /// Number of surface shapes per kind (all four kinds present).
    pub surfaces: BTreeMap<String, usize>,
    /// Number of fixed obstacles.
    pub fixed_obstacles: usize,
    /// Number of movable obstacles.
    pub movable_obstacles: usize,
    /// Number of pucks.
    pub pucks: usize,
    /// Number of position marks.
    pub marks: usize,
    /// Loader warnings.
    pub warnings: Vec<String>,
}

impl Scenario {
    /// Serialisable overview (arena, robots, counts, warnings).
    pub fn summary(&self) -> ScenarioSummary {
        ScenarioSummary {
            arena: ArenaSummary {
                width: self.width,
                height: self.height,
            },
            robots: self
                .robots
                .iter()
                .map(|r| RobotSummary {
                    id: r.id.clone(),
                    x: r.pos.x,
                    y: r.pos.y,
                    heading_deg: heading_degrees(r.heading),
                    team: r.team.clone(),
                })
                .collect(),
            surfaces: SurfaceKind::ALL
                .iter()
                .map(|k| (k.name().to_string(), self.surface_count(*k)))
                .collect(),
            fixed_obstacles: self.fixed_obstacles.len(),
            movable_obstacles: self.movable_obstacles.len(),
            pucks: self.pucks.len(),
            marks: self.marks.len(),
            warnings: self.warnings.clone(),
        }
    }
}

/// Heading in radians → degrees in [0, 360), rounded to 1e-9 to hide float noise.
pub fn heading_degrees(heading: f64) -> f64 {
    let d = heading.to_degrees().rem_euclid(360.0);
    let d = (d * 1e9).round() / 1e9;
    if d >= 360.0 { 0.0 } else { d }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headings_normalise_to_degrees() {
        assert_eq!(heading_degrees(0.0), 0.0);
        assert!((heading_degrees(-std::f64::consts::FRAC_PI_2) - 270.0).abs() < 1e-9);
    }
}

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
    /// The id of its route (`data-route`); absent for none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub route: Option<String>,
}

/// A route in a summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RouteSummary {
    /// Element id.
    pub id: String,
    /// Length of its centre line in px.
    pub length: f64,
    /// Whether it is a loop.
    pub closed: bool,
}

/// An obstacle region in a summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionSummary {
    /// Element id.
    pub id: String,
    /// Obstacles placed per episode.
    pub count: u32,
    /// Each obstacle's width and height in px.
    pub size: [f64; 2],
    /// Least distance from an obstacle's centre to any robot's start, px.
    pub clearance: f64,
}

/// A scripted robot (traffic) in a summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrafficSummary {
    /// Element id.
    pub id: String,
    /// Start position x in px.
    pub x: f64,
    /// Start position y in px.
    pub y: f64,
    /// Start heading in degrees in [0, 360), 0 = up, clockwise.
    pub heading_deg: f64,
    /// The id of the route it follows.
    pub route: String,
    /// Its throttle range (equal ends: a fixed throttle).
    pub throttle: [f64; 2],
    /// Up to this many px further along its route per episode.
    pub spread: f64,
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
    /// Routes, in document order.
    #[serde(default)]
    pub routes: Vec<RouteSummary>,
    /// Regions where obstacles are placed at random each episode.
    #[serde(default)]
    pub obstacle_regions: Vec<RegionSummary>,
    /// Scripted robots (traffic), not learners.
    #[serde(default)]
    pub traffic: Vec<TrafficSummary>,
    /// Loader warnings.
    pub warnings: Vec<String>,
}

impl Scenario {
    /// Serialisable overview (arena, robots, counts, routes, obstacle
    /// regions, scripted robots, warnings).
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
                    route: (r.route.and_then(|i| self.routes.get(i))).map(|r| r.id.clone()),
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
            routes: (self.routes.iter())
                .map(|r| RouteSummary {
                    id: r.id.clone(),
                    length: r.length(),
                    closed: r.closed,
                })
                .collect(),
            obstacle_regions: (self.obstacle_regions.iter())
                .map(|r| RegionSummary {
                    id: r.id.clone(),
                    count: r.count,
                    size: [r.size.x, r.size.y],
                    clearance: r.clearance,
                })
                .collect(),
            traffic: (self.traffic.iter())
                .map(|t| TrafficSummary {
                    id: t.id.clone(),
                    x: t.pos.x,
                    y: t.pos.y,
                    heading_deg: heading_degrees(t.heading),
                    route: (self.routes.get(t.route)).map_or_else(String::new, |r| r.id.clone()),
                    throttle: [t.throttle.0, t.throttle.1],
                    spread: t.spread,
                })
                .collect(),
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

//! A loaded scenario: the arena and everything in it ([`Scenario`]).
//!
//! One concern per file: `labels` (what a label means), `load` (SVG →
//! scenario), `attrs` (reading `data-*` values), `error`, `summary`, `route`
//! (routes), `episodic` (what may change per episode: obstacle regions,
//! scripted traffic), `rows` (regions placing blocks in rows across a road).

mod attrs;
mod episodic;
mod error;
mod ids;
mod labels;
mod limits;
mod load;
mod route;
mod rows;
mod summary;

use std::sync::Arc;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::geometry::Shape;
use crate::raster::SurfaceRaster;

pub use episodic::{MAX_REGION_COUNT, ObstacleRegion, TrafficStart};
pub use error::ScenarioError;
pub use limits::LoadOptions;
pub use route::{Route, RoutePlace};
pub use rows::{DEFAULT_GAP, MAX_LANES, Rows, lanes};
pub use summary::{
    ArenaSummary, RegionSummary, RobotSummary, RouteSummary, ScenarioSummary, TrafficSummary,
    heading_degrees,
};

/// Kind of ground surface (ViVAE's friction classes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfaceKind {
    /// Road: lowest friction.
    Road,
    /// Grass: highest friction, the default background.
    Grass,
    /// Sand.
    Sand,
    /// Water.
    Water,
}

impl SurfaceKind {
    /// All kinds, in a fixed order.
    pub const ALL: [SurfaceKind; 4] = [
        SurfaceKind::Road,
        SurfaceKind::Grass,
        SurfaceKind::Sand,
        SurfaceKind::Water,
    ];

    /// Lower-case name as used in labels and summaries.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKind::Road => "road",
            SurfaceKind::Grass => "grass",
            SurfaceKind::Sand => "sand",
            SurfaceKind::Water => "water",
        }
    }

    /// Label written into snapshots (ViVAE spelling).
    pub fn label(self) -> &'static str {
        match self {
            SurfaceKind::Road => "Road",
            SurfaceKind::Grass => "Grass",
            SurfaceKind::Sand => "Sand",
            SurfaceKind::Water => "Water",
        }
    }
}

/// Which puck label an element carried (kept so snapshots write it back).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum PuckKind {
    /// `SmallPuck`.
    Small,
    /// `BigPuck`.
    Big,
    /// `Puck`.
    Plain,
}

impl PuckKind {
    /// Label written into snapshots.
    pub fn label(self) -> &'static str {
        match self {
            PuckKind::Small => "SmallPuck",
            PuckKind::Big => "BigPuck",
            PuckKind::Plain => "Puck",
        }
    }
}

/// A ground surface: a shape of one kind, optionally with its own friction.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Element id.
    pub id: String,
    /// Kind (road, grass, sand, water).
    pub kind: SurfaceKind,
    /// `data-friction` override, if any.
    pub friction: Option<f64>,
    /// Area covered, in px.
    pub shape: Shape,
}

/// A polygonal obstacle (fixed or movable).
#[derive(Clone, Debug, PartialEq)]
pub struct Obstacle {
    /// Element id.
    pub id: String,
    /// Outline, in px.
    pub shape: Shape,
}

/// A round movable puck.
#[derive(Clone, Debug, PartialEq)]
pub struct Puck {
    /// Element id.
    pub id: String,
    /// Which puck label it had.
    pub kind: PuckKind,
    /// Centre.
    pub pos: DVec2,
    /// Radius.
    pub radius: f64,
}

/// A named position mark (ViVAE `PositionMark`).
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// Element id (the mark's name).
    pub id: String,
    /// Centre.
    pub pos: DVec2,
    /// Bounding-box size.
    pub size: DVec2,
}

/// Where and how a robot starts.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotStart {
    /// Element id.
    pub id: String,
    /// Label (e.g. the ViVAE robot class name).
    pub label: String,
    /// Start position (bounding-box centre).
    pub pos: DVec2,
    /// Heading in radians, 0 = up (−y), clockwise positive.
    pub heading: f64,
    /// Index of its route in [`Scenario::routes`] (`data-route`): the
    /// direction its progress is measured along.
    pub route: Option<usize>,
    /// Its team (`data-team`), empty for none: robots of different teams
    /// touching is a [`crate::TeamContact`].
    pub team: String,
}

/// A loaded scenario: the arena and everything in it, plus the surface raster.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// Source file name (for messages).
    pub source: String,
    /// Arena width in px.
    width: f64,
    /// Arena height in px.
    height: f64,
    /// Surface of points covered by no surface shape.
    background: SurfaceKind,
    /// Surfaces in document order (later ones cover earlier ones).
    surfaces: Vec<Surface>,
    /// Distinct (kind, friction override) pairs; index 0 is the background.
    /// The raster stores indices into this list.
    materials: Vec<(SurfaceKind, Option<f64>)>,
    /// Immovable obstacles.
    pub fixed_obstacles: Vec<Obstacle>,
    /// Movable (heavy) obstacles.
    pub movable_obstacles: Vec<Obstacle>,
    /// Movable (light) pucks.
    pub pucks: Vec<Puck>,
    /// Position marks.
    pub marks: Vec<Mark>,
    /// Robot starts in document order.
    pub robots: Vec<RobotStart>,
    /// Routes (paths labelled `Route`), in document order.
    pub routes: Vec<Route>,
    /// Regions where obstacles are placed at random each episode.
    pub obstacle_regions: Vec<ObstacleRegion>,
    /// How many of the last `fixed_obstacles` were placed for an episode from
    /// its regions (0 as loaded), so that contacts with them can be told apart.
    pub placed_obstacles: usize,
    /// Scripted robots (traffic), in document order; not learners.
    pub traffic: Vec<TrafficStart>,
    /// Non-fatal problems (unknown labels, elements without geometry).
    pub warnings: Vec<String>,
    /// Surface ids on a grid, built once at load.
    raster: Arc<SurfaceRaster>,
}

impl Scenario {
    /// Arena width in px.
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Arena height in px.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Surface of points covered by no surface shape.
    pub fn background(&self) -> SurfaceKind {
        self.background
    }

    /// Surfaces in document order (later ones cover earlier ones).
    pub fn surfaces(&self) -> &[Surface] {
        &self.surfaces
    }

    /// Distinct (kind, friction override) pairs; index 0 is the background.
    pub fn materials(&self) -> &[(SurfaceKind, Option<f64>)] {
        &self.materials
    }

    /// Material ids on a grid, built at load from the surfaces above (read-only,
    /// so it cannot go stale).
    pub fn raster(&self) -> &SurfaceRaster {
        &self.raster
    }

    /// Loads a scenario from raw bytes (checks UTF-8 first).
    pub fn from_svg_bytes(
        bytes: &[u8],
        source: &str,
        opts: &LoadOptions,
    ) -> Result<Scenario, ScenarioError> {
        let text = std::str::from_utf8(bytes).map_err(|_| ScenarioError::NotUtf8 {
            source_name: source.to_string(),
        })?;
        Scenario::from_svg(text, source, opts)
    }

    /// Loads a scenario from SVG text; `source` names the file in messages.
    pub fn from_svg(
        text: &str,
        source: &str,
        opts: &LoadOptions,
    ) -> Result<Scenario, ScenarioError> {
        load::Loader::load(text, source, opts)
    }

    /// The position mark whose id is `id` (e.g. a maze's `goal`), if any.
    pub fn mark(&self, id: &str) -> Option<&Mark> {
        self.marks.iter().find(|m| m.id == id)
    }

    /// Errors with [`ScenarioError::NoRobots`] if the scenario has no robot.
    pub fn require_robots(&self) -> Result<&Self, ScenarioError> {
        if self.robots.is_empty() {
            Err(ScenarioError::NoRobots {
                source_name: self.source.clone(),
            })
        } else {
            Ok(self)
        }
    }

    /// Whether an episode's start depends on its seed: obstacles placed at
    /// random, or traffic whose throttle or start varies.
    pub fn varies(&self) -> bool {
        self.obstacle_regions.iter().any(|r| r.count > 0)
            || (self.traffic.iter()).any(|t| t.spread > 0.0 || t.throttle.0 != t.throttle.1)
    }

    /// The route nearest `p` (by distance to its line), if any.
    pub fn nearest_route(&self, p: DVec2) -> Option<usize> {
        (self.routes.iter().enumerate())
            .map(|(i, r)| (i, r.locate(p, None).distance))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    /// Number of surface shapes of `kind`.
    pub fn surface_count(&self, kind: SurfaceKind) -> usize {
        self.surfaces.iter().filter(|s| s.kind == kind).count()
    }

    /// Surface kind and `data-friction` override at `p` from exact geometry
    /// (slow; the raster is the fast path). `None` outside the arena.
    pub fn surface_exact(&self, p: DVec2) -> Option<(SurfaceKind, Option<f64>)> {
        if !(p.x >= 0.0 && p.y >= 0.0 && p.x < self.width && p.y < self.height) {
            return None;
        }
        Some(
            self.surfaces
                .iter()
                .rev()
                .find(|s| s.shape.contains(p))
                .map(|s| (s.kind, s.friction))
                .unwrap_or((self.background, None)),
        )
    }
}

/// The surface of points no surface shape covers: the root's `data-background`, grass by default.
fn background_of(root: roxmltree::Node, source: &str) -> Result<SurfaceKind, ScenarioError> {
    match root.attribute("data-background") {
        None => Ok(SurfaceKind::Grass),
        Some(v) => labels::surface_kind(v.trim()).ok_or_else(|| ScenarioError::Attribute {
            source_name: source.to_string(),
            id: root.attribute("id").unwrap_or("svg").to_string(),
            attribute: "data-background".into(),
            value: v.into(),
        }),
    }
}

/// A scenario with its arena and nothing in it yet.
fn empty_scenario(source: &str, width: f64, height: f64, background: SurfaceKind) -> Scenario {
    Scenario {
        source: source.to_string(),
        width,
        height,
        background,
        surfaces: Vec::new(),
        materials: vec![(background, None)],
        fixed_obstacles: Vec::new(),
        movable_obstacles: Vec::new(),
        pucks: Vec::new(),
        marks: Vec::new(),
        robots: Vec::new(),
        routes: Vec::new(),
        obstacle_regions: Vec::new(),
        placed_obstacles: 0,
        traffic: Vec::new(),
        warnings: Vec::new(),
        raster: Arc::new(SurfaceRaster::empty()),
    }
}

//! Loading ViVAE scenario files (SVG drawn in Inkscape) into a [`Scenario`].
//!
//! roxmltree reads the raw document (labels, layers, document order, custom
//! attributes); usvg resolves shapes, arcs, CSS, units, the `viewBox` and every
//! ancestor transform into absolute paths. The two are joined by element `id`.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::geometry::{Aabb, FillRule, Shape, flatten_path};
use crate::raster::SurfaceRaster;

/// Flattening tolerance for curves, in px.
const FLATTEN_TOLERANCE: f64 = 0.1;

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

    fn from_name(s: &str) -> Option<SurfaceKind> {
        SurfaceKind::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(s))
    }
}

/// What an `inkscape:label` says an element is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Surface(SurfaceKind),
    Fixed,
    Movable,
    Puck(PuckKind),
    Robot,
    Mark,
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

/// Classifies a label: the last dot-separated part, case-insensitively.
fn classify(label: &str) -> Option<Class> {
    let last = label
        .trim()
        .rsplit('.')
        .next()
        .unwrap_or("")
        .to_ascii_lowercase();
    if let Some(k) = SurfaceKind::from_name(&last) {
        return Some(Class::Surface(k));
    }
    match last.as_str() {
        "fixedobstacle" | "fixed" => Some(Class::Fixed),
        "obstacle" => Some(Class::Movable),
        "smallpuck" => Some(Class::Puck(PuckKind::Small)),
        "bigpuck" => Some(Class::Puck(PuckKind::Big)),
        "puck" => Some(Class::Puck(PuckKind::Plain)),
        "positionmark" => Some(Class::Mark),
        s if s.contains("robot") => Some(Class::Robot),
        _ => None,
    }
}

/// Options for [`Scenario::from_svg`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LoadOptions {
    /// Side of one surface-raster cell in px (default 1).
    pub cell_size: f64,
    /// Largest accepted arena width or height in px (default 20 000).
    pub max_arena_size: f64,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            cell_size: 1.0,
            max_arena_size: 20_000.0,
        }
    }
}

/// Why a scenario could not be loaded. Every variant names the source file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScenarioError {
    /// The bytes are not UTF-8 text.
    #[error("{source_name}: not UTF-8 text")]
    NotUtf8 {
        /// File name.
        source_name: String,
    },
    /// The text is not well-formed XML.
    #[error("{source_name}: not XML: {message}")]
    Xml {
        /// File name.
        source_name: String,
        /// Parser message with position.
        message: String,
    },
    /// The XML root is not `<svg>`.
    #[error("{source_name}: not an SVG document (root element is <{root}>)")]
    NotSvg {
        /// File name.
        source_name: String,
        /// The root element's name.
        root: String,
    },
    /// The arena is zero, negative, not a number or absurdly large.
    #[error("{source_name}: bad arena size {width} x {height}: {problem}")]
    ArenaSize {
        /// File name.
        source_name: String,
        /// Width in px (0 when unreadable).
        width: f64,
        /// Height in px (0 when unreadable).
        height: f64,
        /// What is wrong.
        problem: String,
    },
    /// An element's `d` attribute cannot be parsed.
    #[error("{source_name}: element '{id}': malformed path data: {message}")]
    PathData {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Parser message.
        message: String,
    },
    /// An attribute has a value the loader cannot use.
    #[error("{source_name}: element '{id}': bad attribute {attribute}=\"{value}\"")]
    Attribute {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Attribute name.
        attribute: String,
        /// The offending value.
        value: String,
    },
    /// A robot's start position is outside the arena.
    #[error(
        "{source_name}: robot '{id}' at ({x:.1}, {y:.1}) is outside the {width} x {height} arena"
    )]
    RobotOutsideArena {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Position x.
        x: f64,
        /// Position y.
        y: f64,
        /// Arena width.
        width: f64,
        /// Arena height.
        height: f64,
    },
    /// The scenario has no robot, but the caller needs robots.
    #[error("{source_name}: no robots (label an element e.g. 'Robot' to place one)")]
    NoRobots {
        /// File name.
        source_name: String,
    },
    /// usvg rejected the document.
    #[error("{source_name}: invalid SVG: {message}")]
    Svg {
        /// File name.
        source_name: String,
        /// usvg's message.
        message: String,
    },
    /// More than 256 distinct surface materials (kind + friction override).
    #[error("{source_name}: more than 256 distinct surface frictions")]
    TooManyMaterials {
        /// File name.
        source_name: String,
    },
    /// The load options are invalid.
    #[error("invalid load option {field} = {value}")]
    Options {
        /// Field name.
        field: &'static str,
        /// Its value.
        value: f64,
    },
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
}

/// A loaded scenario: the arena and everything in it, plus the surface raster.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// Source file name (for messages).
    pub source: String,
    /// Arena width in px.
    pub width: f64,
    /// Arena height in px.
    pub height: f64,
    /// Surface of points covered by no surface shape.
    pub background: SurfaceKind,
    /// Surfaces in document order (later ones cover earlier ones).
    pub surfaces: Vec<Surface>,
    /// Distinct (kind, friction override) pairs; index 0 is the background.
    /// The raster stores indices into this list.
    pub materials: Vec<(SurfaceKind, Option<f64>)>,
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
    /// Non-fatal problems (unknown labels, elements without geometry).
    pub warnings: Vec<String>,
    /// Surface ids on a grid, built once at load.
    pub raster: Arc<SurfaceRaster>,
}

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
        Loader::load(text, source, opts)
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

/// Geometry usvg resolved for one element id.
enum Resolved<'a> {
    Path(&'a usvg::Path),
    Group(&'a usvg::Group),
}

struct Loader<'a> {
    source: &'a str,
    ids: BTreeMap<String, Resolved<'a>>,
    sc: Scenario,
}

fn collect_ids<'a>(g: &'a usvg::Group, out: &mut BTreeMap<String, Resolved<'a>>) {
    for n in g.children() {
        match n {
            usvg::Node::Path(p) if !p.id().is_empty() => {
                out.entry(p.id().to_string()).or_insert(Resolved::Path(p));
            }
            usvg::Node::Group(c) => {
                if !c.id().is_empty() {
                    out.entry(c.id().to_string()).or_insert(Resolved::Group(c));
                }
                collect_ids(c, out);
            }
            _ => {}
        }
    }
}

fn is_shape(name: &str) -> bool {
    matches!(
        name,
        "rect" | "circle" | "ellipse" | "line" | "polyline" | "polygon" | "path"
    )
}

const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";

fn label_of<'a>(n: roxmltree::Node<'a, 'a>) -> Option<&'a str> {
    n.attribute((INKSCAPE_NS, "label"))
        .filter(|l| !l.trim().is_empty())
}

fn hidden(n: roxmltree::Node) -> bool {
    n.attribute("display") == Some("none")
        || n.attribute("style").is_some_and(|s| {
            s.split(';')
                .any(|d| d.replace(' ', "").eq_ignore_ascii_case("display:none"))
        })
}

fn map_point(ts: tiny_skia::Transform, p: DVec2) -> DVec2 {
    let mut q = tiny_skia::Point::from_xy(p.x as f32, p.y as f32);
    ts.map_point(&mut q);
    DVec2::new(q.x as f64, q.y as f64)
}

/// Heading of the local "up" direction under `ts` (0 = up, clockwise).
fn heading_of(ts: tiny_skia::Transform) -> f64 {
    let h = libm::atan2(-(ts.kx as f64), ts.sy as f64);
    if h.abs() < 1e-6 { 0.0 } else { h }
}

/// Area geometry of a usvg path: its fill, else its stroke outline, else its outline.
fn path_shape(p: &usvg::Path) -> Shape {
    let ts = p.abs_transform();
    if p.fill().is_none()
        && let Some(stroke) = p.stroke()
    {
        let (sx, sy) = ts.get_scale();
        let res = (sx * sy).abs().sqrt().max(1e-3);
        if let Some(outline) = p.data().stroke(&stroke.to_tiny_skia(), res) {
            return Shape::new(
                flatten_path(&outline, ts, FLATTEN_TOLERANCE),
                FillRule::NonZero,
            );
        }
    }
    let rule = match p.fill().map(|f| f.rule()) {
        Some(usvg::FillRule::EvenOdd) => FillRule::EvenOdd,
        _ => FillRule::NonZero,
    };
    Shape::new(flatten_path(p.data(), ts, FLATTEN_TOLERANCE), rule)
}

impl<'a> Loader<'a> {
    fn load(text: &str, source: &str, opts: &LoadOptions) -> Result<Scenario, ScenarioError> {
        if !(opts.cell_size.is_finite() && opts.cell_size > 0.0) {
            return Err(ScenarioError::Options {
                field: "cell_size",
                value: opts.cell_size,
            });
        }
        if !(opts.max_arena_size.is_finite() && opts.max_arena_size > 0.0) {
            return Err(ScenarioError::Options {
                field: "max_arena_size",
                value: opts.max_arena_size,
            });
        }
        let err_src = || source.to_string();
        let doc = roxmltree::Document::parse_with_options(
            text,
            roxmltree::ParsingOptions {
                allow_dtd: true,
                ..Default::default()
            },
        )
        .map_err(|e| ScenarioError::Xml {
            source_name: err_src(),
            message: e.to_string(),
        })?;
        let root = doc.root_element();
        if root.tag_name().name() != "svg" {
            return Err(ScenarioError::NotSvg {
                source_name: err_src(),
                root: root.tag_name().name().to_string(),
            });
        }
        // Validate all path data before usvg, which silently truncates bad paths.
        for n in doc
            .descendants()
            .filter(|n| n.is_element() && n.tag_name().name() == "path")
        {
            if let Some(d) = n.attribute("d") {
                for seg in svgtypes::PathParser::from(d) {
                    if let Err(e) = seg {
                        return Err(ScenarioError::PathData {
                            source_name: err_src(),
                            id: n.attribute("id").unwrap_or("(no id)").to_string(),
                            message: e.to_string(),
                        });
                    }
                }
            }
        }
        let tree =
            usvg::Tree::from_xmltree(&doc, &usvg::Options::default()).map_err(|e| match e {
                usvg::Error::InvalidSize => ScenarioError::ArenaSize {
                    source_name: err_src(),
                    width: 0.0,
                    height: 0.0,
                    problem: "width and height (or viewBox) must be positive".into(),
                },
                e => ScenarioError::Svg {
                    source_name: err_src(),
                    message: e.to_string(),
                },
            })?;
        let (width, height) = (tree.size().width() as f64, tree.size().height() as f64);
        if !(width.is_finite() && height.is_finite() && width >= 1.0 && height >= 1.0) {
            return Err(ScenarioError::ArenaSize {
                source_name: err_src(),
                width,
                height,
                problem: "must be at least 1 px each way".into(),
            });
        }
        if width > opts.max_arena_size || height > opts.max_arena_size {
            return Err(ScenarioError::ArenaSize {
                source_name: err_src(),
                width,
                height,
                problem: format!("larger than the limit of {} px", opts.max_arena_size),
            });
        }
        let background = match root.attribute("data-background") {
            None => SurfaceKind::Grass,
            Some(v) => {
                SurfaceKind::from_name(v.trim()).ok_or_else(|| ScenarioError::Attribute {
                    source_name: err_src(),
                    id: root.attribute("id").unwrap_or("svg").to_string(),
                    attribute: "data-background".into(),
                    value: v.into(),
                })?
            }
        };
        let mut ids = BTreeMap::new();
        collect_ids(tree.root(), &mut ids);
        let mut loader = Loader {
            source,
            ids,
            sc: Scenario {
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
                warnings: Vec::new(),
                raster: Arc::new(SurfaceRaster::empty()),
            },
        };
        for c in root.children().filter(|c| c.is_element()) {
            loader.walk(c, None)?;
        }
        let mut sc = loader.sc;
        for r in &sc.robots {
            if !(r.pos.x >= 0.0 && r.pos.y >= 0.0 && r.pos.x <= width && r.pos.y <= height) {
                return Err(ScenarioError::RobotOutsideArena {
                    source_name: err_src(),
                    id: r.id.clone(),
                    x: r.pos.x,
                    y: r.pos.y,
                    width,
                    height,
                });
            }
        }
        // Materials: distinct (kind, friction override) pairs; the raster stores one byte each.
        let mut ids = Vec::with_capacity(sc.surfaces.len());
        for s in &sc.surfaces {
            let key = (s.kind, s.friction);
            let m = match sc.materials.iter().position(|k| *k == key) {
                Some(m) => m,
                None => {
                    sc.materials.push(key);
                    sc.materials.len() - 1
                }
            };
            if m > u8::MAX as usize {
                return Err(ScenarioError::TooManyMaterials {
                    source_name: err_src(),
                });
            }
            ids.push(m as u8);
        }
        sc.raster = Arc::new(SurfaceRaster::build(
            width,
            height,
            opts.cell_size,
            &sc.surfaces,
            &ids,
        ));
        Ok(sc)
    }

    fn warn(&mut self, msg: String) {
        self.sc.warnings.push(msg);
    }

    /// Walks one element; `inherited` is the class of the nearest labelled group.
    fn walk(
        &mut self,
        n: roxmltree::Node<'a, 'a>,
        inherited: Option<(Class, roxmltree::Node<'a, 'a>)>,
    ) -> Result<(), ScenarioError> {
        if hidden(n) {
            return Ok(());
        }
        let name = n.tag_name().name();
        let id = n.attribute("id").unwrap_or("(no id)");
        let own = label_of(n);
        let own_class = own.and_then(classify);
        let is_container = matches!(name, "g" | "a" | "switch");
        if is_container {
            if n.attribute((INKSCAPE_NS, "groupmode")) == Some("layer") {
                // Layer names ("Layer 1", "Pozadí") are not objects.
                for c in n.children().filter(|c| c.is_element()) {
                    self.walk(c, inherited)?;
                }
                return Ok(());
            }
            if let (Some(l), None) = (own, own_class)
                && inherited.is_none()
            {
                self.warn(format!(
                    "{}: element '{id}': unknown label '{l}', ignored",
                    self.source
                ));
            }
            if matches!(own_class, Some(Class::Robot) | Some(Class::Mark)) {
                // A robot or mark drawn as a group is one object.
                return self.add_object(n, own_class.unwrap_or(Class::Mark), n);
            }
            let next = own_class.map(|c| (c, n)).or(inherited);
            for c in n.children().filter(|c| c.is_element()) {
                self.walk(c, next)?;
            }
            return Ok(());
        }
        if is_shape(name) {
            let class = match (own_class, inherited) {
                (Some(c), _) => Some((c, n)),
                (None, Some(inh)) => Some(inh),
                (None, None) => {
                    if let Some(l) = own {
                        self.warn(format!(
                            "{}: element '{id}': unknown label '{l}', ignored",
                            self.source
                        ));
                    }
                    None
                }
            };
            if let Some((c, owner)) = class {
                self.add_object(n, c, owner)?;
            }
            return Ok(());
        }
        if let Some(l) = own
            && own_class.is_some()
        {
            self.warn(format!(
                "{}: element '{id}' (label '{l}'): <{name}> is not a supported shape, ignored",
                self.source
            ));
        }
        Ok(())
    }

    /// Shapes (with transforms) of an element: itself if a shape, else its descendant shapes.
    fn shapes_of(&self, n: roxmltree::Node<'a, 'a>) -> Vec<(&'a usvg::Path, Shape)> {
        let mut out = Vec::new();
        for d in n
            .descendants()
            .filter(|d| d.is_element() && is_shape(d.tag_name().name()))
        {
            if d.ancestors().any(hidden) {
                continue;
            }
            if let Some(Resolved::Path(p)) = d.attribute("id").and_then(|id| self.ids.get(id)) {
                let shape = path_shape(p);
                out.push((*p, shape));
            }
        }
        out
    }

    fn add_object(
        &mut self,
        n: roxmltree::Node<'a, 'a>,
        class: Class,
        owner: roxmltree::Node<'a, 'a>,
    ) -> Result<(), ScenarioError> {
        let id = n.attribute("id").unwrap_or("(no id)").to_string();
        let shapes = self.shapes_of(n);
        let mut bbox = Aabb::EMPTY;
        for (_, s) in &shapes {
            if !s.bbox.is_empty() {
                bbox.include(s.bbox.min);
                bbox.include(s.bbox.max);
            }
        }
        let label = label_of(n)
            .or_else(|| label_of(owner))
            .unwrap_or("")
            .to_string();
        if shapes.is_empty() || (bbox.is_empty() && !matches!(class, Class::Robot | Class::Mark)) {
            self.warn(format!(
                "{}: element '{id}' (label '{label}') has no usable geometry, ignored",
                self.source
            ));
            return Ok(());
        }
        match class {
            Class::Surface(kind) => {
                let friction = self.friction_of(n, owner)?;
                let (_, shape) = shapes.into_iter().next().expect("checked non-empty");
                if shape.is_empty() {
                    self.warn(format!(
                        "{}: element '{id}' (label '{label}') has no area, ignored",
                        self.source
                    ));
                } else {
                    self.sc.surfaces.push(Surface {
                        id,
                        kind,
                        friction,
                        shape,
                    });
                }
            }
            Class::Fixed | Class::Movable => {
                let (_, shape) = shapes.into_iter().next().expect("checked non-empty");
                if shape.is_empty() || shape.area() <= 0.0 {
                    self.warn(format!(
                        "{}: element '{id}' (label '{label}') has no area, ignored",
                        self.source
                    ));
                } else if class == Class::Fixed {
                    self.sc.fixed_obstacles.push(Obstacle { id, shape });
                } else {
                    self.sc.movable_obstacles.push(Obstacle { id, shape });
                }
            }
            Class::Puck(kind) => {
                let size = bbox.size();
                let radius = (size.x + size.y) * 0.25;
                if radius > 0.0 {
                    self.sc.pucks.push(Puck {
                        id,
                        kind,
                        pos: bbox.center(),
                        radius,
                    });
                } else {
                    self.warn(format!(
                        "{}: element '{id}' (label '{label}') has zero size, ignored",
                        self.source
                    ));
                }
            }
            Class::Mark => {
                let (pos, _) = self.pose(n, &shapes, bbox);
                self.sc.marks.push(Mark {
                    id,
                    pos,
                    size: bbox.size(),
                });
            }
            Class::Robot => {
                let (pos, heading) = self.pose(n, &shapes, bbox);
                self.sc.robots.push(RobotStart {
                    id,
                    label,
                    pos,
                    heading,
                });
            }
        }
        Ok(())
    }

    /// Position (local bounding-box centre under the element's transform) and heading.
    fn pose(
        &self,
        n: roxmltree::Node<'a, 'a>,
        shapes: &[(&'a usvg::Path, Shape)],
        bbox: Aabb,
    ) -> (DVec2, f64) {
        if shapes.len() == 1 && n.attribute("id").and_then(|i| self.ids.get(i)).is_some() {
            let p = shapes[0].0;
            let b = p.bounding_box();
            let local = DVec2::new(
                (b.left() + b.right()) as f64 * 0.5,
                (b.top() + b.bottom()) as f64 * 0.5,
            );
            let ts = p.abs_transform();
            return (map_point(ts, local), heading_of(ts));
        }
        let ts = match n.attribute("id").and_then(|i| self.ids.get(i)) {
            Some(Resolved::Group(g)) => g.abs_transform(),
            Some(Resolved::Path(p)) => p.abs_transform(),
            None => shapes
                .first()
                .map(|s| s.0.abs_transform())
                .unwrap_or_default(),
        };
        (bbox.center(), heading_of(ts))
    }

    fn friction_of(
        &self,
        n: roxmltree::Node<'a, 'a>,
        owner: roxmltree::Node<'a, 'a>,
    ) -> Result<Option<f64>, ScenarioError> {
        let attr = n
            .attribute("data-friction")
            .map(|v| (n, v))
            .or_else(|| owner.attribute("data-friction").map(|v| (owner, v)));
        match attr {
            None => Ok(None),
            Some((e, v)) => match v.trim().parse::<f64>() {
                Ok(f) if f.is_finite() && f >= 0.0 => Ok(Some(f)),
                _ => Err(ScenarioError::Attribute {
                    source_name: self.source.to_string(),
                    id: e.attribute("id").unwrap_or("(no id)").to_string(),
                    attribute: "data-friction".into(),
                    value: v.to_string(),
                }),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_classify_by_last_dotted_part_case_insensitively() {
        assert_eq!(classify("Road"), Some(Class::Surface(SurfaceKind::Road)));
        assert_eq!(classify("road"), Some(Class::Surface(SurfaceKind::Road)));
        assert_eq!(
            classify("vivae.arena.parts.PositionMark"),
            Some(Class::Mark)
        );
        assert_eq!(classify("fixed"), Some(Class::Fixed));
        assert_eq!(
            classify("hyper.experiments.robots.friction.NetControlledRobotFriction"),
            Some(Class::Robot)
        );
        assert_eq!(
            classify("vivae.example.FRNNControlledRobot"),
            Some(Class::Robot)
        );
        assert_eq!(classify("Layer 1"), None);
        assert_eq!(classify("SmallPuck"), Some(Class::Puck(PuckKind::Small)));
    }

    #[test]
    fn headings_normalise_to_degrees() {
        assert_eq!(heading_degrees(0.0), 0.0);
        assert!((heading_degrees(-std::f64::consts::FRAC_PI_2) - 270.0).abs() < 1e-9);
    }
}

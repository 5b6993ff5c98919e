//! Loading ViVAE scenario files (SVG drawn in Inkscape).
//!
//! roxmltree reads the raw document (labels, layers, document order, custom
//! attributes); usvg resolves shapes, arcs, CSS, units, the `viewBox` and every
//! ancestor transform into absolute paths. The two are joined by element `id`.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::DVec2;

use crate::geometry::{Aabb, FillRule, Shape, flatten_path};
use crate::raster::SurfaceRaster;

use super::episodic::{self, TrafficStart};
use super::ids::{is_shape, unique_ids};
use super::labels::{Class, classify, surface_kind};
use super::limits::*;
use super::{
    Mark, Obstacle, Puck, PuckKind, RobotStart, Scenario, ScenarioError, Surface, SurfaceKind,
};

/// Flattening tolerance for curves, in px.
const FLATTEN_TOLERANCE: f64 = 0.1;

/// Geometry usvg resolved for one element id.
enum Resolved<'a> {
    Path(&'a usvg::Path),
    Group(&'a usvg::Group),
}

pub(super) struct Loader<'a> {
    source: &'a str,
    /// The user's name for each id the loader invented (see `ids.rs`).
    display: BTreeMap<String, String>,
    ids: BTreeMap<String, Resolved<'a>>,
    /// Geometry reaching beyond this box is refused.
    limit: Aabb,
    sc: Scenario,
    /// The route id each robot names (`data-route`) and each scripted robot
    /// follows (`data-traffic`), resolved at the end.
    route_names: (Vec<Option<String>>, Vec<String>),
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

/// Bounding box of a path's control points under `ts`, grown by `pad` (cheap:
/// no flattening), or `None` when a coordinate is not finite.
fn control_box(p: &tiny_skia::Path, ts: tiny_skia::Transform, pad: f64) -> Option<Aabb> {
    let mut b = Aabb::EMPTY;
    for pt in p.points() {
        let q = map_point(ts, DVec2::new(pt.x as f64, pt.y as f64));
        if !(q.x.is_finite() && q.y.is_finite()) {
            return None;
        }
        b.include(q - DVec2::splat(pad));
        b.include(q + DVec2::splat(pad));
    }
    Some(b)
}

/// Area geometry of a usvg path: its fill, else its stroke outline, else its
/// outline; `Err` with the furthest reach when it extends far outside `limit`.
fn path_shape(p: &usvg::Path, limit: &Aabb) -> Result<Shape, Aabb> {
    let ts = p.abs_transform();
    let stroked = p.fill().is_none() && p.stroke().is_some();
    let (sx, sy) = ts.get_scale();
    let pad = match p.stroke() {
        Some(s) if stroked => s.width().get() as f64 * (sx.abs().max(sy.abs()) as f64),
        _ => 0.0,
    };
    // Refused before stroking or flattening, whose cost grows with size.
    match control_box(p.data(), ts, pad) {
        Some(b)
            if b.is_empty()
                || (limit.contains_with_margin(b.min, 0.0)
                    && limit.contains_with_margin(b.max, 0.0)) => {}
        Some(b) => return Err(b),
        None => {
            return Err(Aabb {
                min: DVec2::splat(f64::NAN),
                max: DVec2::splat(f64::NAN),
            });
        }
    }
    if stroked && let Some(stroke) = p.stroke() {
        let res = (sx * sy).abs().sqrt().max(1e-3);
        if let Some(outline) = p.data().stroke(&stroke.to_tiny_skia(), res) {
            return Ok(Shape::new(
                flatten_path(&outline, ts, FLATTEN_TOLERANCE),
                FillRule::NonZero,
            ));
        }
    }
    let rule = match p.fill().map(|f| f.rule()) {
        Some(usvg::FillRule::EvenOdd) => FillRule::EvenOdd,
        _ => FillRule::NonZero,
    };
    Ok(Shape::new(
        flatten_path(p.data(), ts, FLATTEN_TOLERANCE),
        rule,
    ))
}

/// Each surface's material id, adding the distinct (kind, friction override)
/// pairs to `sc.materials`; the raster stores one byte each.
fn material_ids(sc: &mut Scenario, source: &str) -> Result<Vec<u8>, ScenarioError> {
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
                source_name: source.to_string(),
            });
        }
        ids.push(m as u8);
    }
    Ok(ids)
}

/// usvg's tree of the (checked) document.
fn usvg_tree(doc: &roxmltree::Document, source: &str) -> Result<usvg::Tree, ScenarioError> {
    let err_src = || source.to_string();
    usvg::Tree::from_xmltree(doc, &usvg::Options::default()).map_err(|e| match e {
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
    })
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

impl<'a> Loader<'a> {
    pub(super) fn load(
        text: &str,
        source: &str,
        opts: &LoadOptions,
    ) -> Result<Scenario, ScenarioError> {
        check_options(opts)?;
        let err_src = || source.to_string();
        prescan(text, source)?;
        let parse = |text| {
            roxmltree::Document::parse_with_options(
                text,
                roxmltree::ParsingOptions {
                    allow_dtd: true,
                    nodes_limit: MAX_XML_NODES,
                    ..Default::default()
                },
            )
            .map_err(|e| ScenarioError::Xml {
                source_name: err_src(),
                message: e.to_string(),
            })
        };
        let doc = parse(text)?;
        // The join with usvg is by id: give every element its own first.
        let rewritten = unique_ids(&doc, text, source)?;
        let (doc, display) = match &rewritten {
            Some(u) => (parse(&u.text)?, u.display.clone()),
            None => (doc, BTreeMap::new()),
        };
        let root = doc.root_element();
        if root.tag_name().name() != "svg" {
            return Err(ScenarioError::NotSvg {
                source_name: err_src(),
                root: root.tag_name().name().to_string(),
            });
        }
        check_root_size(root, source, opts.max_arena_size)?;
        // Validate all path data before usvg, which silently truncates bad paths.
        check_path_data(&doc, &display, source)?;
        let tree = usvg_tree(&doc, source)?;
        let (width, height) = (tree.size().width() as f64, tree.size().height() as f64);
        check_arena_size(width, height, opts, source)?;
        let background = match root.attribute("data-background") {
            None => SurfaceKind::Grass,
            Some(v) => surface_kind(v.trim()).ok_or_else(|| ScenarioError::Attribute {
                source_name: err_src(),
                id: root.attribute("id").unwrap_or("svg").to_string(),
                attribute: "data-background".into(),
                value: v.into(),
            })?,
        };
        let mut ids = BTreeMap::new();
        collect_ids(tree.root(), &mut ids);
        let reach = MAX_OUTSIDE_ARENAS * width.max(height);
        let mut loader = Loader {
            source,
            display,
            ids,
            limit: Aabb {
                min: DVec2::splat(-reach),
                max: DVec2::new(width + reach, height + reach),
            },
            sc: empty_scenario(source, width, height, background),
            route_names: Default::default(),
        };
        for c in root.children().filter(|c| c.is_element()) {
            loader.walk(c, None)?;
        }
        let (mut sc, (robots, traffic)) = (loader.sc, loader.route_names);
        episodic::resolve_routes(&mut sc, &robots, &traffic)?;
        check_robots_inside(&sc, source)?;
        let ids = material_ids(&mut sc, source)?;
        sc.raster = Arc::new(SurfaceRaster::build(
            width,
            height,
            opts.cell_size,
            sc.surfaces.iter().map(|s| &s.shape).zip(ids),
        ));
        Ok(sc)
    }

    /// The element's id as the user wrote it (or where it is, if it had none).
    fn name_of(&self, n: roxmltree::Node) -> String {
        match n.attribute("id") {
            Some(id) => self
                .display
                .get(id)
                .cloned()
                .unwrap_or_else(|| id.to_string()),
            None => "(no id)".to_string(),
        }
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
        let id = self.name_of(n);
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
    fn shapes_of(
        &self,
        n: roxmltree::Node<'a, 'a>,
    ) -> Result<Vec<(&'a usvg::Path, Shape)>, ScenarioError> {
        let mut out = Vec::new();
        for d in n
            .descendants()
            .filter(|d| d.is_element() && is_shape(d.tag_name().name()))
        {
            if d.ancestors().any(hidden) {
                continue;
            }
            if let Some(Resolved::Path(p)) = d.attribute("id").and_then(|id| self.ids.get(id)) {
                let shape =
                    path_shape(p, &self.limit).map_err(|reach| ScenarioError::FarOutside {
                        source_name: self.source.to_string(),
                        id: self.name_of(d),
                        min_x: reach.min.x,
                        min_y: reach.min.y,
                        max_x: reach.max.x,
                        max_y: reach.max.y,
                    })?;
                out.push((*p, shape));
            }
        }
        Ok(out)
    }

    fn add_object(
        &mut self,
        n: roxmltree::Node<'a, 'a>,
        class: Class,
        owner: roxmltree::Node<'a, 'a>,
    ) -> Result<(), ScenarioError> {
        let id = self.name_of(n);
        let shapes = self.shapes_of(n)?;
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
                self.add_surface(
                    Surface {
                        id,
                        kind,
                        friction,
                        shape,
                    },
                    &label,
                );
            }
            Class::Fixed | Class::Movable => {
                let (_, shape) = shapes.into_iter().next().expect("checked non-empty");
                self.add_obstacle(class == Class::Fixed, Obstacle { id, shape }, &label);
            }
            Class::Puck(kind) => self.add_puck(kind, id, &label, bbox),
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
                let team = self.team_of(n, owner)?;
                self.add_robot(
                    n,
                    RobotStart {
                        id,
                        label,
                        pos,
                        heading,
                        route: None,
                        team,
                    },
                )?;
            }
            Class::Region => {
                let (_, shape) = shapes.into_iter().next().expect("checked non-empty");
                let attr = |k: &str| n.attribute(k).or_else(|| owner.attribute(k));
                let region = episodic::region(self.source, id, shape, attr)?;
                self.sc.obstacle_regions.push(region);
            }
            Class::Route => self.add_route(id, &shapes),
        }
        Ok(())
    }

    /// Adds a learner, or a scripted robot when it names a route to follow
    /// (`data-traffic`).
    fn add_robot(
        &mut self,
        n: roxmltree::Node<'a, 'a>,
        start: RobotStart,
    ) -> Result<(), ScenarioError> {
        let Some(route) = n.attribute("data-traffic") else {
            self.route_names
                .0
                .push(n.attribute("data-route").map(str::to_string));
            self.sc.robots.push(start);
            return Ok(());
        };
        let (throttle, spread) =
            episodic::traffic_settings(self.source, &start.id, |k| n.attribute(k))?;
        self.route_names.1.push(route.to_string());
        self.sc.traffic.push(TrafficStart {
            id: start.id,
            pos: start.pos,
            heading: start.heading,
            route: usize::MAX,
            throttle,
            spread,
        });
        Ok(())
    }

    /// Adds a route along the first shape's centre line (not its stroke).
    fn add_route(&mut self, id: String, shapes: &[(&'a usvg::Path, Shape)]) {
        let p = shapes[0].0;
        let closed = p
            .data()
            .segments()
            .any(|s| matches!(s, tiny_skia::PathSegment::Close));
        let line = flatten_path(p.data(), p.abs_transform(), FLATTEN_TOLERANCE);
        match line
            .first()
            .and_then(|pts| super::Route::new(id.clone(), pts, closed))
        {
            Some(r) => self.sc.routes.push(r),
            None => self.warn(format!(
                "{}: route '{id}' has no length, ignored",
                self.source
            )),
        }
    }

    /// Adds `surface`, or warns (labelled `label`) when it has no area.
    fn add_surface(&mut self, surface: Surface, label: &str) {
        if surface.shape.is_empty() {
            self.warn(format!(
                "{}: element '{}' (label '{label}') has no area, ignored",
                self.source, surface.id
            ));
        } else {
            self.sc.surfaces.push(surface);
        }
    }

    /// Adds a fixed or movable obstacle, or warns when it has no area.
    fn add_obstacle(&mut self, fixed: bool, ob: Obstacle, label: &str) {
        if ob.shape.is_empty() || ob.shape.area() <= 0.0 {
            self.warn(format!(
                "{}: element '{}' (label '{label}') has no area, ignored",
                self.source, ob.id
            ));
        } else if fixed {
            self.sc.fixed_obstacles.push(ob);
        } else {
            self.sc.movable_obstacles.push(ob);
        }
    }

    /// Adds a puck filling `bbox` (radius: the mean half-side), or warns when
    /// it has zero size.
    fn add_puck(&mut self, kind: PuckKind, id: String, label: &str, bbox: Aabb) {
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
                    id: self.name_of(e),
                    attribute: "data-friction".into(),
                    value: v.to_string(),
                }),
            },
        }
    }

    /// A robot's team: `data-team` on the element or its labelled group
    /// (letters, digits, `-` and `_`), or empty for a robot of no team.
    fn team_of(
        &self,
        n: roxmltree::Node<'a, 'a>,
        owner: roxmltree::Node<'a, 'a>,
    ) -> Result<String, ScenarioError> {
        let attr = n
            .attribute("data-team")
            .map(|v| (n, v))
            .or_else(|| owner.attribute("data-team").map(|v| (owner, v)));
        let Some((e, v)) = attr else {
            return Ok(String::new());
        };
        let team = v.trim();
        let ok = !team.is_empty()
            && team.len() <= 64
            && team
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if ok {
            Ok(team.to_string())
        } else {
            Err(ScenarioError::Attribute {
                source_name: self.source.to_string(),
                id: self.name_of(e),
                attribute: "data-team".into(),
                value: v.to_string(),
            })
        }
    }
}

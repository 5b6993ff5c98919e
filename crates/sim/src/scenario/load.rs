//! Loading ViVAE scenario files (SVG drawn in Inkscape).
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

use super::ids::{is_shape, unique_ids};
use super::labels::{Class, classify, surface_kind};
use super::{
    Mark, Obstacle, Puck, PuckKind, RobotStart, Scenario, ScenarioError, Surface, SurfaceKind,
};

/// Flattening tolerance for curves, in px.
const FLATTEN_TOLERANCE: f64 = 0.1;

/// Largest magnitude of a number in path data: beyond it usvg's arc
/// conversion can run for minutes (an endpoint of 3.4e38 never finishes).
const MAX_PATH_NUMBER: f64 = 1e9;

/// How far (in arena sizes) geometry may reach outside the arena: further out
/// it cannot matter, and flattening it could take unbounded time and memory.
const MAX_OUTSIDE_ARENAS: f64 = 4.0;

/// Most XML nodes a scenario may have (the shipped ones have a few thousand).
const MAX_XML_NODES: u32 = 200_000;

/// Most attributes one element may have (roxmltree's duplicate check is quadratic).
const MAX_ATTRIBUTES: usize = 1_000;

/// Options for [`Scenario::from_svg`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LoadOptions {
    /// Side of one surface-raster cell in px (default 1).
    pub cell_size: f64,
    /// Largest accepted arena width or height in px (default 20 000).
    pub max_arena_size: f64,
    /// Largest accepted arena area in px² (default 10⁸: a 100 MB surface
    /// raster at 1 px cells, the memory a run needs for it).
    pub max_arena_area: f64,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            cell_size: 1.0,
            max_arena_size: 20_000.0,
            max_arena_area: 1e8,
        }
    }
}

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

/// Refuses what would make parsing slow or huge before roxmltree sees it:
/// entity declarations (a small file can expand to gigabytes) and elements
/// with too many attributes.
fn prescan(text: &str, source: &str) -> Result<(), ScenarioError> {
    let refuse = |message: String| ScenarioError::Svg {
        source_name: source.to_string(),
        message,
    };
    if text.contains("<!ENTITY") {
        return Err(refuse(
            "entity declarations (<!ENTITY>) are not supported".into(),
        ));
    }
    // Counts `=` outside quoted values within each tag: an upper bound on attributes.
    let (mut in_tag, mut quote, mut count) = (false, 0u8, 0usize);
    for &b in text.as_bytes() {
        if quote != 0 {
            if b == quote {
                quote = 0;
            }
            continue;
        }
        match b {
            b'<' => {
                in_tag = true;
                count = 0;
            }
            b'>' => in_tag = false,
            b'"' | b'\'' if in_tag => quote = b,
            b'=' if in_tag => {
                count += 1;
                if count > MAX_ATTRIBUTES {
                    return Err(refuse(format!(
                        "an element has more than {MAX_ATTRIBUTES} attributes"
                    )));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Reads the root's `width`, `height` and `viewBox` as written, refusing
/// values usvg would silently replace (`inf`, `100%`, an empty `viewBox`) or
/// overflow (`1e308` does not fit an f32).
fn check_root_size(root: roxmltree::Node, source: &str, max: f64) -> Result<(), ScenarioError> {
    let bad = |attribute: &'static str, value: &str, problem: &str| ScenarioError::RootSize {
        source_name: source.to_string(),
        attribute,
        value: value.to_string(),
        problem: problem.to_string(),
    };
    let mut size = [0.0; 2];
    for (i, attribute) in ["width", "height"].into_iter().enumerate() {
        let Some(v) = root.attribute(attribute) else {
            continue;
        };
        let length: svgtypes::Length = v
            .trim()
            .parse()
            .map_err(|_| bad(attribute, v, "not a length"))?;
        if length.unit == svgtypes::LengthUnit::Percent {
            return Err(bad(attribute, v, "percentages are not supported, give px"));
        }
        if !length.number.is_finite() {
            return Err(bad(attribute, v, "not a finite number"));
        }
        size[i] = length.number;
    }
    // Units (mm, in, pt) scale by at most 96/2.54·10 px: a generous bound
    // before the f32 overflow that usvg would report as "0 x 0".
    for (i, attribute) in ["width", "height"].into_iter().enumerate() {
        let problem = if root.attribute(attribute).is_some() && size[i] <= 0.0 {
            "width and height must be positive".to_string()
        } else if size[i] > max * 100.0 {
            format!("larger than the limit of {max} px")
        } else {
            continue;
        };
        return Err(ScenarioError::ArenaSize {
            source_name: source.to_string(),
            width: size[0],
            height: size[1],
            problem,
        });
    }
    if let Some(v) = root.attribute("viewBox") {
        let nums: Vec<f64> = svgtypes::NumberListParser::from(v)
            .collect::<Result<_, _>>()
            .map_err(|_| bad("viewBox", v, "not four numbers"))?;
        match nums[..] {
            [x, y, w, h] if [x, y, w, h].iter().all(|n| n.is_finite() && n.abs() < 1e9) => {
                if w <= 0.0 || h <= 0.0 {
                    return Err(bad("viewBox", v, "width and height must be positive"));
                }
            }
            [_, _, _, _] => return Err(bad("viewBox", v, "numbers out of range")),
            _ => return Err(bad("viewBox", v, "not four numbers")),
        }
    }
    Ok(())
}

/// Refuses load options that are not finite and positive.
fn check_options(opts: &LoadOptions) -> Result<(), ScenarioError> {
    if !(opts.cell_size.is_finite() && opts.cell_size > 0.0) {
        return Err(ScenarioError::Options {
            field: "cell_size",
            value: opts.cell_size,
        });
    }
    if !(opts.max_arena_area.is_finite() && opts.max_arena_area > 0.0) {
        return Err(ScenarioError::Options {
            field: "max_arena_area",
            value: opts.max_arena_area,
        });
    }
    if !(opts.max_arena_size.is_finite() && opts.max_arena_size > 0.0) {
        return Err(ScenarioError::Options {
            field: "max_arena_size",
            value: opts.max_arena_size,
        });
    }
    Ok(())
}

/// Refuses path data usvg would silently truncate: syntax errors and numbers
/// beyond ±[`MAX_PATH_NUMBER`].
fn check_path_data(
    doc: &roxmltree::Document,
    display: &BTreeMap<String, String>,
    source: &str,
) -> Result<(), ScenarioError> {
    let err_src = || source.to_string();
    for n in doc
        .descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "path")
    {
        if let Some(d) = n.attribute("d") {
            for seg in svgtypes::PathParser::from(d) {
                let message = match seg {
                    Err(e) => e.to_string(),
                    Ok(seg) if !path_numbers_in_range(&seg) => {
                        format!("a number is beyond ±{MAX_PATH_NUMBER:e} (or not finite)")
                    }
                    Ok(_) => continue,
                };
                return Err(ScenarioError::PathData {
                    source_name: err_src(),
                    id: n
                        .attribute("id")
                        .map(|id| display.get(id).map_or(id, |d| d.as_str()))
                        .unwrap_or("(no id)")
                        .to_string(),
                    message,
                });
            }
        }
    }
    Ok(())
}

/// Refuses an arena smaller than 1 px, or beyond the options' size or area.
fn check_arena_size(
    width: f64,
    height: f64,
    opts: &LoadOptions,
    source: &str,
) -> Result<(), ScenarioError> {
    let err_src = || source.to_string();
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
    if width * height > opts.max_arena_area {
        return Err(ScenarioError::ArenaSize {
            source_name: err_src(),
            width,
            height,
            problem: format!(
                "larger than the limit of {:e} px² in area (its surface raster would take {:.0} MB)",
                opts.max_arena_area,
                width * height / (opts.cell_size * opts.cell_size) / 1e6
            ),
        });
    }
    Ok(())
}

/// Refuses a robot that starts outside the arena.
fn check_robots_inside(sc: &Scenario, source: &str) -> Result<(), ScenarioError> {
    let (width, height) = (sc.width, sc.height);
    for r in &sc.robots {
        if !(r.pos.x >= 0.0 && r.pos.y >= 0.0 && r.pos.x <= width && r.pos.y <= height) {
            return Err(ScenarioError::RobotOutsideArena {
                source_name: source.to_string(),
                id: r.id.clone(),
                x: r.pos.x,
                y: r.pos.y,
                width,
                height,
            });
        }
    }
    Ok(())
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
        };
        for c in root.children().filter(|c| c.is_element()) {
            loader.walk(c, None)?;
        }
        let mut sc = loader.sc;
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
}

/// Whether every number of a path segment is finite and within ±[`MAX_PATH_NUMBER`].
fn path_numbers_in_range(seg: &svgtypes::PathSegment) -> bool {
    use svgtypes::PathSegment as S;
    let nums: &[f64] = match *seg {
        S::MoveTo { x, y, .. } | S::LineTo { x, y, .. } | S::SmoothQuadratic { x, y, .. } => {
            &[x, y]
        }
        S::HorizontalLineTo { x, .. } => &[x],
        S::VerticalLineTo { y, .. } => &[y],
        S::CurveTo {
            x1,
            y1,
            x2,
            y2,
            x,
            y,
            ..
        } => &[x1, y1, x2, y2, x, y],
        S::SmoothCurveTo { x2, y2, x, y, .. }
        | S::Quadratic {
            x1: x2,
            y1: y2,
            x,
            y,
            ..
        } => &[x2, y2, x, y],
        S::EllipticalArc {
            rx,
            ry,
            x_axis_rotation,
            x,
            y,
            ..
        } => &[rx, ry, x_axis_rotation, x, y],
        S::ClosePath { .. } => &[],
    };
    nums.iter()
        .all(|v| v.is_finite() && v.abs() <= MAX_PATH_NUMBER)
}

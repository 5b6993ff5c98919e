//! Pictures of a world (the paper's Fig. 1 and trajectory figures) as SVG and PNG.
//! Text uses the DejaVu Sans font shipped in the crate; no system fonts are read.

use std::fmt::Write;
use std::sync::{Arc, OnceLock};

use glam::DVec2;

use crate::geometry::{FillRule, fmt_num};
use crate::scenario::SurfaceKind;
use crate::sensors::{DistanceSensors, Sensor, SurfaceSensors};
pub use crate::style::robot_color;
use crate::style::{surface_color, xml_escape};
use crate::world::World;

/// DejaVu Sans (see `assets/LICENSE-DejaVu.txt`), the font of every drawing.
pub static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Height of one line of the title band in px.
const TITLE_LINE: f64 = 20.0;
/// Width of a title glyph in px: DejaVu Sans at 16 px is at most about this
/// wide on average (a title is wrapped to fit the picture's width).
const TITLE_GLYPH: f64 = 9.6;
/// Height of one line of the legend band in px.
const LEGEND_LINE: f64 = 20.0;
/// Fill of fixed obstacles: a slate grey no robot colour resembles.
const FIXED_FILL: &str = "#5d6d7e";
/// Fill of movable obstacles.
const MOVABLE_FILL: &str = "#c8c8c8";
/// Fill of pucks.
const PUCK_FILL: &str = "#f0f0f0";

/// What to draw besides the world itself.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawOptions {
    /// Title drawn in a band above the arena.
    pub title: Option<String>,
    /// Draw the recorded trajectories (if the world recorded any).
    pub trajectories: bool,
    /// Draw each robot's surface sensors, coloured by their reading.
    pub surface_sensors: Option<SurfaceSensors>,
    /// Draw each robot's distance rays, coloured by their reading.
    pub distance_sensors: Option<DistanceSensors>,
    /// Pixels per world px in PNG output (default 1).
    pub scale: f64,
    /// Explain colours and marks in a band below the arena (default on).
    pub legend: bool,
}

impl Default for DrawOptions {
    fn default() -> Self {
        DrawOptions {
            title: None,
            trajectories: true,
            surface_sensors: None,
            distance_sensors: None,
            scale: 1.0,
            legend: true,
        }
    }
}

/// Why a PNG could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DrawError {
    /// The picture would be empty or too large.
    #[error("bad image size {width} x {height} px (scale {scale})")]
    Size {
        /// Width in pixels.
        width: f64,
        /// Height in pixels.
        height: f64,
        /// The scale asked for.
        scale: f64,
    },
    /// The SVG could not be parsed.
    #[error("cannot render SVG: {0}")]
    Svg(String),
    /// PNG encoding failed.
    #[error("cannot encode PNG: {0}")]
    Png(String),
}

/// Sensor colour for a reading in [0, 1]: red (0, grass / far) to white (1, road / near).
fn reading_color(v: f64) -> String {
    let v = v.clamp(0.0, 1.0);
    let g = (48.0 + v * 207.0).round() as u8;
    format!("#ff{g:02x}{g:02x}")
}

/// One legend entry: a small symbol (SVG drawn around the origin) and its text.
struct LegendItem {
    symbol: String,
    text: String,
}

impl LegendItem {
    fn new(symbol: String, text: impl Into<String>) -> LegendItem {
        LegendItem {
            symbol,
            text: text.into(),
        }
    }

    /// Width in px: symbol, gap, text (DejaVu Sans at 12 px averages about 7 px a glyph).
    fn width(&self) -> f64 {
        14.0 + 6.0 + 7.0 * self.text.chars().count() as f64 + 16.0
    }
}

/// What the picture shows that needs explaining, in drawing order.
fn legend_items(world: &World, opts: &DrawOptions) -> Vec<LegendItem> {
    let sc = world.scenario();
    let disc = |fill: &str, stroke: &str| {
        format!(
            r##"<circle cx="0" cy="0" r="5" fill="{fill}" stroke="{stroke}" stroke-width="1.2"/>"##
        )
    };
    let mut items = Vec::new();
    let trajectories = opts.trajectories && world.trajectories().is_some();
    for i in 0..world.robots().len() {
        let name = if trajectories {
            format!("robot {}", i + 1)
        } else {
            match sc.robots.get(i) {
                Some(start) if !start.id.is_empty() => start.id.clone(),
                _ => format!("robot {}", i + 1),
            }
        };
        items.push(LegendItem::new(disc(robot_color(i), "#000000"), name));
    }
    if !world.traffic().is_empty() {
        let fill = crate::draw_traffic::TRAFFIC_FILL;
        items.push(LegendItem::new(disc(fill, "#000000"), "scripted traffic"));
    }
    if trajectories {
        items.push(LegendItem::new(
            disc("none", "#000000"),
            "start (hollow), end (filled); lines: paths",
        ));
    }
    if opts.surface_sensors.is_some() {
        items.push(LegendItem::new(
            disc(&reading_color(1.0), "#000000"),
            "sensor on road (reads 1)",
        ));
        items.push(LegendItem::new(
            disc(&reading_color(0.0), "#000000"),
            "sensor on grass (reads 0)",
        ));
    }
    if opts.distance_sensors.is_some() {
        items.push(LegendItem::new(
            format!(
                r##"<line x1="-6" y1="0" x2="6" y2="0" stroke="{}" stroke-width="2"/>"##,
                reading_color(0.0)
            ),
            "ray: red = nothing in range, pale = something near",
        ));
    }
    let block = |fill: &str| {
        format!(
            r##"<rect x="-6" y="-5" width="12" height="10" fill="{fill}" stroke="#000000" stroke-width="0.8"/>"##
        )
    };
    if !sc.fixed_obstacles.is_empty() {
        items.push(LegendItem::new(block(FIXED_FILL), "fixed obstacle"));
    }
    if !sc.movable_obstacles.is_empty() {
        items.push(LegendItem::new(block(MOVABLE_FILL), "movable obstacle"));
    }
    if !sc.pucks.is_empty() {
        items.push(LegendItem::new(disc(PUCK_FILL, "#000000"), "puck"));
    }
    for kind in [SurfaceKind::Sand, SurfaceKind::Water] {
        if sc.background() == kind || sc.surfaces().iter().any(|s| s.kind == kind) {
            items.push(LegendItem::new(block(surface_color(kind)), kind.name()));
        }
    }
    if !sc.marks.is_empty() {
        items.push(LegendItem::new(
            r##"<rect x="-5" y="-5" width="10" height="10" fill="none" stroke="#ff00ff" stroke-width="1.5"/>"##.to_string(),
            "position mark",
        ));
    }
    items
}

/// Lays legend items out in lines no wider than `width`: (x, line) of each.
fn legend_layout(items: &[LegendItem], width: f64) -> (Vec<(f64, usize)>, usize) {
    let mut places = Vec::with_capacity(items.len());
    let (mut x, mut line) = (8.0, 0);
    for item in items {
        if x > 8.0 && x + item.width() > width {
            x = 8.0;
            line += 1;
        }
        places.push((x, line));
        x += item.width();
    }
    (places, if items.is_empty() { 0 } else { line + 1 })
}

/// `title` in lines of at most `width` px: words kept whole, but a word
/// wider than a line alone (a long path) cut where the line ends.
fn wrap_title(title: &str, width: f64) -> Vec<String> {
    let most = ((width - 16.0) / TITLE_GLYPH).floor().max(8.0) as usize;
    let mut pieces: Vec<String> = Vec::new();
    for word in title.split(' ') {
        let chars: Vec<char> = word.chars().collect();
        pieces.extend(chars.chunks(most).map(|c| c.iter().collect::<String>()));
        if chars.is_empty() {
            pieces.push(String::new());
        }
    }
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for piece in pieces {
        let fits = line.chars().count() + 1 + piece.chars().count() <= most;
        if !line.is_empty() && !fits {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&piece);
    }
    lines.push(line);
    lines
}

/// The world as an SVG picture (not a loadable scenario: see [`World::to_svg`]).
///
/// A picture is at least as wide as its widest legend entry (the arena is
/// centred in it), its title wraps to that width, and nothing of the
/// scenario outside the arena is drawn.
pub fn render_svg(world: &World, opts: &DrawOptions) -> String {
    let sc = world.scenario();
    let items = if opts.legend {
        legend_items(world, opts)
    } else {
        Vec::new()
    };
    let widest = items.iter().map(|i| i.width() + 16.0).fold(0.0, f64::max);
    let w = sc.width().max(widest);
    let title = opts.title.as_deref().map(|t| wrap_title(t, w));
    let band = title
        .as_ref()
        .map_or(0.0, |t| TITLE_LINE * t.len() as f64 + 8.0);
    let (places, lines) = legend_layout(&items, w);
    let legend_band = if lines > 0 {
        LEGEND_LINE * lines as f64 + 6.0
    } else {
        0.0
    };
    let h = sc.height() + band + legend_band;
    let left = (w - sc.width()) / 2.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}">"##,
        fmt_num(w),
        fmt_num(h),
        fmt_num(w),
        fmt_num(h)
    );
    if let Some(lines) = &title {
        let _ = writeln!(
            s,
            r##"<rect x="0" y="0" width="{}" height="{band}" fill="#ffffff"/>"##,
            fmt_num(w)
        );
        for (k, line) in lines.iter().enumerate() {
            let _ = writeln!(
                s,
                r##"<text x="8" y="{}" font-family="DejaVu Sans" font-size="16" fill="#000000">{}</text>"##,
                fmt_num(20.0 + TITLE_LINE * k as f64),
                xml_escape(line)
            );
        }
    }
    // Shapes a scenario has outside its arena stay out of the title and legend.
    let _ = writeln!(
        s,
        r##"<defs><clipPath id="vivae-arena"><rect x="0" y="0" width="{}" height="{}"/></clipPath></defs>"##,
        fmt_num(sc.width()),
        fmt_num(sc.height())
    );
    let _ = writeln!(
        s,
        r##"<g transform="translate({} {band})"><g clip-path="url(#vivae-arena)">"##,
        fmt_num(left)
    );
    draw_arena(&mut s, world);
    if opts.trajectories
        && let Some(trajs) = world.trajectories()
    {
        draw_trajectories(&mut s, world, trajs);
    }
    let r = world.params().robot_radius;
    if let Some(layout) = &opts.distance_sensors {
        draw_distance_rays(&mut s, world, layout, r);
    }
    if let Some(layout) = &opts.surface_sensors {
        draw_surface_dots(&mut s, world, layout, r);
    }
    crate::draw_traffic::draw_traffic(&mut s, world, opts.trajectories);
    draw_robots(&mut s, world, r);
    s.push_str("</g></g>\n");
    if lines > 0 {
        let top = band + sc.height();
        draw_legend(&mut s, &items, &places, (top, w, legend_band));
    }
    s.push_str("</svg>\n");
    s
}

/// SVG's name for a fill rule.
fn fill_rule_name(r: FillRule) -> &'static str {
    match r {
        FillRule::NonZero => "nonzero",
        FillRule::EvenOdd => "evenodd",
    }
}

/// The arena: background, surfaces, marks, obstacles (movable ones where they
/// were pushed) and pucks.
fn draw_arena(s: &mut String, world: &World) {
    let sc = world.scenario();
    let _ = writeln!(
        s,
        r##"<rect x="0" y="0" width="{}" height="{}" fill="{}"/>"##,
        fmt_num(sc.width()),
        fmt_num(sc.height()),
        surface_color(sc.background())
    );
    for surf in sc.surfaces() {
        let _ = writeln!(
            s,
            r##"<path d="{}" fill="{}" fill-rule="{}"/>"##,
            surf.shape.to_path_data(),
            surface_color(surf.kind),
            fill_rule_name(surf.shape.fill_rule)
        );
    }
    for mk in &sc.marks {
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#ff00ff" stroke-width="1.5"/>"##,
            fmt_num(mk.pos.x - mk.size.x / 2.0),
            fmt_num(mk.pos.y - mk.size.y / 2.0),
            fmt_num(mk.size.x),
            fmt_num(mk.size.y)
        );
    }
    for ob in &sc.fixed_obstacles {
        let _ = writeln!(
            s,
            r##"<path d="{}" fill="{FIXED_FILL}" fill-rule="{}" stroke="#000000" stroke-width="0.8"/>"##,
            ob.shape.to_path_data(),
            fill_rule_name(ob.shape.fill_rule)
        );
    }
    for (ob, m) in sc.movable_obstacles.iter().zip(world.movables()) {
        let _ = writeln!(
            s,
            r##"<path d="{}" fill="{MOVABLE_FILL}" fill-rule="{}" stroke="#000000" stroke-width="0.8" stroke-dasharray="3 2"/>"##,
            ob.shape.translated(m.offset).to_path_data(),
            fill_rule_name(ob.shape.fill_rule)
        );
    }
    for pk in world.pucks() {
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="{PUCK_FILL}" stroke="#000000" stroke-width="0.5"/>"##,
            fmt_num(pk.pos.x),
            fmt_num(pk.pos.y),
            fmt_num(pk.radius)
        );
    }
}

/// Each robot's recorded path, and its start pose as hollow discs (with a
/// heading tick when the path starts at the scenario's start).
fn draw_trajectories(s: &mut String, world: &World, trajs: &[Vec<DVec2>]) {
    let sc = world.scenario();
    for (i, t) in trajs.iter().enumerate() {
        if t.len() < 2 {
            continue;
        }
        let mut pts = String::new();
        for p in t {
            let _ = write!(pts, "{},{} ", fmt_num(p.x), fmt_num(p.y));
        }
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5" stroke-linejoin="round" stroke-opacity="0.9"/>"##,
            pts.trim_end(),
            robot_color(i)
        );
    }
    // Start poses: hollow discs (the filled discs drawn last are the end poses).
    let r = world.params().robot_radius;
    for (i, t) in trajs.iter().enumerate() {
        let Some(&p) = t.first() else { continue };
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="none" stroke="{}" stroke-width="2"/><circle cx="{}" cy="{}" r="{}" fill="none" stroke="#000000" stroke-width="0.6"/>"##,
            fmt_num(p.x),
            fmt_num(p.y),
            fmt_num(r),
            robot_color(i),
            fmt_num(p.x),
            fmt_num(p.y),
            fmt_num(r + 1.0)
        );
        if let Some(start) = sc.robots.get(i).filter(|st| st.pos == p) {
            let (sin, cos) = libm::sincos(start.heading);
            let tip = p + glam::DVec2::new(sin, -cos) * r;
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="1.5"/>"##,
                fmt_num(p.x),
                fmt_num(p.y),
                fmt_num(tip.x),
                fmt_num(tip.y),
                robot_color(i)
            );
        }
    }
}

/// Each robot's distance rays, as far as they reach, coloured by reading.
fn draw_distance_rays(s: &mut String, world: &World, layout: &DistanceSensors, r: f64) {
    let grid = layout.grid();
    let mut out = vec![0.0; grid.len()];
    for i in 0..world.robots().len() {
        grid.read(world, i, &mut out);
        let rb = &world.robots()[i];
        let (ahead, right) = (rb.ahead(), rb.right());
        for (d, v) in grid.dirs.iter().zip(&out) {
            let dir = ahead * d.x + right * d.y;
            let len = if *v > 0.0 {
                (1.0 - v) * grid.range
            } else {
                grid.range
            };
            let (a, b) = (rb.pos + dir * r, rb.pos + dir * (r + len));
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="1" stroke-opacity="0.8"/>"##,
                fmt_num(a.x),
                fmt_num(a.y),
                fmt_num(b.x),
                fmt_num(b.y),
                reading_color(*v)
            );
        }
    }
}

/// Each robot's surface sensor points, coloured by reading.
fn draw_surface_dots(s: &mut String, world: &World, layout: &SurfaceSensors, r: f64) {
    let grid = layout.grid();
    let mut out = vec![0.0; grid.len()];
    let dot = (r * 0.35).clamp(1.0, 3.0);
    for i in 0..world.robots().len() {
        grid.read(world, i, &mut out);
        for (p, v) in grid.positions(world, i).iter().zip(&out) {
            let _ = writeln!(
                s,
                r##"<circle cx="{}" cy="{}" r="{}" fill="{}" stroke="#000000" stroke-width="0.4"/>"##,
                fmt_num(p.x),
                fmt_num(p.y),
                fmt_num(dot),
                reading_color(*v)
            );
        }
    }
}

/// Each robot as a disc in its colour with a heading line.
fn draw_robots(s: &mut String, world: &World, r: f64) {
    for (i, rb) in world.robots().iter().enumerate() {
        let tip = rb.pos + rb.ahead() * r;
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="{}" stroke="#000000" stroke-width="1"/><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#000000" stroke-width="1.5"/>"##,
            fmt_num(rb.pos.x),
            fmt_num(rb.pos.y),
            fmt_num(r),
            robot_color(i),
            fmt_num(rb.pos.x),
            fmt_num(rb.pos.y),
            fmt_num(tip.x),
            fmt_num(tip.y)
        );
    }
}

/// The legend band below the arena: its white background, then each item's
/// symbol and text at its place `(x, line)`.
fn draw_legend(
    s: &mut String,
    items: &[LegendItem],
    places: &[(f64, usize)],
    (top, w, legend_band): (f64, f64, f64),
) {
    let _ = writeln!(
        s,
        r##"<rect x="0" y="{}" width="{}" height="{}" fill="#ffffff"/>"##,
        fmt_num(top),
        fmt_num(w),
        fmt_num(legend_band)
    );
    for (item, &(x, line)) in items.iter().zip(places) {
        let y = top + 3.0 + LEGEND_LINE * (line as f64 + 0.5);
        let _ = writeln!(
            s,
            r##"<g transform="translate({} {})">{}</g><text x="{}" y="{}" font-family="DejaVu Sans" font-size="12" fill="#000000">{}</text>"##,
            fmt_num(x + 7.0),
            fmt_num(y),
            item.symbol,
            fmt_num(x + 20.0),
            fmt_num(y + 4.0),
            xml_escape(&item.text)
        );
    }
}

/// A font database holding only [`FONT`], built once.
fn fontdb() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        Arc::new(db)
    })
    .clone()
}

/// Most pixels in one PNG (400 MB of RGBA); larger pictures are scaled down to fit.
pub const MAX_PIXELS: f64 = 1.0e8;

/// Renders any SVG text to PNG bytes at `scale` pixels per user unit (less
/// when the picture would exceed [`MAX_PIXELS`]), using
/// only the shipped font. Useful for every figure the project draws.
pub fn svg_to_png(svg: &str, scale: f64) -> Result<Vec<u8>, DrawError> {
    svg_to_png_capped(svg, scale, MAX_PIXELS)
}

/// [`svg_to_png`] with a pixel cap of `max_pixels`.
fn svg_to_png_capped(svg: &str, scale: f64, max_pixels: f64) -> Result<Vec<u8>, DrawError> {
    let opt = usvg::Options {
        fontdb: fontdb(),
        font_family: "DejaVu Sans".to_string(),
        ..Default::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| DrawError::Svg(e.to_string()))?;
    let size = tree.size();
    let (w, h) = (size.width() as f64, size.height() as f64);
    // A picture that would exceed the pixel cap is drawn smaller rather than
    // refused: a large arena still gets its figures.
    let scale = if scale.is_finite() && scale > 0.0 && w * h * scale * scale > max_pixels {
        (max_pixels / (w * h)).sqrt()
    } else {
        scale
    };
    let (pw, ph) = (w * scale, h * scale);
    if !(scale.is_finite() && scale > 0.0 && pw >= 1.0 && ph >= 1.0 && pw * ph <= max_pixels * 1.01)
    {
        return Err(DrawError::Size {
            width: pw,
            height: ph,
            scale,
        });
    }
    let mut pixmap =
        tiny_skia::Pixmap::new(pw.ceil() as u32, ph.ceil() as u32).ok_or(DrawError::Size {
            width: pw,
            height: ph,
            scale,
        })?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale as f32, scale as f32),
        &mut pixmap.as_mut(),
    );
    encode_png(&pixmap)
}

/// Encodes `pixmap` as PNG with fast compression (tiny-skia's own encoder,
/// at the default level, spends most of a large figure's time compressing).
pub fn encode_png(pixmap: &tiny_skia::Pixmap) -> Result<Vec<u8>, DrawError> {
    let png_err = |e: png::EncodingError| DrawError::Png(e.to_string());
    // Opaque and fully transparent pixels read the same premultiplied or not:
    // a figure's pixmap (opaque background) needs no straight-alpha copy.
    let straight = pixmap
        .pixels()
        .iter()
        .all(|p| p.alpha() == 255 || p.alpha() == 0);
    let copy;
    let rgba = if straight {
        pixmap.data()
    } else {
        copy = pixmap
            .pixels()
            .iter()
            .flat_map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue(), c.alpha()]
            })
            .collect::<Vec<u8>>();
        &copy
    };
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let mut writer = encoder.write_header().map_err(png_err)?;
        writer.write_image_data(rgba).map_err(png_err)?;
        writer.finish().map_err(png_err)?;
    }
    Ok(out)
}

/// The world as a PNG picture (see [`render_svg`]).
pub fn render_png(world: &World, opts: &DrawOptions) -> Result<Vec<u8>, DrawError> {
    svg_to_png(&render_svg(world, opts), opts.scale)
}

#[cfg(test)]
mod pixel_cap_tests {
    use super::*;

    #[test]
    fn a_picture_over_the_pixel_cap_is_scaled_down_to_fit() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="2000" height="1000"><rect width="10" height="10"/></svg>"#;
        let png = svg_to_png_capped(svg, 2.0, 20_000.0).expect("drawn, smaller");
        let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
        assert!(f64::from(w) * f64::from(h) <= 20_000.0 * 1.01, "{w} x {h}");
        assert!(
            (199..=201).contains(&w) && (99..=101).contains(&h),
            "{w} x {h}"
        );
    }
}

#[cfg(test)]
mod small_map_tests {
    use super::*;
    use crate::{LoadOptions, Scenario};

    /// A 200×120 arena with a sand patch, a water patch, a road poking far
    /// outside it (above, where the title goes) and one robot.
    fn small_world() -> World {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="200" height="120">
<rect inkscape:label="Grass" x="0" y="0" width="200" height="120"/>
<rect inkscape:label="Sand" x="10" y="10" width="40" height="30"/>
<rect inkscape:label="Water" x="60" y="10" width="40" height="30"/>
<rect inkscape:label="Road" x="120" y="-400" width="30" height="800"/>
<rect inkscape:label="vivae.robots.FRNNControlledRobot" x="94" y="74" width="12" height="12"/>
</svg>"#;
        let sc = Scenario::from_svg(svg, "small.svg", &LoadOptions::default()).unwrap();
        World::new(&sc, &Default::default()).unwrap()
    }

    #[test]
    fn a_small_map_keeps_its_title_and_legend_whole_and_its_shapes_inside() {
        let title = "Champion on training map small — fitness 2.345 px/step, 100.0% on road";
        let opts = DrawOptions {
            title: Some(title.into()),
            ..DrawOptions::default()
        };
        let world = small_world();
        let svg = render_svg(&world, &opts);
        let items = legend_items(&world, &opts);
        let widest = items.iter().map(LegendItem::width).fold(0.0, f64::max);
        let width: f64 = svg
            .split("width=\"")
            .nth(1)
            .and_then(|w| w.split('"').next())
            .and_then(|w| w.parse().ok())
            .unwrap();
        assert!(width >= widest + 16.0, "{width} < {widest} + 16");
        // Every word of the title is there, on lines that fit the picture.
        let lines = wrap_title(title, width);
        assert!(lines.len() > 1, "{lines:?}");
        assert_eq!(lines.join(" "), title);
        // A path longer than a line is cut, not lost.
        let path = "/a/very/long/folder/name/that/goes/on/and/on/scenario2.svg";
        let cut = wrap_title(path, 200.0);
        assert!(cut.len() > 1, "{cut:?}");
        assert_eq!(cut.concat(), path);
        assert!(
            cut.iter()
                .all(|l| 8.0 + TITLE_GLYPH * l.chars().count() as f64 <= 200.0)
        );
        for l in &lines {
            assert!(8.0 + TITLE_GLYPH * l.chars().count() as f64 <= width, "{l}");
            assert!(svg.contains(&format!(">{}</text>", xml_escape(l))), "{l}");
        }
        // Sand and water have legend entries; the road is clipped to the arena.
        let names: Vec<&str> = items.iter().map(|i| i.text.as_str()).collect();
        assert!(
            names.contains(&"sand") && names.contains(&"water"),
            "{names:?}"
        );
        assert!(svg.contains(r#"<g clip-path="url(#vivae-arena)">"#));
        let png = render_png(&world, &opts).unwrap();
        assert!(png.len() > 100);
    }
}

//! The network figure of a large controller: receptive fields.
//!
//! A line per link stops being readable after a few hundred links and costs
//! time and bytes per link (243,286 links at 32×96 → 9×9). This form shows
//! every weight as a colour instead:
//!
//! * one panel per neuron, placed by its ring (rows, outermost at the top) and
//!   angle (columns, left to right): its incoming weights over the sensor
//!   sheet, in the sheet's polar layout seen from above (ahead is up, the robot
//!   at the centre; ring `k` of `R` is the band from radius `k/R` to `(k+1)/R`,
//!   each wedge one sensor), every further input sheet (e.g. distance rays)
//!   as a band outside it, one wedge per node; the dot at the
//!   centre is the neuron's bias; wheel neurons are outlined red;
//! * the recurrent weights as a neuron × neuron matrix;
//! * the biases as a row, aligned with the matrix columns.
//!
//! Colours run from orange (negative) through white (0 or no link) to blue
//! (positive); each block has its own scale, up to its largest |weight|,
//! because sheet normalisation makes input weights far smaller than recurrent
//! ones at high resolution.
//!
//! The heat maps are rasters at the PNG's resolution, so drawing costs grow
//! with the figure's pixels, not with its links. The SVG embeds them as PNG
//! images under the vector labels; the PNG output draws the same pixels under
//! the same labels, so both files show one picture.

use std::f64::consts::FRAC_PI_2;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use tiny_skia::{Pixmap, PixmapPaint, PremultipliedColorU8, Transform};
use vivae_neat::hyperneat::SubstrateController;

use super::controller::{Checked, FigureSheet, GUIDE, NetworkOptions, WHEEL, blend, check, px};
use super::{
    FAMILY, Figure, FigureError, NEGATIVE, PNG_SCALE, POSITIVE, base64, draw_err, draw_svg_over,
    encode_png_fast, register_font,
};
use vivae_lab::substrate::{PolarNode, SubstrateSpec};

/// The receptive-field figure is this much larger than the link figure (more to show).
const ENLARGE: f64 = 1.6;
/// Inner and outer radius (sheet radius = 1) of the first band outside the
/// panel: the second input sheet's (e.g. the distance rays').
const BAND: (f64, f64) = (1.06, 1.22);
/// How much further out each further band is.
const BAND_STEP: f64 = 0.22;

/// Inner and outer radius of input sheet `band`'s band (1 = the second sheet).
fn band_radii(band: usize) -> (f64, f64) {
    let shift = BAND_STEP * (band - 1) as f64;
    (BAND.0 + shift, BAND.1 + shift)
}

/// Outer radius of a panel with `sheets` input sheets (1 = no band).
fn outer_radius(sheets: usize) -> f64 {
    if sheets > 1 {
        band_radii(sheets - 1).1
    } else {
        1.0
    }
}
/// Marks a pixel outside every sensor's wedge.
const OUTSIDE: u32 = u32::MAX;

/// A raster heat map and where it lies, in pixels of the PNG.
struct Heat {
    x: i32,
    y: i32,
    pixmap: Pixmap,
}

/// The figure's parts: labels and outlines (SVG without background), heat maps, size in units.
struct Drawn {
    overlay: String,
    heats: Vec<Heat>,
    size: (f64, f64),
}

/// Renders the receptive-field figure as SVG and PNG.
pub(crate) fn render(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<Figure, FigureError> {
    let Drawn {
        overlay,
        heats,
        size: (w, h),
    } = draw(spec, sheets, controller, opts)?;
    let scale = f64::from(PNG_SCALE);
    let too_big = || FigureError::Png(format!("figure of {w}x{h} units is too large"));
    let mut base =
        Pixmap::new((w * scale).ceil() as u32, (h * scale).ceil() as u32).ok_or_else(too_big)?;
    base.fill(tiny_skia::Color::WHITE);
    for heat in &heats {
        base.draw_pixmap(
            heat.x,
            heat.y,
            heat.pixmap.as_ref(),
            &PixmapPaint::default(),
            Transform::identity(),
            None,
        );
    }
    draw_svg_over(&overlay, &mut base, PNG_SCALE)?;
    let png = encode_png_fast(&base)?;
    let svg = with_images(overlay, &heats, (w, h))?;
    Ok(Figure { svg, png })
}

/// Renders the receptive-field figure as an SVG document (heat maps embedded as PNG).
pub(crate) fn render_svg(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    let d = draw(spec, sheets, controller, opts)?;
    with_images(d.overlay, &d.heats, d.size)
}

/// Puts a white background and the heat maps under the labels of `overlay`.
fn with_images(overlay: String, heats: &[Heat], (w, h): (f64, f64)) -> Result<String, FigureError> {
    let open = overlay
        .find("<svg")
        .and_then(|at| overlay[at..].find('>').map(|end| at + end + 1))
        .ok_or_else(|| FigureError::Draw("the overlay is not an SVG document".into()))?;
    let scale = f64::from(PNG_SCALE);
    let mut images = format!(r##"<rect x="0" y="0" width="{w}" height="{h}" fill="#FFFFFF"/>"##);
    for heat in heats {
        let png = encode_png_fast(&heat.pixmap)?;
        images.push_str(&format!(
            r#"<image x="{}" y="{}" width="{}" height="{}" preserveAspectRatio="none" href="data:image/png;base64,{}"/>"#,
            f64::from(heat.x) / scale,
            f64::from(heat.y) / scale,
            f64::from(heat.pixmap.width()) / scale,
            f64::from(heat.pixmap.height()) / scale,
            base64(&png)
        ));
    }
    let mut svg = String::with_capacity(overlay.len() + images.len() + 1);
    svg.push_str(&overlay[..open]);
    svg.push('\n');
    svg.push_str(&images);
    svg.push_str(&overlay[open..]);
    Ok(svg)
}

/// An opaque pixel of colour `c`.
fn pixel(c: RGBColor) -> PremultipliedColorU8 {
    PremultipliedColorU8::from_rgba(c.0, c.1, c.2, 255).expect("opaque colours are premultiplied")
}

/// The diverging colour of `v` on a symmetric scale `±scale`: orange, white at 0, blue.
fn diverging(v: f64, scale: f64) -> RGBColor {
    let m = (v.abs() / scale).clamp(0.0, 1.0);
    let m = if m.is_nan() { 0.0 } else { m };
    blend(if v >= 0.0 { POSITIVE } else { NEGATIVE }, m)
}

/// Largest |value|, or 1 when all are 0 (a scale never divides by 0).
fn max_abs(values: impl Iterator<Item = f64>) -> f64 {
    let m = values.fold(0.0f64, |m, v| m.max(v.abs()));
    if m > 0.0 && m.is_finite() { m } else { 1.0 }
}

/// A value with three significant digits, for scale labels.
fn short(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 0.01 {
        let digits = (2 - v.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.2e}")
    }
}

/// Boundaries between the wedges of nodes at angles `phis` (ascending): midway
/// between neighbours, half a spacing beyond the ends (`half_fov` for one node).
fn wedge_bounds(phis: &[f64], half_fov: f64) -> Vec<f64> {
    match phis {
        [] => Vec::new(),
        [only] => vec![only - half_fov, only + half_fov],
        _ => {
            let first = phis[0] - (phis[1] - phis[0]) / 2.0;
            let last = phis[phis.len() - 1] + (phis[phis.len() - 1] - phis[phis.len() - 2]) / 2.0;
            std::iter::once(first)
                .chain(phis.windows(2).map(|p| (p[0] + p[1]) / 2.0))
                .chain(std::iter::once(last))
                .collect()
        }
    }
}

/// Index of the wedge holding angle `phi`.
fn wedge(bounds: &[f64], phi: f64) -> Option<usize> {
    if bounds.len() < 2 || !(phi >= bounds[0] && phi < bounds[bounds.len() - 1]) {
        return None;
    }
    Some(bounds.partition_point(|&b| b <= phi) - 1)
}

/// Which input feeds each pixel of a panel: the same for every panel, so
/// computed once. `radius` is the sheet radius in pixels; the panel's box
/// spans `x0..x0+width`, `y0..y0+height` pixels around the centre.
struct Stencil {
    x0: i32,
    y0: i32,
    width: u32,
    /// Input index per pixel, row-major, [`OUTSIDE`] where there is none.
    input: Vec<u32>,
}

/// Which input of one sheet feeds a point of a panel: the sheet's nodes by
/// ring (radial slices of `r0..r1`) and wedge (angle).
struct Placement {
    /// Radial extent in sheet radii: `0..1` for the panel, a band outside it.
    r0: f64,
    r1: f64,
    rings: usize,
    angles: usize,
    /// Input index (over all sheets) by `ring * angles + angle_index`.
    by_place: Vec<u32>,
    bounds: Vec<f64>,
}

impl Placement {
    fn new(nodes: &[PolarNode], first_input: usize, (r0, r1): (f64, f64), half: f64) -> Self {
        let rings = nodes.iter().map(|n| n.ring + 1).max().unwrap_or(1);
        let angles = nodes.iter().map(|n| n.angle_index + 1).max().unwrap_or(1);
        // Input index by (ring, angle): the sheet need not list them in grid order.
        let mut by_place = vec![OUTSIDE; rings * angles];
        let mut phis = vec![0.0; angles];
        for (i, n) in nodes.iter().enumerate() {
            by_place[n.ring * angles + n.angle_index] = (first_input + i) as u32;
            phis[n.angle_index] = n.phi;
        }
        Placement {
            r0,
            r1,
            rings,
            angles,
            by_place,
            bounds: wedge_bounds(&phis, half),
        }
    }

    /// The input at radius `rho` (in `r0..r1`) and angle `phi`.
    fn input(&self, rho: f64, phi: f64) -> u32 {
        let ring = (((rho - self.r0) / (self.r1 - self.r0) * self.rings as f64) as usize)
            .min(self.rings - 1);
        wedge(&self.bounds, phi).map_or(OUTSIDE, |a| self.by_place[ring * self.angles + a])
    }
}

impl Stencil {
    fn new(radius: f64, half: f64, sheets: &[FigureSheet]) -> Stencil {
        let mut first_input = 0;
        let placements: Vec<Placement> = sheets
            .iter()
            .enumerate()
            .map(|(k, sheet)| {
                let radii = if k == 0 { (0.0, 1.0) } else { band_radii(k) };
                let p = Placement::new(&sheet.nodes, first_input, radii, half);
                first_input += sheet.nodes.len();
                p
            })
            .collect();
        let outer = outer_radius(sheets.len());
        let side = outer * half.min(FRAC_PI_2).sin().max(0.05);
        let below = if half > FRAC_PI_2 { -half.cos() } else { 0.0 };
        let x0 = -(side * radius).ceil() as i32 - 1;
        let y0 = -(outer * radius).ceil() as i32 - 1;
        let width = (2 * -x0) as u32;
        let height = (-y0 + (below * outer * radius).ceil() as i32 + 1) as u32;
        let mut input = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height as i32 {
            for x in 0..width as i32 {
                let (dx, dy) = (f64::from(x0 + x) + 0.5, f64::from(y0 + y) + 0.5);
                let rho = dx.hypot(dy) / radius;
                // Angle from straight ahead (up), positive to the right.
                let phi = dx.atan2(-dy);
                let index = placements
                    .iter()
                    .find(|p| rho < p.r1 && (p.r0 == 0.0 || rho >= p.r0))
                    .map_or(OUTSIDE, |p| p.input(rho, phi));
                input.push(index);
            }
        }
        Stencil {
            x0,
            y0,
            width,
            input,
        }
    }
}

/// Where the blocks go, in SVG units.
struct Layout {
    w: f64,
    h: f64,
    /// Panel grid: left, top, cell width, cell height.
    grid: (f64, f64, f64, f64),
    /// Sheet radius of a panel.
    radius: f64,
    /// Recurrent matrix: left, top, side.
    matrix: (f64, f64, f64),
    /// Bias row: top and height (left and width are the matrix's).
    bias: (f64, f64),
}

impl Layout {
    fn new(opts: &NetworkOptions, rows: usize, cols: usize, half: f64, outer: f64) -> Layout {
        let (w, h) = (
            (f64::from(opts.width) * ENLARGE).round(),
            (f64::from(opts.height) * ENLARGE).round(),
        );
        let (left, top) = (w * 0.07, 130.0);
        let (right, bottom) = (w * 0.63, h - 150.0);
        let (cw, ch) = ((right - left) / cols as f64, (bottom - top) / rows as f64);
        let fan_w = 2.0 * outer * half.min(FRAC_PI_2).sin().max(0.05);
        let fan_h = outer * (1.0 + if half > FRAC_PI_2 { -half.cos() } else { 0.0 });
        let radius = (cw * 0.9 / fan_w).min(ch * 0.86 / fan_h);
        let mx = w * 0.68;
        let side = (w - 40.0 - mx).min(h - 330.0 - top);
        Layout {
            w,
            h,
            grid: (left, top, cw, ch),
            radius,
            matrix: (mx, top + 20.0, side),
            bias: (top + 20.0 + side + 46.0, 24.0),
        }
    }

    /// Centre of the panel at `row`, `col`, rounded to whole PNG pixels so
    /// every panel shares one [`Stencil`].
    fn centre(&self, row: usize, col: usize, half: f64, outer: f64) -> (f64, f64) {
        let (left, top, cw, ch) = self.grid;
        let fan_h = outer * (1.0 + if half > FRAC_PI_2 { -half.cos() } else { 0.0 });
        let cx = left + cw * (col as f64 + 0.5);
        let cy = top + ch * row as f64 + (ch - fan_h * self.radius) / 2.0 + outer * self.radius;
        let s = f64::from(PNG_SCALE);
        ((cx * s).round() / s, (cy * s).round() / s)
    }
}

/// The drawing area of the vector overlay.
type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The font of captions.
fn font() -> FontDesc<'static> {
    (FAMILY, 17).into_font()
}

/// The font of labels and notes.
fn small() -> FontDesc<'static> {
    (FAMILY, 14).into_font()
}

/// Draws `s` at `at` in font `f`, anchored at `pos`.
fn text(
    root: &Root<'_>,
    s: &str,
    at: (f64, f64),
    f: &FontDesc<'_>,
    pos: Pos,
) -> Result<(), FigureError> {
    root.draw(&Text::new(
        s.to_string(),
        px(at),
        TextStyle::from(f.clone()).pos(pos),
    ))
    .map_err(draw_err)
}

fn too_big() -> FigureError {
    FigureError::Draw("heat map too large".into())
}

/// Everything the figure is drawn from: the checked controller and
/// substrate, the layout and the three blocks' colour scales.
struct Fields<'a> {
    spec: &'a SubstrateSpec,
    controller: &'a SubstrateController,
    opts: &'a NetworkOptions,
    nodes: Checked,
    layout: Layout,
    /// Rings and angles of the neuron sheet (the panel grid's rows and columns).
    rows: usize,
    cols: usize,
    /// Half the sensors' field of view, in radians.
    half: f64,
    /// Outer radius of a panel, its bands included (in sheet radii).
    outer: f64,
    /// Largest |weight| of each block: sensor → neuron, recurrent, bias.
    input_scale: f64,
    recurrent_scale: f64,
    bias_scale: f64,
}

impl<'a> Fields<'a> {
    fn new(
        spec: &'a SubstrateSpec,
        sheets: &[FigureSheet],
        controller: &'a SubstrateController,
        opts: &'a NetworkOptions,
    ) -> Result<Fields<'a>, FigureError> {
        let nodes = check(spec, sheets, controller, opts)?;
        let n = nodes.neurons.len();
        let inputs = nodes.num_inputs();
        let (rows, cols) = (spec.neurons.rings, spec.neurons.angles);
        let half = spec.fov.to_radians() / 2.0;
        let outer = outer_radius(nodes.inputs.len());
        let layout = Layout::new(opts, rows, cols, half, outer);
        // Colour scales, one per block.
        let input_scale = max_abs(
            (0..inputs)
                .flat_map(|i| (0..n).map(move |t| (i, t)))
                .map(|(i, t)| controller.input_weight(i, t)),
        );
        let recurrent_scale = max_abs(
            (0..n)
                .flat_map(|s| (0..n).map(move |t| (s, t)))
                .map(|(s, t)| controller.recurrent_weight(s, t)),
        );
        let bias_scale = max_abs(controller.biases().iter().copied());
        Ok(Fields {
            spec,
            controller,
            opts,
            nodes,
            layout,
            rows,
            cols,
            half,
            outer,
            input_scale,
            recurrent_scale,
            bias_scale,
        })
    }

    /// Centre of neuron `i`'s panel.
    fn centre_of(&self, i: usize) -> (f64, f64) {
        let node = &self.nodes.neurons[i];
        self.layout.centre(
            self.rows - 1 - node.ring,
            node.angle_index,
            self.half,
            self.outer,
        )
    }

    /// The panels' heat maps: one raster over the whole grid.
    fn panels_heat(&self) -> Result<Heat, FigureError> {
        let scale = f64::from(PNG_SCALE);
        let inputs = &self.nodes.inputs;
        let stencil = Stencil::new(self.layout.radius * scale, self.half, inputs);
        let (left, top, cw, ch) = self.layout.grid;
        let grid_x = (left * scale).floor() as i32;
        let grid_y = (top * scale).floor() as i32;
        let mut grid = Pixmap::new(
            (cw * self.cols as f64 * scale).ceil() as u32 + 2,
            (ch * self.rows as f64 * scale).ceil() as u32 + 2,
        )
        .ok_or_else(too_big)?;
        let mut colours = vec![pixel(WHITE); self.nodes.num_inputs()];
        for t in 0..self.nodes.neurons.len() {
            for (i, c) in colours.iter_mut().enumerate() {
                *c = pixel(diverging(
                    self.controller.input_weight(i, t),
                    self.input_scale,
                ));
            }
            let (cx, cy) = self.centre_of(t);
            let ox = (cx * scale).round() as i32 + stencil.x0 - grid_x;
            let oy = (cy * scale).round() as i32 + stencil.y0 - grid_y;
            stamp(&mut grid, &stencil, (ox, oy), &colours);
        }
        Ok(Heat {
            x: grid_x,
            y: grid_y,
            pixmap: grid,
        })
    }

    /// The recurrent matrix (row = target, column = source) and the bias row,
    /// sampled per pixel.
    fn matrix_heats(&self) -> Result<[Heat; 2], FigureError> {
        let n = self.nodes.neurons.len();
        let scale = f64::from(PNG_SCALE);
        let (mx, my, side) = self.layout.matrix;
        let side_px = (side * scale).round().max(1.0) as u32;
        let mut matrix = Pixmap::new(side_px, side_px).ok_or_else(too_big)?;
        let cell = |p: u32| ((f64::from(p) + 0.5) / f64::from(side_px) * n as f64) as usize;
        let lookup: Vec<usize> = (0..side_px).map(|p| cell(p).min(n - 1)).collect();
        for (py, &target) in lookup.iter().enumerate() {
            let line = &mut matrix.pixels_mut()[py * side_px as usize..(py + 1) * side_px as usize];
            for (p, &source) in line.iter_mut().zip(&lookup) {
                *p = pixel(diverging(
                    self.controller.recurrent_weight(source, target),
                    self.recurrent_scale,
                ));
            }
        }
        let (by, bh) = self.layout.bias;
        let bh_px = (bh * scale).round() as u32;
        let mut bias = Pixmap::new(side_px, bh_px).ok_or_else(too_big)?;
        for line in bias.pixels_mut().chunks_exact_mut(side_px as usize) {
            for (p, &i) in line.iter_mut().zip(&lookup) {
                *p = pixel(diverging(self.controller.biases()[i], self.bias_scale));
            }
        }
        Ok([
            Heat {
                x: (mx * scale).round() as i32,
                y: (my * scale).round() as i32,
                pixmap: matrix,
            },
            Heat {
                x: (mx * scale).round() as i32,
                y: (by * scale).round() as i32,
                pixmap: bias,
            },
        ])
    }

    /// The vector overlay: labels, outlines and scales (no background), as SVG.
    fn overlay(&self) -> Result<String, FigureError> {
        let (w, h) = (self.layout.w, self.layout.h);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (w as u32, h as u32)).into_drawing_area();
            self.draw_titles(&root)?;
            self.draw_grid_labels(&root)?;
            self.draw_panels(&root)?;
            self.draw_matrix_frame(&root)?;
            self.draw_wheel_ticks(&root)?;
            self.draw_colour_bars(&root)?;
            self.draw_reading_guide(&root)?;
            root.present().map_err(draw_err)?;
        }
        Ok(svg)
    }

    /// The title and the line under it.
    fn draw_titles(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let w = self.layout.w;
        let centre_top = Pos::new(HPos::Center, VPos::Top);
        let title_font = (FAMILY, 24).into_font().style(FontStyle::Bold);
        text(
            root,
            &self.opts.title,
            (w / 2.0, 10.0),
            &title_font,
            centre_top,
        )?;
        text(
            root,
            &format!(
                "{} expressed of {} possible links, drawn as receptive fields: {} {}{} → neurons {}",
                self.controller.expressed_links(),
                self.controller.possible_links(),
                self.nodes.first().label,
                self.nodes.first().grid(),
                self.nodes.bands_caption(),
                self.spec.neurons
            ),
            (w / 2.0, 42.0),
            &font(),
            centre_top,
        )
    }

    /// Column (angle) and row (ring) labels of the panel grid.
    fn draw_grid_labels(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (left, top, cw, ch) = self.layout.grid;
        let (rows, cols) = (self.rows, self.cols);
        let centre_bottom = Pos::new(HPos::Center, VPos::Bottom);
        text(
            root,
            "incoming weights of each neuron, by its angle →",
            (left + cw * cols as f64 / 2.0, top - 42.0),
            &font(),
            centre_bottom,
        )?;
        let every = ((60.0 / cw).ceil() as usize).max(1);
        for node in self.nodes.neurons.iter().filter(|n| n.ring == 0) {
            if node.angle_index % every == 0 || node.angle_index + 1 == cols {
                let (cx, _) = self
                    .layout
                    .centre(0, node.angle_index, self.half, self.outer);
                text(
                    root,
                    &format!("{:+.0}°", node.phi.to_degrees()),
                    (cx, top - 8.0),
                    &small(),
                    centre_bottom,
                )?;
            }
        }
        text(
            root,
            "ring ρ",
            (left - 10.0, top - 8.0),
            &small(),
            Pos::new(HPos::Right, VPos::Bottom),
        )?;
        let every_row = ((22.0 / ch).ceil() as usize).max(1);
        for ring in (0..rows).filter(|r| r % every_row == 0 || r + 1 == rows) {
            let row = rows - 1 - ring;
            text(
                root,
                &format!("{:.2}", self.spec.neurons.radius(ring)),
                (left - 10.0, top + ch * (row as f64 + 0.5)),
                &small(),
                Pos::new(HPos::Right, VPos::Center),
            )?;
        }
        Ok(())
    }

    /// Panel outlines, wheel neurons red (labelled L and R), bias dots.
    fn draw_panels(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (r, half) = (self.layout.radius, self.half);
        let wheels = &self.nodes.wheels;
        let dot = (r * 0.1).clamp(1.5, 5.0);
        for (i, node) in self.nodes.neurons.iter().enumerate() {
            let (cx, cy) = self.centre_of(i);
            let wheel = if i == wheels.left {
                Some("L")
            } else if i == wheels.right {
                Some("R")
            } else {
                None
            };
            let style = match wheel {
                Some(_) => WHEEL.stroke_width(3),
                None => GUIDE.stroke_width(1),
            };
            let outline: Vec<(i32, i32)> = std::iter::once((cx, cy))
                .chain((0..=48).map(|k| {
                    let phi = -half + 2.0 * half * f64::from(k) / 48.0;
                    (cx + r * phi.sin(), cy - r * phi.cos())
                }))
                .chain(std::iter::once((cx, cy)))
                .map(px)
                .collect();
            root.draw(&PathElement::new(outline, style))
                .map_err(draw_err)?;
            let bias = diverging(self.controller.biases()[i], self.bias_scale);
            root.draw(&Circle::new(px((cx, cy)), dot as i32, bias.filled()))
                .map_err(draw_err)?;
            root.draw(&Circle::new(
                px((cx, cy)),
                dot as i32,
                BLACK.stroke_width(1),
            ))
            .map_err(draw_err)?;
            if let Some(label) = wheel {
                let side = if node.phi < 0.0 { -1.0 } else { 1.0 };
                let at = (cx + side * (r * 0.75), cy - r * 0.95);
                root.draw(&Text::new(
                    label,
                    px(at),
                    (FAMILY, 18)
                        .into_font()
                        .style(FontStyle::Bold)
                        .color(&WHEEL)
                        .pos(Pos::new(HPos::Center, VPos::Center)),
                ))
                .map_err(draw_err)?;
            }
        }
        Ok(())
    }

    /// The recurrent matrix's captions, ring blocks and frame, and the bias row's frame.
    fn draw_matrix_frame(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (mx, my, side) = self.layout.matrix;
        let (rows, cols) = (self.rows, self.cols);
        let centre_bottom = Pos::new(HPos::Center, VPos::Bottom);
        text(
            root,
            "recurrent weights: column = from neuron, row = to neuron",
            (mx + side / 2.0, my - 26.0),
            &font(),
            centre_bottom,
        )?;
        text(
            root,
            "(neurons ring by ring from the inside, left to right)",
            (mx + side / 2.0, my - 6.0),
            &small(),
            centre_bottom,
        )?;
        let per = side / self.nodes.neurons.len() as f64;
        if self.spec.neurons.rings > 1 && per * cols as f64 >= 4.0 {
            for ring in 1..rows {
                let at = per * (ring * cols) as f64;
                for line in [
                    vec![px((mx + at, my)), px((mx + at, my + side))],
                    vec![px((mx, my + at)), px((mx + side, my + at))],
                ] {
                    root.draw(&PathElement::new(
                        line,
                        RGBColor(120, 120, 120).stroke_width(1),
                    ))
                    .map_err(draw_err)?;
                }
            }
        }
        root.draw(&Rectangle::new(
            [px((mx, my)), px((mx + side, my + side))],
            BLACK.stroke_width(1),
        ))
        .map_err(draw_err)?;
        let (by, bh) = self.layout.bias;
        root.draw(&Rectangle::new(
            [px((mx, by)), px((mx + side, by + bh))],
            BLACK.stroke_width(1),
        ))
        .map_err(draw_err)?;
        let right_mid = Pos::new(HPos::Right, VPos::Center);
        text(root, "bias", (mx - 8.0, by + bh / 2.0), &font(), right_mid)
    }

    /// The wheel neurons' ticks and L/R labels along the matrix and the bias row.
    fn draw_wheel_ticks(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (mx, my, side) = self.layout.matrix;
        let (by, bh) = self.layout.bias;
        let per = side / self.nodes.neurons.len() as f64;
        let wheels = &self.nodes.wheels;
        let wheel_font = (FAMILY, 16)
            .into_font()
            .style(FontStyle::Bold)
            .color(&WHEEL);
        for (i, label) in [(wheels.left, "L"), (wheels.right, "R")] {
            let c = mx + per * (i as f64 + 0.5);
            let rmid = my + per * (i as f64 + 0.5);
            for tick in [
                vec![px((c, my + side)), px((c, my + side + 8.0))],
                vec![px((mx - 8.0, rmid)), px((mx, rmid))],
                vec![px((c, by + bh)), px((c, by + bh + 8.0))],
            ] {
                root.draw(&PathElement::new(tick, WHEEL.stroke_width(3)))
                    .map_err(draw_err)?;
            }
            root.draw(&Text::new(
                label,
                px((c, by + bh + 10.0)),
                wheel_font.clone().pos(Pos::new(HPos::Center, VPos::Top)),
            ))
            .map_err(draw_err)?;
            root.draw(&Text::new(
                label,
                px((mx - 11.0, rmid)),
                wheel_font.clone().pos(Pos::new(HPos::Right, VPos::Center)),
            ))
            .map_err(draw_err)?;
        }
        Ok(())
    }

    /// The colour scales of the three blocks.
    fn draw_colour_bars(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (mx, _, side) = self.layout.matrix;
        let (by, bh) = self.layout.bias;
        let (left, top, cw, ch) = self.layout.grid;
        let bar_y = by + bh + 62.0;
        colour_bar(
            root,
            (mx + 110.0, bar_y),
            side - 190.0,
            "recurrent",
            self.recurrent_scale,
            &small(),
        )?;
        colour_bar(
            root,
            (mx + 110.0, bar_y + 34.0),
            side - 190.0,
            "bias",
            self.bias_scale,
            &small(),
        )?;
        let grid_bottom = top + ch * self.rows as f64;
        colour_bar(
            root,
            (left + 170.0, grid_bottom + 30.0),
            (cw * self.cols as f64 - 260.0).max(120.0),
            "sensor → neuron",
            self.input_scale,
            &small(),
        )
    }

    /// How to read the panels, along the bottom.
    fn draw_reading_guide(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let (left, _, _, _) = self.layout.grid;
        let mut lines = vec![
            "Each panel is one neuron: its weight from every sensor, drawn where the sensor looks (ahead is up, robot at the centre;".to_string(),
            "each wedge one sensor). The dot is the neuron's bias. Red outline, L/R: wheel neurons. White: no link (or 0).".to_string(),
        ];
        let bands: Vec<String> = self
            .nodes
            .bands()
            .map(|(_, s)| possessive(s.label))
            .collect();
        match bands.as_slice() {
            [] => {}
            [one] => lines.push(format!(
                "The outer band of each panel holds the {one} weights (same colour scale)."
            )),
            more => lines.push(format!(
                "The outer bands of each panel hold, from the inside out, the {} weights (same colour scale).",
                more.join(", ")
            )),
        }
        for (k, line) in lines.iter().enumerate() {
            text(
                root,
                line,
                (left - 40.0, self.layout.h - 70.0 + 22.0 * k as f64),
                &small(),
                Pos::new(HPos::Left, VPos::Center),
            )?;
        }
        Ok(())
    }
}

/// `label`'s possessive: "distance rays'", "speedometer's".
fn possessive(label: &str) -> String {
    if label.ends_with('s') {
        format!("{label}'")
    } else {
        format!("{label}'s")
    }
}

/// Paints `stencil`'s inputs in `colours` onto `grid`, its top left corner at
/// `(ox, oy)` pixels (clipped to the grid).
fn stamp(
    grid: &mut Pixmap,
    stencil: &Stencil,
    (ox, oy): (i32, i32),
    colours: &[PremultipliedColorU8],
) {
    let (gw, gh) = (grid.width() as i32, grid.height() as i32);
    let pixels = grid.pixels_mut();
    for (row, line) in stencil
        .input
        .chunks_exact(stencil.width as usize)
        .enumerate()
    {
        let y = oy + row as i32;
        if !(0..gh).contains(&y) {
            continue;
        }
        for (col, &input) in line.iter().enumerate() {
            let x = ox + col as i32;
            if input != OUTSIDE && (0..gw).contains(&x) {
                pixels[(y * gw + x) as usize] = colours[input as usize];
            }
        }
    }
}

/// Draws the figure: the vector overlay (labels, outlines; no background) and the heat maps.
fn draw(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<Drawn, FigureError> {
    register_font()?;
    let fields = Fields::new(spec, sheets, controller, opts)?;
    let mut heats = vec![fields.panels_heat()?];
    heats.extend(fields.matrix_heats()?);
    Ok(Drawn {
        overlay: fields.overlay()?,
        heats,
        size: (fields.layout.w, fields.layout.h),
    })
}

/// A horizontal colour bar from `−scale` through 0 to `+scale`, named `label`.
fn colour_bar(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    (x, y): (f64, f64),
    width: f64,
    label: &str,
    scale: f64,
    font: &FontDesc<'_>,
) -> Result<(), FigureError> {
    let steps = 41;
    let cell = width / steps as f64;
    for i in 0..steps {
        let v = scale * (-1.0 + 2.0 * i as f64 / (steps - 1) as f64);
        let x0 = x + cell * i as f64;
        root.draw(&Rectangle::new(
            [px((x0, y - 8.0)), px((x0 + cell + 0.5, y + 8.0))],
            diverging(v, scale).filled(),
        ))
        .map_err(draw_err)?;
    }
    root.draw(&Rectangle::new(
        [px((x, y - 8.0)), px((x + width, y + 8.0))],
        BLACK.stroke_width(1),
    ))
    .map_err(draw_err)?;
    let style = |pos| TextStyle::from(font.clone()).pos(pos);
    root.draw(&Text::new(
        format!("{label}  −{}", short(scale)),
        px((x - 6.0, y)),
        style(Pos::new(HPos::Right, VPos::Center)),
    ))
    .map_err(draw_err)?;
    root.draw(&Text::new(
        format!("+{}", short(scale)),
        px((x + width + 6.0, y)),
        style(Pos::new(HPos::Left, VPos::Center)),
    ))
    .map_err(draw_err)?;
    root.draw(&Text::new(
        "0",
        px((x + width / 2.0, y + 10.0)),
        style(Pos::new(HPos::Center, VPos::Top)),
    ))
    .map_err(draw_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wedges_split_halfway_between_nodes() {
        let b = wedge_bounds(&[-1.0, 0.0, 1.0], 1.0);
        assert_eq!(b, vec![-1.5, -0.5, 0.5, 1.5]);
        assert_eq!(wedge(&b, -1.5), Some(0));
        assert_eq!(wedge(&b, 0.0), Some(1));
        assert_eq!(wedge(&b, 1.49), Some(2));
        assert_eq!(wedge(&b, 1.5), None);
        assert_eq!(wedge(&b, f64::NAN), None);
        assert_eq!(wedge_bounds(&[0.0], 0.5), vec![-0.5, 0.5]);
        assert_eq!(wedge_bounds(&[], 0.5), Vec::<f64>::new());
    }

    #[test]
    fn outer_sensors_and_distance_rays_get_their_own_pixels() {
        use vivae_lab::substrate::PolarGrid;
        let spec = SubstrateSpec {
            sensors: PolarGrid::new(32, 96).unwrap(),
            distance_rays: Some(7),
            ..SubstrateSpec::default()
        };
        let sheets = FigureSheet::all(&spec.sheets());
        let (sensors, distance) = (&sheets[0].nodes, &sheets[1].nodes);
        let half = spec.fov.to_radians() / 2.0;
        // A panel as large as the 9×9 figure draws it (radius ≈ 90 pixels).
        let stencil = Stencil::new(90.0, half, &sheets);
        let mut seen = vec![0usize; sensors.len() + distance.len()];
        for &i in stencil.input.iter().filter(|&&i| i != OUTSIDE) {
            seen[i as usize] += 1;
        }
        // Wedges of inner rings are narrower than a pixel (true to the geometry:
        // they are that close together); every sensor of the outer half of the
        // rings and every distance ray has pixels of its own.
        let outer_half = sensors.iter().enumerate().filter(|(_, n)| n.ring >= 16);
        assert!(outer_half.clone().count() == 16 * 96);
        assert!(outer_half.into_iter().all(|(i, _)| seen[i] > 0));
        assert!(
            seen[sensors.len()..].iter().all(|&n| n > 0),
            "a ray has no pixel"
        );
        // The left-most outer sensor is drawn left of the centre, the right-most right of it.
        let column_of = |input: u32| {
            let at = stencil.input.iter().position(|&i| i == input).unwrap();
            at as i32 % stencil.width as i32 + stencil.x0
        };
        let outer_left = (31 * 96) as u32;
        assert!(column_of(outer_left) < 0 && column_of(outer_left + 95) > 0);
    }

    #[test]
    fn every_further_sheet_is_a_band_of_its_own() {
        let spec = SubstrateSpec {
            distance_rays: Some(5),
            ..SubstrateSpec::default()
        };
        let mut sheets = FigureSheet::all(&spec.sheets());
        let ahead = PolarNode {
            ring: 0,
            angle_index: 0,
            rho: 1.0,
            phi: 0.0,
        };
        sheets.push(FigureSheet {
            name: "speed",
            label: "speedometer",
            nodes: vec![ahead],
        });
        let radius = 90.0;
        let stencil = Stencil::new(radius, FRAC_PI_2, &sheets);
        let inputs = 15 + 5 + 1;
        let mut seen = vec![0usize; inputs];
        for &i in stencil.input.iter().filter(|&&i| i != OUTSIDE) {
            seen[i as usize] += 1;
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
        // The speedometer fills the third band, the whole half ring.
        let (r0, r1) = band_radii(2);
        assert!(r0 > band_radii(1).1);
        let row = |input: u32| {
            let at = stencil.input.iter().position(|&i| i == input).unwrap();
            at as i32 / stencil.width as i32 + stencil.y0
        };
        let top = -f64::from(row(20));
        assert!(top > r0 * radius - 2.0 && top <= r1 * radius + 1.0, "{top}");
        assert_eq!(outer_radius(sheets.len()), r1);
        assert_eq!(possessive("distance rays"), "distance rays'");
        assert_eq!(possessive("speedometer"), "speedometer's");
    }

    #[test]
    fn scales_and_labels() {
        assert_eq!(max_abs([0.5, -2.0, 1.0].into_iter()), 2.0);
        assert_eq!(max_abs([0.0, 0.0].into_iter()), 1.0);
        assert_eq!(short(2.9876), "2.99");
        assert_eq!(short(0.0146), "0.0146");
        assert_eq!(short(123.4), "123");
        assert_eq!(short(0.001), "1.00e-3");
        assert_eq!(diverging(0.0, 1.0), WHITE);
        assert_eq!(diverging(5.0, 1.0), POSITIVE);
        assert_eq!(diverging(-1.0, 1.0), NEGATIVE);
    }
}

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

mod geometry;
mod overlay;

use geometry::{Layout, OUTSIDE, Stencil, outer_radius};

use plotters::prelude::*;
use tiny_skia::{Pixmap, PixmapPaint, PremultipliedColorU8, Transform};
use vivae_neat::hyperneat::SubstrateController;

use super::controller::{Checked, FigureSheet, NetworkOptions, blend, check};
use super::{
    Figure, FigureError, NEGATIVE, PNG_SCALE, POSITIVE, base64, draw_svg_over, encode_png_fast,
    register_font, white_canvas,
};
use vivae_lab::controller::substrate::SubstrateSpec;

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
    let mut base = white_canvas(w, h)?;
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

#[cfg(test)]
mod tests {
    use super::overlay::possessive;
    use super::*;

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
        assert_eq!(possessive("distance rays"), "distance rays'");
        assert_eq!(possessive("speedometer"), "speedometer's");
    }
}

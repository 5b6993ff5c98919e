//! The receptive-field figure's vector overlay: titles, grid labels, panel
//! outlines, the matrix frame, wheel ticks, colour bars and the reading guide,
//! drawn over the heat maps.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{Fields, diverging, short};
use crate::figures::controller::{GUIDE, WHEEL, px};
use crate::figures::{FAMILY, FigureError, draw_err};

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

impl<'a> Fields<'a> {
    /// The vector overlay: labels, outlines and scales (no background), as SVG.
    pub(super) fn overlay(&self) -> Result<String, FigureError> {
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
pub(super) fn possessive(label: &str) -> String {
    if label.ends_with('s') {
        format!("{label}'")
    } else {
        format!("{label}'s")
    }
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

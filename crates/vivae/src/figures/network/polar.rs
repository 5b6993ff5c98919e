//! The dense controller drawn as its sheets: the input sheet(s) and the
//! neuron sheet as two stacked polar layers seen in perspective, a line per link.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use vivae_lab::controller::substrate::{PolarNode, SubstrateSpec};
use vivae_neat::hyperneat::{LinkSource, SubstrateController};

use super::legend::draw_legend;
use super::{Root, WHEEL_RING, draw_curved_arrow, link_style};
use crate::figures::controller::{
    Checked, FigureSheet, GUIDE, NetworkOptions, WHEEL, blend, check, px,
};
use crate::figures::{FAMILY, FigureError, NEGATIVE, POSITIVE, draw_err, register_font};

/// Display radius (fraction of the sheet radius) of the first ring of nodes
/// outside the inner panel (the second input sheet's, e.g. distance rays).
const BAND_RING: f64 = 1.13;
/// How much further out each further sheet's ring is.
const BAND_STEP: f64 = 0.13;

/// Display radius of the nodes of input sheet `band` (1 = the second sheet).
fn band_ring(band: usize) -> f64 {
    BAND_RING + BAND_STEP * (band - 1) as f64
}

/// Where one sheet is drawn: centre of its half-disc and its radius, in pixels.
#[derive(Clone, Copy)]
struct Panel {
    cx: f64,
    cy: f64,
    radius: f64,
    /// Vertical squash of the perspective view (1 = seen from above).
    squash: f64,
}

impl Panel {
    /// Pixel position of a point at radius `rho` (sheet units) and angle `phi`.
    fn at(&self, rho: f64, phi: f64) -> (f64, f64) {
        (
            self.cx + rho * phi.sin() * self.radius,
            self.cy - rho * phi.cos() * self.radius * self.squash,
        )
    }

    /// Pixel position of a node.
    fn node(&self, n: &PolarNode) -> (f64, f64) {
        self.at(n.rho, n.phi)
    }
}

/// What the figure is drawn from: the checked controller and substrate, and
/// where its two sheets go.
struct Scene<'a> {
    spec: &'a SubstrateSpec,
    controller: &'a SubstrateController,
    opts: &'a NetworkOptions,
    nodes: Checked,
    /// Figure size in units.
    w: f64,
    h: f64,
    neuron_panel: Panel,
    inputs_panel: Panel,
    /// Radius of a neuron's disc.
    neuron_r: f64,
}

impl<'a> Scene<'a> {
    fn new(
        spec: &'a SubstrateSpec,
        sheets: &[FigureSheet],
        controller: &'a SubstrateController,
        opts: &'a NetworkOptions,
    ) -> Result<Scene<'a>, FigureError> {
        let nodes = check(spec, sheets, controller, opts)?;
        let (w, h) = (f64::from(opts.width), f64::from(opts.height));
        // The two sheets stacked in perspective, input sheet below the neuron
        // sheet, so input→neuron links run between the layers instead of along
        // the sheets' baselines (where every ±90° node sits).
        let radius = (w * 0.3).min(h * 0.75);
        let squash = 0.5;
        let neuron_panel = Panel {
            cx: w * 0.55,
            cy: h * 0.44,
            radius,
            squash,
        };
        let inputs_panel = Panel {
            cx: w * 0.55,
            cy: h * 0.87,
            radius,
            squash,
        };
        // Smaller nodes for dense substrates (e.g. 9×9).
        let side = spec.neurons.rings.max(spec.neurons.angles) as f64;
        let neuron_r = (9.0 * (3.0 / side).sqrt()).clamp(4.0, 9.0).round();
        Ok(Scene {
            spec,
            controller,
            opts,
            nodes,
            w,
            h,
            neuron_panel,
            inputs_panel,
            neuron_r,
        })
    }

    /// The title and the count of links under it.
    fn draw_titles(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let title_font = (FAMILY, 24).into_font().style(FontStyle::Bold);
        let font = (FAMILY, 17).into_font();
        let centre_top = Pos::new(HPos::Center, VPos::Top);
        root.draw(&Text::new(
            self.opts.title.clone(),
            px((self.w / 2.0, 10.0)),
            TextStyle::from(title_font).pos(centre_top),
        ))
        .map_err(draw_err)?;
        root.draw(&Text::new(
            format!(
                "{} expressed of {} possible links",
                self.controller.expressed_links(),
                self.controller.possible_links()
            ),
            px((self.w / 2.0, 42.0)),
            TextStyle::from(font).pos(centre_top),
        ))
        .map_err(draw_err)
    }

    /// Every expressed link, weakest first so strong links stay visible on top.
    fn draw_links(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let Checked {
            inputs, neurons, ..
        } = &self.nodes;
        let (inputs_panel, neuron_panel) = (&self.inputs_panel, &self.neuron_panel);
        let neuron_r = self.neuron_r;
        let mut links: Vec<_> = self.controller.links().collect();
        links.sort_by(|a, b| a.weight.abs().total_cmp(&b.weight.abs()));
        // Fainter links for dense substrates (e.g. 9×9).
        let density = (300.0 / links.len().max(1) as f64).sqrt().clamp(0.2, 1.0);
        for link in &links {
            let style = link_style(link.weight, self.opts.weight_scale, density);
            let to = neuron_panel.node(&neurons[link.target]);
            match link.source {
                LinkSource::Input { sheet, index } => {
                    let node = &inputs[sheet].nodes[index];
                    let from = if sheet == 0 {
                        inputs_panel.node(node)
                    } else {
                        inputs_panel.at(band_ring(sheet), node.phi)
                    };
                    root.draw(&PathElement::new(vec![px(from), px(to)], style))
                        .map_err(draw_err)?;
                }
                LinkSource::Neuron(s) if s == link.target => {
                    // Self-loop: a small circle just outside the node, away from the centre.
                    let n = &neurons[s];
                    let (dx, dy) = (n.phi.sin(), -n.phi.cos() * neuron_panel.squash);
                    let norm = (dx * dx + dy * dy).sqrt().max(1e-9);
                    let (dx, dy) = (dx / norm, dy / norm);
                    let c = (to.0 + dx * neuron_r * 1.6, to.1 + dy * neuron_r * 1.6);
                    root.draw(&Circle::new(px(c), (neuron_r * 0.8) as i32, style))
                        .map_err(draw_err)?;
                }
                LinkSource::Neuron(s) => {
                    let from = neuron_panel.node(&neurons[s]);
                    draw_curved_arrow(root, from, to, neuron_r, style)?;
                }
            }
        }
        Ok(())
    }

    /// The nodes, on top of the links: the first sheet's grey, further
    /// sheets' (e.g. distance rays) dark squares, neurons filled by their
    /// bias, wheel neurons too but ringed red.
    fn draw_nodes(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let Checked {
            neurons, wheels, ..
        } = &self.nodes;
        for n in &self.nodes.first().nodes {
            root.draw(&Circle::new(
                px(self.inputs_panel.node(n)),
                6,
                RGBColor(150, 150, 150).filled(),
            ))
            .map_err(draw_err)?;
        }
        for (band, sheet) in self.nodes.bands() {
            for n in &sheet.nodes {
                let (x, y) = self.inputs_panel.at(band_ring(band), n.phi);
                root.draw(&Rectangle::new(
                    [px((x - 5.0, y - 5.0)), px((x + 5.0, y + 5.0))],
                    RGBColor(90, 90, 90).filled(),
                ))
                .map_err(draw_err)?;
            }
        }
        let neuron_r = self.neuron_r;
        for (i, n) in neurons.iter().enumerate() {
            let c = px(self.neuron_panel.node(n));
            let b = self.controller.biases()[i];
            let m = (b.abs() / self.opts.weight_scale).clamp(0.0, 1.0);
            let base = if b >= 0.0 { POSITIVE } else { NEGATIVE };
            root.draw(&Circle::new(
                c,
                neuron_r as i32,
                blend(base, m * 0.8).filled(),
            ))
            .map_err(draw_err)?;
            root.draw(&Circle::new(c, neuron_r as i32, BLACK.stroke_width(1)))
                .map_err(draw_err)?;
            if i == wheels.left || i == wheels.right {
                // The fill stays the bias: a wheel neuron is marked by a red ring.
                root.draw(&Circle::new(c, neuron_r as i32 + 4, WHEEL_RING))
                    .map_err(draw_err)?;
            }
        }
        Ok(())
    }

    /// L and R above-outside the wheel neurons, on a white patch to stay legible.
    fn draw_wheel_labels(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let wheel_font = (FAMILY, 17)
            .into_font()
            .style(FontStyle::Bold)
            .color(&WHEEL);
        let (neurons, wheels) = (&self.nodes.neurons, &self.nodes.wheels);
        let neuron_r = self.neuron_r;
        for (i, label, side) in [(wheels.left, "L", -1.0), (wheels.right, "R", 1.0)] {
            let (x, y) = self.neuron_panel.node(&neurons[i]);
            let at = (x + side * (neuron_r + 9.0), y - neuron_r - 11.0);
            root.draw(&Rectangle::new(
                [px((at.0 - 8.0, at.1 - 10.0)), px((at.0 + 8.0, at.1 + 10.0))],
                WHITE.mix(0.85).filled(),
            ))
            .map_err(draw_err)?;
            root.draw(&Text::new(
                label,
                px(at),
                wheel_font.clone().pos(Pos::new(HPos::Center, VPos::Center)),
            ))
            .map_err(draw_err)?;
        }
        Ok(())
    }

    /// The sheets' captions, left of the layers.
    fn draw_captions(&self, root: &Root<'_>) -> Result<(), FigureError> {
        let font = (FAMILY, 17).into_font();
        let left_top = Pos::new(HPos::Left, VPos::Center);
        let first = self.nodes.first();
        let mut input_caption = vec![first.label.to_string(), first.grid().to_string()];
        for (_, sheet) in self.nodes.bands() {
            input_caption.push(format!("+ {} {}", sheet.nodes.len(), sheet.label));
        }
        for (panel, lines) in [
            (&self.inputs_panel, input_caption),
            (
                &self.neuron_panel,
                vec!["neurons".to_string(), self.spec.neurons.to_string()],
            ),
        ] {
            let top = panel.cy - panel.radius * panel.squash * 0.5;
            for (i, line) in lines.into_iter().enumerate() {
                root.draw(&Text::new(
                    line,
                    px((self.w * 0.02, top + 22.0 * i as f64)),
                    TextStyle::from(font.clone()).pos(left_top),
                ))
                .map_err(draw_err)?;
            }
        }
        Ok(())
    }
}

/// Renders the figure with a line per link (at any size) as an SVG document.
pub fn render_svg(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    register_font()?;
    let scene = Scene::new(spec, sheets, controller, opts)?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (opts.width, opts.height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        scene.draw_titles(&root)?;
        // Guides: ring arcs and baseline of each sheet.
        let rings = scene.nodes.first().grid().rings;
        draw_guides(&root, &scene.inputs_panel, rings, spec.fov)?;
        draw_guides(
            &root,
            &scene.neuron_panel,
            spec.neurons.rings,
            spec.neuron_fov,
        )?;
        scene.draw_links(&root)?;
        scene.draw_nodes(&root)?;
        scene.draw_wheel_labels(&root)?;
        scene.draw_captions(&root)?;
        let small = (FAMILY, 15).into_font();
        let bands: Vec<&str> = scene.nodes.bands().map(|(_, s)| s.name).collect();
        draw_legend(&root, (scene.w, scene.h), &bands, small, opts.weight_scale)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// Draws a sheet's ring arcs over its field of view and its baseline.
fn draw_guides(
    root: &Root<'_>,
    panel: &Panel,
    rings: usize,
    fov_deg: f64,
) -> Result<(), FigureError> {
    let half = fov_deg.to_radians() / 2.0;
    let style = GUIDE.stroke_width(1);
    // The sheet itself, faintly filled.
    let outline: Vec<(i32, i32)> = std::iter::once((panel.cx, panel.cy))
        .chain((0..=64).map(|i| panel.at(1.0, -half + 2.0 * half * f64::from(i) / 64.0)))
        .map(px)
        .collect();
    root.draw(&Polygon::new(outline, RGBColor(246, 246, 246).filled()))
        .map_err(draw_err)?;
    for k in 0..rings {
        let rho = (k + 1) as f64 / rings as f64;
        let arc: Vec<(i32, i32)> = (0..=64)
            .map(|i| panel.at(rho, -half + 2.0 * half * f64::from(i) / 64.0))
            .map(px)
            .collect();
        root.draw(&PathElement::new(arc, style)).map_err(draw_err)?;
    }
    let ends = [
        panel.at(1.0, -half),
        (panel.cx, panel.cy),
        panel.at(1.0, half),
    ];
    root.draw(&PathElement::new(ends.map(px).to_vec(), style))
        .map_err(draw_err)?;
    Ok(())
}

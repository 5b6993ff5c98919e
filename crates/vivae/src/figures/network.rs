//! The network figure (the paper's Fig. 3): the input sheet(s) and the neuron
//! sheet drawn in their polar layout as two stacked layers seen in perspective
//! (straight ahead points into the page), every expressed link drawn
//! with width and opacity growing with |weight| (blue positive, orange
//! negative), recurrent links as arrows curving inside the neuron sheet,
//! self-loops as small loops, wheel neurons ringed red.
//!
//! Above [`NetworkOptions::max_links`] expressed links (a few hundred) lines
//! stop being readable and cost time and bytes per link, so [`render`] draws
//! the receptive-field form of [`super::fields`] instead.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use vivae_neat::hyperneat::{LinkSource, SubstrateController};

use super::controller::{Checked, GUIDE, WHEEL, blend, check, px};
pub use super::controller::{FigureSheet, NetworkOptions};
use super::{FAMILY, Figure, FigureError, NEGATIVE, POSITIVE, draw_err, register_font, svg_to_png};
use vivae_lab::es_controller::{EsController, EsSetup, RobotController};
use vivae_lab::experiment::Experiment;
use vivae_lab::substrate::{PolarNode, SubstrateSpec};
use vivae_neat::Network;

/// Display radius (fraction of the sheet radius) of the first ring of nodes
/// outside the inner panel (the second input sheet's, e.g. distance rays).
const BAND_RING: f64 = 1.13;
/// How much further out each further sheet's ring is.
const BAND_STEP: f64 = 0.13;

/// Display radius of the nodes of input sheet `band` (1 = the second sheet).
fn band_ring(band: usize) -> f64 {
    BAND_RING + BAND_STEP * (band - 1) as f64
}

/// Renders the controller decoded on `spec` as SVG and PNG: a line per link
/// up to `opts.max_links` expressed links, receptive fields above.
pub fn render(
    spec: &SubstrateSpec,
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<Figure, FigureError> {
    render_sheets(spec, &FigureSheet::all(&spec.sheets()), controller, opts)
}

/// As [`render`], for the controller decoded on the input `sheets` (any
/// number, e.g. an experiment's `sensors()`) and `spec`'s neuron sheet: the
/// first sheet is drawn as the inner panel, every further one outside it.
pub fn render_sheets(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<Figure, FigureError> {
    if draws_fields(controller, opts) {
        return super::fields::render(spec, sheets, controller, opts);
    }
    let svg = render_svg(spec, sheets, controller, opts)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

/// The SVG of [`render`]'s figure (either form), without drawing the PNG.
pub fn figure_svg(
    spec: &SubstrateSpec,
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    figure_svg_sheets(spec, &FigureSheet::all(&spec.sheets()), controller, opts)
}

/// The SVG of [`render_sheets`]'s figure (either form), without drawing the PNG.
pub fn figure_svg_sheets(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    if draws_fields(controller, opts) {
        super::fields::render_svg(spec, sheets, controller, opts)
    } else {
        render_svg(spec, sheets, controller, opts)
    }
}

/// Whether [`render`] draws `controller` as receptive fields.
pub fn draws_fields(controller: &SubstrateController, opts: &NetworkOptions) -> bool {
    controller.expressed_links() > opts.max_links
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

/// Link style for a weight: colour by sign, width and opacity by magnitude.
/// `density` ≤ 1 thins links out when there are very many of them.
fn link_style(w: f64, scale: f64, density: f64) -> ShapeStyle {
    let m = (w.abs() / scale).clamp(0.0, 1.0);
    let colour = if w >= 0.0 { POSITIVE } else { NEGATIVE };
    let max_extra = if density < 0.5 { 1.0 } else { 2.0 };
    colour
        .mix((0.15 + 0.75 * m) * density)
        .stroke_width(1 + (max_extra * m).round() as u32)
}

/// The drawing area of the figure.
type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

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

/// A recurrent link: a quadratic curve bending to its left (so `a→b` and
/// `b→a` do not overlap), with an arrowhead at the target's rim.
fn draw_curved_arrow(
    root: &Root<'_>,
    from: (f64, f64),
    to: (f64, f64),
    node_r: f64,
    style: ShapeStyle,
) -> Result<(), FigureError> {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = (dx * dx + dy * dy).sqrt().max(1e-9);
    // Left normal in screen coordinates (y down).
    let (nx, ny) = (dy / len, -dx / len);
    let bend = 0.18 * len;
    let ctrl = (
        (from.0 + to.0) / 2.0 + nx * bend,
        (from.1 + to.1) / 2.0 + ny * bend,
    );
    let point = |t: f64| {
        let u = 1.0 - t;
        (
            u * u * from.0 + 2.0 * u * t * ctrl.0 + t * t * to.0,
            u * u * from.1 + 2.0 * u * t * ctrl.1 + t * t * to.1,
        )
    };
    let curve: Vec<(i32, i32)> = (0..=16).map(|i| px(point(f64::from(i) / 16.0))).collect();
    root.draw(&PathElement::new(curve, style))
        .map_err(draw_err)?;
    // Arrowhead along the end tangent (to − ctrl), tip on the node's rim.
    let (tx, ty) = (to.0 - ctrl.0, to.1 - ctrl.1);
    let tl = (tx * tx + ty * ty).sqrt().max(1e-9);
    let (ux, uy) = (tx / tl, ty / tl);
    let tip = (to.0 - ux * node_r, to.1 - uy * node_r);
    let size = 7.0;
    let base = (tip.0 - ux * size, tip.1 - uy * size);
    let head = vec![
        px(tip),
        px((base.0 + uy * size * 0.45, base.1 - ux * size * 0.45)),
        px((base.0 - uy * size * 0.45, base.1 + ux * size * 0.45)),
    ];
    root.draw(&Polygon::new(head, style.color.filled()))
        .map_err(draw_err)?;
    Ok(())
}

/// The ring that marks a wheel neuron (its fill is its bias, like any neuron's).
const WHEEL_RING: ShapeStyle = ShapeStyle {
    color: RGBAColor(214, 39, 40, 1.0),
    filled: false,
    stroke_width: 4,
};

/// Legend along the bottom edge: what lines and nodes mean, and above it
/// self-loops and the bias colour scale.
fn draw_legend(
    root: &Root<'_>,
    (w, h): (f64, f64),
    bands: &[&str],
    font: FontDesc<'_>,
    scale: f64,
) -> Result<(), FigureError> {
    let y = h - 26.0;
    draw_legend_items(root, (w, y), bands, &font)?;
    draw_bias_legend(root, (w, y - 28.0), &font, scale)
}

/// The legend's bottom row, at height `y`: link colours, wheel neurons,
/// sensors (with the names of the sheets drawn as `bands`, if any).
fn draw_legend_items(
    root: &Root<'_>,
    (w, y): (f64, f64),
    bands: &[&str],
    font: &FontDesc<'_>,
) -> Result<(), FigureError> {
    let left = Pos::new(HPos::Left, VPos::Center);
    let mut x = w * 0.04;
    let mut item = |draw: &dyn Fn(f64) -> Result<(), FigureError>, text: &str, step: f64| {
        draw(x)?;
        root.draw(&Text::new(
            text.to_string(),
            px((x + 30.0, y)),
            TextStyle::from(font.clone()).pos(left),
        ))
        .map_err(draw_err)?;
        x += step;
        Ok::<(), FigureError>(())
    };
    let line = |c: RGBColor| {
        move |x: f64| {
            root.draw(&PathElement::new(
                vec![px((x, y)), px((x + 24.0, y))],
                c.stroke_width(3),
            ))
            .map_err(draw_err)
        }
    };
    item(&line(POSITIVE), "positive weight", 170.0)?;
    item(&line(NEGATIVE), "negative weight", 175.0)?;
    item(
        &|x| {
            let c = px((x + 12.0, y));
            root.draw(&Circle::new(c, 7, BLACK.stroke_width(1)))
                .map_err(draw_err)?;
            root.draw(&Circle::new(c, 11, WHEEL_RING)).map_err(draw_err)
        },
        "wheel neuron",
        150.0,
    )?;
    item(
        &|x| {
            root.draw(&Circle::new(
                px((x + 12.0, y)),
                6,
                RGBColor(150, 150, 150).filled(),
            ))
            .map_err(draw_err)
        },
        &if bands.is_empty() {
            "sensor".to_string()
        } else {
            format!("sensor (■ {})", bands.join(", "))
        },
        if bands.is_empty() { 110.0 } else { 210.0 },
    )?;
    Ok(())
}

/// The legend's second row, at height `y2`: what the rings beside neurons
/// are, and the bias colour scale.
fn draw_bias_legend(
    root: &Root<'_>,
    (w, y2): (f64, f64),
    font: &FontDesc<'_>,
    scale: f64,
) -> Result<(), FigureError> {
    let left = Pos::new(HPos::Left, VPos::Center);
    let x0 = w * 0.04;
    root.draw(&Circle::new(
        px((x0 + 12.0, y2)),
        7,
        POSITIVE.stroke_width(2),
    ))
    .map_err(draw_err)?;
    root.draw(&Text::new(
        "ring beside a neuron = self-loop (feeds its own output back; colour, width as links)",
        px((x0 + 30.0, y2)),
        TextStyle::from(font.clone()).pos(left),
    ))
    .map_err(draw_err)?;
    // Neuron fill: bias from −scale (full negative colour) through 0 (white) to +scale.
    let steps = 11;
    let cell = 14.0;
    let bar_x = w * 0.96 - cell * steps as f64 - 60.0;
    let label = |text: String, at: f64, pos: Pos| {
        root.draw(&Text::new(
            text,
            px((at, y2)),
            TextStyle::from(font.clone()).pos(pos),
        ))
        .map_err(draw_err)
    };
    label(
        format!("neuron fill = bias:  {:+}", -scale),
        bar_x - 6.0,
        Pos::new(HPos::Right, VPos::Center),
    )?;
    for i in 0..steps {
        let b = -1.0 + 2.0 * i as f64 / (steps - 1) as f64;
        let base = if b >= 0.0 { POSITIVE } else { NEGATIVE };
        let x = bar_x + cell * i as f64;
        root.draw(&Rectangle::new(
            [px((x, y2 - 7.0)), px((x + cell, y2 + 7.0))],
            blend(base, b.abs() * 0.8).filled(),
        ))
        .map_err(draw_err)?;
    }
    root.draw(&Rectangle::new(
        [
            px((bar_x, y2 - 7.0)),
            px((bar_x + cell * steps as f64, y2 + 7.0)),
        ],
        BLACK.stroke_width(1),
    ))
    .map_err(draw_err)?;
    label(
        format!("{:+}", scale),
        bar_x + cell * steps as f64 + 6.0,
        left,
    )?;
    Ok(())
}

/// Renders `experiment`'s controller `controller`, dense or ES, as SVG and PNG.
pub fn render_robot(
    experiment: &Experiment,
    controller: &RobotController,
    opts: &NetworkOptions,
) -> Result<Figure, FigureError> {
    match (controller, experiment.es_setup()) {
        (RobotController::Es(c), Some(setup)) => {
            let svg = render_es_svg(setup, c, opts)?;
            let png = svg_to_png(&svg)?;
            Ok(Figure { svg, png })
        }
        (RobotController::Polar(c), None) => render_sheets(
            experiment.substrate_spec(),
            &FigureSheet::all(experiment.sensors()),
            c,
            opts,
        ),
        _ => Err(FigureError::Invalid(
            "the controller is not of the experiment's substrate kind".into(),
        )),
    }
}

/// The SVG of [`render_robot`]'s figure, without drawing the PNG.
pub fn figure_svg_robot(
    experiment: &Experiment,
    controller: &RobotController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    match (controller, experiment.es_setup()) {
        (RobotController::Es(c), Some(setup)) => render_es_svg(setup, c, opts),
        (RobotController::Polar(c), None) => figure_svg_sheets(
            experiment.substrate_spec(),
            &FigureSheet::all(experiment.sensors()),
            c,
            opts,
        ),
        _ => Err(FigureError::Invalid(
            "the controller is not of the experiment's substrate kind".into(),
        )),
    }
}

/// The ES plane seen from above: CPPN coordinates `[−1, 1]²` (x right,
/// y ahead) mapped onto a square panel.
struct Plane {
    cx: f64,
    cy: f64,
    half: f64,
}

impl Plane {
    fn at(&self, [x, y]: [f64; 2]) -> (f64, f64) {
        (self.cx + x * self.half, self.cy - y * self.half)
    }
}

/// The ES-HyperNEAT controller drawn where its nodes are: sensors grey,
/// discovered hidden neurons filled by their bias, wheel neurons ringed red,
/// every link a curved arrow (weakest first, thinned out when there are many).
pub fn render_es_svg(
    setup: &EsSetup,
    controller: &EsController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    register_font()?;
    let net = controller.network();
    let (ni, no) = (setup.layout.inputs.len(), setup.layout.outputs.len());
    if net.num_inputs() != ni || net.num_outputs() != no {
        return Err(FigureError::Invalid(
            "the ES network does not fit the experiment's sensors and wheels".into(),
        ));
    }
    let (w, h) = (f64::from(opts.width), f64::from(opts.height));
    let plane = Plane {
        cx: w / 2.0,
        cy: 78.0 + (h - 150.0) / 2.0,
        half: ((h - 150.0) / 2.0).min(w * 0.45),
    };
    let position = |node: usize| -> [f64; 2] {
        if node < ni {
            setup.layout.inputs[node]
        } else if node < ni + no {
            setup.layout.outputs[node - ni]
        } else {
            net.hidden()[node - ni - no]
        }
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (opts.width, opts.height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        draw_es_titles(&root, w, opts, controller)?;
        draw_es_frame(&root, &plane)?;
        let mut links: Vec<_> = net.links().to_vec();
        links.sort_by(|a, b| a.weight.abs().total_cmp(&b.weight.abs()));
        // Past a few thousand lines a figure only gets bigger, not clearer:
        // the strongest are drawn (the subtitle says so).
        let links = &links[links.len().saturating_sub(es_drawn_links(opts))..];
        let density = (opts.max_links as f64 / links.len().max(1) as f64).min(1.0);
        let node_r = (5.0 * (15.0 / ni as f64).sqrt()).clamp(1.5, 5.0);
        for l in links {
            let (a, b) = (plane.at(position(l.source)), plane.at(position(l.target)));
            let style = link_style(l.weight, opts.weight_scale, density);
            draw_curved_arrow(&root, a, b, node_r + 2.0, style)?;
        }
        draw_es_nodes(&root, &plane, setup, net, (node_r, opts.weight_scale))?;
        let small = (FAMILY, 15).into_font();
        draw_legend_items(&root, (w, h - 26.0), &[], &small)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// The ES figure's nodes: sensors, hidden neurons filled by their bias, and
/// the wheel neurons ringed red and labelled.
fn draw_es_nodes(
    root: &Root<'_>,
    plane: &Plane,
    setup: &EsSetup,
    net: &vivae_neat::hyperneat::SparseNetwork,
    (node_r, weight_scale): (f64, f64),
) -> Result<(), FigureError> {
    let no = setup.layout.outputs.len();
    let sensor = RGBColor(150, 150, 150).filled();
    for &p in &setup.layout.inputs {
        root.draw(&Circle::new(px(plane.at(p)), node_r.round() as i32, sensor))
            .map_err(draw_err)?;
    }
    let biases = net.biases();
    let bias_fill = |b: f64| {
        let m = (b.abs() / weight_scale).clamp(0.0, 1.0);
        blend(if b >= 0.0 { POSITIVE } else { NEGATIVE }, 0.15 + 0.85 * m).filled()
    };
    for (k, &p) in net.hidden().iter().enumerate() {
        let c = px(plane.at(p));
        root.draw(&Circle::new(c, 6, bias_fill(biases[no + k])))
            .map_err(draw_err)?;
        root.draw(&Circle::new(c, 6, BLACK.stroke_width(1)))
            .map_err(draw_err)?;
    }
    for (k, &p) in setup.layout.outputs.iter().enumerate() {
        let c = px(plane.at(p));
        root.draw(&Circle::new(c, 8, bias_fill(biases[k])))
            .map_err(draw_err)?;
        root.draw(&Circle::new(c, 8, BLACK.stroke_width(1)))
            .map_err(draw_err)?;
        root.draw(&Circle::new(c, 12, WHEEL_RING))
            .map_err(draw_err)?;
        let label = if k == 0 { "L" } else { "R" };
        let font = (FAMILY, 20).into_font().style(FontStyle::Bold);
        root.draw(&Text::new(
            label.to_string(),
            px((c.0 as f64, c.1 as f64 + 16.0)),
            TextStyle::from(font)
                .color(&WHEEL)
                .pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(draw_err)?;
    }
    Ok(())
}

/// Most links the ES figure draws: ten times the dense figure's line limit.
fn es_drawn_links(opts: &NetworkOptions) -> usize {
    opts.max_links * 10
}

/// The title, and the hidden neurons and links under it.
fn draw_es_titles(
    root: &Root<'_>,
    w: f64,
    opts: &NetworkOptions,
    controller: &EsController,
) -> Result<(), FigureError> {
    let title_font = (FAMILY, 24).into_font().style(FontStyle::Bold);
    let font = (FAMILY, 17).into_font();
    let centre_top = Pos::new(HPos::Center, VPos::Top);
    root.draw(&Text::new(
        opts.title.clone(),
        px((w / 2.0, 10.0)),
        TextStyle::from(title_font).pos(centre_top),
    ))
    .map_err(draw_err)?;
    let recurrent = if controller.network().is_recurrent() {
        ", recurrent"
    } else {
        ""
    };
    let links = controller.expressed_links();
    let drawn = es_drawn_links(opts);
    let strongest = if links > drawn {
        format!(" (the strongest {drawn} drawn)")
    } else {
        String::new()
    };
    root.draw(&Text::new(
        format!(
            "ES-HyperNEAT: {} hidden neurons found, {links} links{strongest}{recurrent}; seen from above, ahead is up",
            controller.hidden_neurons(),
        ),
        px((w / 2.0, 42.0)),
        TextStyle::from(font).pos(centre_top),
    ))
    .map_err(draw_err)
}

/// The plane's square, its axes and the unit circle the sensors lie within.
fn draw_es_frame(root: &Root<'_>, plane: &Plane) -> Result<(), FigureError> {
    let style = GUIDE.stroke_width(1);
    let corners = [
        [-1.0, -1.0],
        [1.0, -1.0],
        [1.0, 1.0],
        [-1.0, 1.0],
        [-1.0, -1.0],
    ];
    let square: Vec<(i32, i32)> = corners.iter().map(|&c| px(plane.at(c))).collect();
    root.draw(&Polygon::new(
        square.clone(),
        RGBColor(248, 248, 248).filled(),
    ))
    .map_err(draw_err)?;
    root.draw(&PathElement::new(square, style))
        .map_err(draw_err)?;
    for axis in [[[-1.0, 0.0], [1.0, 0.0]], [[0.0, -1.0], [0.0, 1.0]]] {
        let line: Vec<(i32, i32)> = axis.iter().map(|&c| px(plane.at(c))).collect();
        root.draw(&PathElement::new(line, style))
            .map_err(draw_err)?;
    }
    for rho in [1.0 / 3.0, 2.0 / 3.0, 1.0] {
        let circle: Vec<(i32, i32)> = (0..=96)
            .map(|i| {
                let t = std::f64::consts::TAU * f64::from(i) / 96.0;
                px(plane.at([rho * t.cos(), rho * t.sin()]))
            })
            .collect();
        root.draw(&PathElement::new(circle, style))
            .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};
    use vivae_lab::substrate::PolarGrid;
    use vivae_neat::Network;
    use vivae_neat::hyperneat::{HyperParams, decode};

    /// A hand-written CPPN with structured weights: left sensors drive left
    /// neurons, right drive right, with negative cross-talk and recurrence.
    struct Cppn(usize);

    impl Network for Cppn {
        fn num_inputs(&self) -> usize {
            5
        }
        fn num_outputs(&self) -> usize {
            self.0
        }
        fn activate(&mut self, q: &[f64], out: &mut [f64]) {
            let (x1, y1, x2, y2) = (q[0], q[1], q[2], q[3]);
            out[0] = (2.5 * x1 * x2 + 0.8 * y2 - 0.6).tanh();
            out[1] = (1.5 * y1 - 0.8).tanh();
            out[2] =
                (-4.0 * ((x1 - x2).powi(2) + (y1 - y2).powi(2)) + 1.0).tanh() * (x1 * 3.0).cos();
            if self.0 > 3 {
                out[3] = (-2.0 * x1 * x2).tanh();
            }
        }
        fn reset(&mut self) {}
    }

    fn sheets(spec: &SubstrateSpec) -> Vec<FigureSheet> {
        FigureSheet::all(&spec.sheets())
    }

    fn controller(spec: &SubstrateSpec) -> SubstrateController {
        let layout = spec.layout().unwrap();
        decode(
            &mut Cppn(spec.cppn_outputs()),
            &layout,
            &HyperParams::default(),
        )
        .unwrap()
    }

    #[test]
    fn renders_the_paper_substrate() {
        let spec = SubstrateSpec::default();
        let c = controller(&spec);
        assert!(c.expressed_links() > 10, "test CPPN should express links");
        let fig = render(&spec, &c, &NetworkOptions::default()).unwrap();
        assert_eq!(png_size(&fig.png), (2000, 1440));
        assert!(distinct_colours(&fig.png) > 50);
        let count = format!(
            "{} expressed of {} possible links",
            c.expressed_links(),
            9 * 24
        );
        for label in [
            count.as_str(),
            "surface sensors",
            ">\n3x5\n<",
            ">\nneurons\n<",
            ">\n3x3\n<",
            "wheel neuron",
            ">\nL\n<",
            ">\nR\n<",
            "= self-loop",
            "neuron fill = bias:  -3",
            ">\n+3\n<",
        ] {
            assert!(fig.svg.contains(label), "missing {label:?}");
        }
        // Wheel neurons are filled by their bias like any neuron, and ringed red.
        let circles: Vec<&str> = fig.svg.split("<circle").skip(1).collect();
        let red_fill = circles.iter().filter(|c| {
            let tag = &c[..c.find('>').unwrap()];
            tag.contains("fill=\"#D62728\"") && !tag.contains("fill-opacity=\"0")
        });
        assert_eq!(red_fill.count(), 0);
        let red_rings = circles
            .iter()
            .filter(|c| c[..c.find('>').unwrap()].contains("stroke=\"#D62728\""));
        assert!(red_rings.count() >= 3);
    }

    #[test]
    fn renders_a_resampled_substrate_with_distance_sensors() {
        let spec = SubstrateSpec {
            sensors: PolarGrid::new(3, 6).unwrap(),
            neurons: PolarGrid::new(9, 9).unwrap(),
            distance_rays: Some(7),
            ..SubstrateSpec::default()
        };
        let c = controller(&spec);
        let svg = render_svg(&spec, &sheets(&spec), &c, &NetworkOptions::default()).unwrap();
        for label in [">\n3x6\n<", "+ 7 distance rays", ">\n9x9\n<"] {
            assert!(svg.contains(label), "missing {label:?}");
        }
        // Every expressed link other than a self-loop is one polyline.
        let self_loops = c
            .links()
            .filter(|l| l.source == LinkSource::Neuron(l.target))
            .count();
        assert!(c.expressed_links() > 1000);
        assert!(svg.matches("<polyline").count() >= c.expressed_links() - self_loops);
    }

    #[test]
    fn mismatched_controller_is_an_error() {
        let spec = SubstrateSpec::default();
        let other = SubstrateSpec {
            neurons: PolarGrid::new(9, 9).unwrap(),
            ..SubstrateSpec::default()
        };
        let e = render_svg(
            &spec,
            &sheets(&spec),
            &controller(&other),
            &NetworkOptions::default(),
        )
        .unwrap_err();
        assert!(matches!(e, FigureError::Invalid(_)), "{e}");
    }

    /// A one-reading sensor (the robot's speed), as docs/architecture.md's
    /// "A new sensor" adds one.
    #[derive(Debug)]
    struct Speedometer([vivae_sim::SensorPlace; 1]);

    impl vivae_sim::Sensor for Speedometer {
        fn name(&self) -> &'static str {
            "speed"
        }
        fn rings(&self) -> usize {
            1
        }
        fn places(&self) -> &[vivae_sim::SensorPlace] {
            &self.0
        }
        fn read(&self, world: &vivae_sim::World, robot: usize, out: &mut [f64]) {
            out[0] = world.robots()[robot].speed / world.params().v_max;
        }
    }

    #[test]
    fn network_figure_draws_an_extra_sheet() {
        use std::sync::Arc;
        use vivae_lab::config::Config;
        use vivae_lab::sensors::{SensorSheet, sensor_sheets};
        use vivae_lab::substrate::{cppn_outputs, layout_of};
        use vivae_neat::hyperneat::decode_genome;
        use vivae_neat::{GenomeSpec, NeatParams, Population};

        let place = vivae_sim::SensorPlace {
            ring: 0,
            angle_index: 0,
            distance: 0.0,
            angle: 0.0,
        };
        let mut sheets = sensor_sheets(&Config::default());
        sheets.push(SensorSheet {
            sensor: Arc::new(Speedometer([place])),
            cppn_output: 4,
            reference_len: 1,
            label: "speedometer",
        });
        let spec = SubstrateSpec::default();
        let layout = layout_of(&sheets, &spec.neuron_nodes(), spec.coords);
        let cppn = GenomeSpec {
            outputs: cppn_outputs(&sheets),
            ..GenomeSpec::cppn()
        };
        assert_eq!(cppn.outputs, 5);
        let population = Population::new(NeatParams::default(), cppn, 7).unwrap();
        let genome = &population.genomes()[0];
        let c = decode_genome(genome, &layout, &HyperParams::default()).unwrap();
        assert_eq!(c.sheet_sizes(), &[15, 1]);
        let figure_sheets = FigureSheet::all(&sheets);
        assert_eq!(figure_sheets[1].name, "speed");

        // A line per link: the extra sheet's caption and its one node, a dark square.
        let opts = NetworkOptions::default();
        assert!(!draws_fields(&c, &opts));
        let fig = render_sheets(&spec, &figure_sheets, &c, &opts).unwrap();
        for label in [
            ">\nsurface sensors\n<",
            ">\n+ 1 speedometer\n<",
            "sensor (■ speed)",
        ] {
            assert!(fig.svg.contains(label), "missing {label:?}");
        }
        assert_eq!(fig.svg.matches("fill=\"#5A5A5A\"").count(), 1);
        assert_eq!(png_size(&fig.png), (2000, 1440));
        assert!(distinct_colours(&fig.png) > 20);

        // Receptive fields: the extra sheet is a band of each panel.
        let opts = NetworkOptions {
            max_links: 0,
            ..NetworkOptions::default()
        };
        let fig = render_sheets(&spec, &figure_sheets, &c, &opts).unwrap();
        for label in [
            "surface sensors 3x5 + 1 speedometer → neurons 3x3",
            "holds the speedometer&apos;s weights",
        ] {
            assert!(fig.svg.contains(label), "missing {label:?}");
        }
        assert_eq!(png_size(&fig.png), (3200, 2304));
        assert!(distinct_colours(&fig.png) > 20);

        // Without the extra sheet, the controller does not fit.
        let e = render_sheets(&spec, &figure_sheets[..1], &c, &opts).unwrap_err();
        assert!(matches!(e, FigureError::Invalid(_)), "{e}");
    }

    /// Writes sample figures: `VIVAE_FIGURE_DIR=/tmp cargo test ... -- --ignored`.
    #[test]
    #[ignore]
    fn write_sample() {
        let dir = std::env::var("VIVAE_FIGURE_DIR").unwrap_or_else(|_| "/tmp".into());
        for (name, spec) in [
            ("network", SubstrateSpec::default()),
            (
                "network-9x9",
                SubstrateSpec {
                    neurons: PolarGrid::new(9, 9).unwrap(),
                    distance_rays: Some(5),
                    ..SubstrateSpec::default()
                },
            ),
        ] {
            let fig = render(&spec, &controller(&spec), &NetworkOptions::default()).unwrap();
            std::fs::write(format!("{dir}/{name}.png"), fig.png).unwrap();
            std::fs::write(format!("{dir}/{name}.svg"), fig.svg).unwrap();
        }
    }
}

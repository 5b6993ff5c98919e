//! The ES-HyperNEAT controller drawn where its nodes are, on the CPPN plane
//! seen from above.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use vivae_lab::controller::es::{EsController, EsSetup};
use vivae_neat::Network;

use super::legend::draw_legend_items;
use super::{Root, WHEEL_RING, draw_curved_arrow, link_style};
use crate::figures::controller::{GUIDE, NetworkOptions, WHEEL, blend, px};
use crate::figures::{FAMILY, FigureError, NEGATIVE, POSITIVE, draw_err, register_font};

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

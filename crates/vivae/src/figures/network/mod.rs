//! The network figure (the paper's Fig. 3): the input sheet(s) and the neuron
//! sheet drawn in their polar layout as two stacked layers seen in perspective
//! (straight ahead points into the page), every expressed link drawn
//! with width and opacity growing with |weight| (blue positive, orange
//! negative), recurrent links as arrows curving inside the neuron sheet,
//! self-loops as small loops, wheel neurons ringed red.
//!
//! Above [`NetworkOptions::max_links`] expressed links (a few hundred) lines
//! stop being readable and cost time and bytes per link, so [`render`] draws
//! the receptive-field form of `super::fields` instead.
//!
//! `polar` draws the dense controller's sheets, `es` an ES-HyperNEAT
//! controller, `legend` the legend both share; this file chooses the form
//! and holds the strokes they share.

mod es;
mod legend;
mod polar;

pub use es::render_es_svg;
pub use polar::render_svg;

use plotters::coord::Shift;
use plotters::prelude::*;
use vivae_neat::hyperneat::SubstrateController;

use super::controller::px;
pub use super::controller::{FigureSheet, NetworkOptions};
use super::{Figure, FigureError, NEGATIVE, POSITIVE, draw_err, svg_to_png};
use vivae_lab::controller::es::{EsSetup, RobotController};
use vivae_lab::controller::sensors::SensorSheet;
use vivae_lab::controller::substrate::SubstrateSpec;

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

/// A robot's substrate as its network figure draws it: the dense
/// substrate and the sensor sheets feeding it, and the ES-HyperNEAT setup
/// of a robot decoded that way.
#[derive(Debug, Clone, Copy)]
pub struct RobotSubstrate<'a> {
    /// The dense substrate's layout.
    pub spec: &'a SubstrateSpec,
    /// The sensor sheets, in controller-input order.
    pub sensors: &'a [SensorSheet],
    /// The ES-HyperNEAT setup (none: a dense substrate).
    pub es: Option<&'a EsSetup>,
}

/// Renders the controller `controller` of a robot on `robot`, dense or ES, as SVG and PNG.
pub fn render_robot(
    robot: RobotSubstrate<'_>,
    controller: &RobotController,
    opts: &NetworkOptions,
) -> Result<Figure, FigureError> {
    match (controller, robot.es) {
        (RobotController::Es(c), Some(setup)) => {
            let svg = render_es_svg(setup, c, opts)?;
            let png = svg_to_png(&svg)?;
            Ok(Figure { svg, png })
        }
        (RobotController::Polar(c), None) => {
            render_sheets(robot.spec, &FigureSheet::all(robot.sensors), c, opts)
        }
        _ => Err(FigureError::Invalid(
            "the controller is not of the experiment's substrate kind".into(),
        )),
    }
}

/// The SVG of [`render_robot`]'s figure, without drawing the PNG.
pub fn figure_svg_robot(
    robot: RobotSubstrate<'_>,
    controller: &RobotController,
    opts: &NetworkOptions,
) -> Result<String, FigureError> {
    match (controller, robot.es) {
        (RobotController::Es(c), Some(setup)) => render_es_svg(setup, c, opts),
        (RobotController::Polar(c), None) => {
            figure_svg_sheets(robot.spec, &FigureSheet::all(robot.sensors), c, opts)
        }
        _ => Err(FigureError::Invalid(
            "the controller is not of the experiment's substrate kind".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};
    use vivae_lab::controller::substrate::PolarGrid;
    use vivae_neat::Network;
    use vivae_neat::hyperneat::LinkSource;
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
        use vivae_lab::controller::sensors::{SensorSheet, sensor_sheets};
        use vivae_lab::controller::substrate::{cppn_outputs, layout_of};
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

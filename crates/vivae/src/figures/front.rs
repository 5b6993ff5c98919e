//! NSGA-II's Pareto front over two objectives: every scored member of the
//! last generation (parents and children) as a grey point, the first
//! non-dominated front highlighted, joined in order of the first objective
//! and numbered as `vivae replay --front N` and `vivae view --front N` number it.

use plotters::prelude::*;

use super::{FAMILY, Figure, FigureError, draw_err, register_font, svg_to_png};

/// Two objectives of a population and its front, to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontPlot {
    /// Figure title.
    pub title: String,
    /// Axis names of the two objectives (x, then y), units and sense included.
    pub axes: [String; 2],
    /// Every scored member's two objective values, as measured.
    pub population: Vec<[f64; 2]>,
    /// The front's members' values, in member order (0 = the fittest).
    pub front: Vec<[f64; 2]>,
}

/// The axis name of objective `name` as configs write it (`fitness`,
/// `-contacts`, …): what it measures, its unit, and whether it is maximised.
pub fn objective_axis(name: &str) -> String {
    let (what, sense) = match name.strip_prefix('-') {
        Some(min) => (min, "minimised"),
        None => (name, "maximised"),
    };
    let what = match what {
        "fitness" => "fitness (px/step)",
        "contacts" => "contacts per 1,000 robot-steps",
        "on_road" => "share of robot-steps on road",
        other => other,
    };
    format!("{what}, {sense}")
}

/// Most front members numbered on the figure (more would overlap).
const MAX_LABELS: usize = 16;
/// Colour of the front (the convergence figure's mean-curve orange).
const FRONT: RGBColor = RGBColor(230, 97, 1);
/// Colour of the population's points.
const POPULATION: RGBColor = RGBColor(150, 150, 150);

/// Renders the figure (SVG and PNG).
pub fn render(plot: &FrontPlot) -> Result<Figure, FigureError> {
    let svg = draw(plot)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

/// The range of `values` (finite ones; a non-finite objective is recorded as
/// ±`f64::MAX`), padded by 6% on each side.
fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let finite = values.filter(|v| v.is_finite() && v.abs() < 1e300);
    let (lo, hi) = finite.fold(None, |acc: Option<(f64, f64)>, v| {
        Some(acc.map_or((v, v), |(l, h)| (l.min(v), h.max(v))))
    })?;
    let pad = if hi - lo > 1e-12 {
        0.06 * (hi - lo)
    } else {
        0.5_f64.max(0.06 * lo.abs())
    };
    Some((lo - pad, hi + pad))
}

/// The front's distinct points, each with the members on it: `4`, `3–7`
/// (members with equal objectives are usually neighbours in fitness order)
/// or `3, 9`.
fn member_points(front: &[[f64; 2]]) -> Vec<([f64; 2], String)> {
    let mut points: Vec<([f64; 2], Vec<usize>)> = Vec::new();
    for (i, v) in front.iter().enumerate() {
        match points.iter_mut().find(|(p, _)| p == v) {
            Some((_, members)) => members.push(i),
            None => points.push((*v, vec![i])),
        }
    }
    let label = |m: &[usize]| match m {
        [one] => one.to_string(),
        [first, .., last] if last - first + 1 == m.len() => format!("{first}–{last}"),
        [first, second] => format!("{first}, {second}"),
        [first, ..] => format!("{first}, … ({} members)", m.len()),
        [] => String::new(),
    };
    (points.into_iter()).map(|(v, m)| (v, label(&m))).collect()
}

fn draw(p: &FrontPlot) -> Result<String, FigureError> {
    register_font()?;
    let all = || p.population.iter().chain(&p.front);
    let (Some(x), Some(y)) = (range(all().map(|v| v[0])), range(all().map(|v| v[1]))) else {
        return Err(FigureError::NoData("no finite objective values"));
    };
    let inside = |v: &&[f64; 2]| (x.0..=x.1).contains(&v[0]) && (y.0..=y.1).contains(&v[1]);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (820, 620)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let root = (root.titled(&p.title, (FAMILY, 20).into_font().style(FontStyle::Bold)))
            .map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&root)
            .margin(16)
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(draw_err)?;
        (chart.configure_mesh())
            .light_line_style(WHITE)
            .x_desc(p.axes[0].as_str())
            .y_desc(p.axes[1].as_str())
            .axis_desc_style((FAMILY, 17).into_font())
            .label_style((FAMILY, 14).into_font())
            .draw()
            .map_err(draw_err)?;
        let dots = p.population.iter().filter(inside);
        (chart.draw_series(dots.map(|v| Circle::new((v[0], v[1]), 3, POPULATION.filled()))))
            .map_err(draw_err)?
            .label(format!("population ({} scored)", p.population.len()))
            .legend(|(x, y)| Circle::new((x + 8, y), 4, POPULATION.filled()));
        let mut joined: Vec<(f64, f64)> = (p.front.iter().filter(inside))
            .map(|v| (v[0], v[1]))
            .collect();
        joined.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        chart
            .draw_series(LineSeries::new(joined, FRONT.stroke_width(2)))
            .map_err(draw_err)?;
        let front = p.front.iter().filter(inside);
        (chart.draw_series(front.map(|v| Circle::new((v[0], v[1]), 6, FRONT.filled()))))
            .map_err(draw_err)?
            .label(match member_points(&p.front).len() {
                n if n < p.front.len() => {
                    format!("Pareto front ({} members at {n} points)", p.front.len())
                }
                _ => format!("Pareto front ({} members)", p.front.len()),
            })
            .legend(|(x, y)| Circle::new((x + 8, y), 6, FRONT.filled()));
        let points = member_points(&p.front);
        if points.len() <= MAX_LABELS {
            let labels = points.iter().filter(|(v, _)| inside(&v));
            let font = (FAMILY, 14).into_font().color(&BLACK);
            (chart.draw_series(labels.map(|(v, label)| {
                EmptyElement::at((v[0], v[1])) + Text::new(label.clone(), (8, -18), font.clone())
            })))
            .map_err(draw_err)?;
        }
        (chart.configure_series_labels())
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(190, 190, 190))
            .label_font((FAMILY, 14).into_font())
            .draw()
            .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};

    #[test]
    fn objectives_are_named_with_units_and_sense() {
        assert_eq!(objective_axis("fitness"), "fitness (px/step), maximised");
        assert_eq!(
            objective_axis("-contacts"),
            "contacts per 1,000 robot-steps, minimised"
        );
    }

    #[test]
    fn front_figure_draws_population_and_front_and_refuses_nothing_finite() {
        let plot = FrontPlot {
            title: "front".into(),
            axes: ["fitness".into(), "contacts".into()],
            population: vec![[1.0, 3.0], [2.0, 1.0], [0.5, 0.5], [f64::MAX, 0.0]],
            front: vec![[3.0, 2.0], [2.0, 0.5], [2.0, 0.5], [0.5, 0.1]],
        };
        let f = render(&plot).unwrap();
        assert!(png_size(&f.png).0 > 800);
        assert!(distinct_colours(&f.png) > 10);
        let labels = [
            "Pareto front (4 members at 3 points)",
            ">\n0\n<",
            ">\n1–2\n<",
            ">\n3\n<",
        ];
        for text in labels.into_iter().chain(["population (4 scored)"]) {
            assert!(f.svg.contains(text), "{text}");
        }
        let none = FrontPlot {
            population: vec![[f64::NAN, 1.0]],
            front: vec![],
            ..plot
        };
        assert!(render(&none).is_err());
    }
}

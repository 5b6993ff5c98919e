//! The comparison figure: two panels, best fitness per generation and
//! best-so-far fitness against wall-clock seconds, a thin line per run and a
//! thick median line per group.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::runs::{Group, RunData};
use super::table::{median_per_generation, median_per_second, steps};
use crate::figures::{
    FAMILY, Figure, FigureError, axis_font, draw_err, draw_series_legend, label_font,
    register_font, svg_to_png,
};

/// Colour-blind safe group colours (Okabe & Ito), cycled.
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// Size and title of the comparison figure.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Figure title.
    pub title: String,
    /// Width in SVG units (the PNG is `PNG_SCALE` times larger).
    pub width: u32,
    /// Height in SVG units.
    pub height: u32,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            title: "Best fitness per generation and per wall-clock second".into(),
            width: 1300,
            height: 580,
        }
    }
}

/// Label of a seconds tick on the log axis.
fn seconds_label(t: &f64) -> String {
    if *t >= 1.0 {
        format!("{t:.0}")
    } else {
        let s = format!("{t:.3}");
        s.trim_end_matches('0').to_string()
    }
}

/// Renders the comparison figure (SVG and PNG).
pub fn render(groups: &[Group], opts: &CompareOptions) -> Result<Figure, FigureError> {
    let svg = draw(groups, opts)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

/// The left panel: fitness against generation.
type GenerationChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;
/// The right panel: fitness against seconds on a log scale.
type SecondsChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, RangedCoordf64>>;

/// The axes' ranges shared by the panels.
struct Ranges {
    /// Fitness, both panels.
    fitness: std::ops::Range<f64>,
    /// Generations, the left panel.
    generations: std::ops::Range<f64>,
    /// Seconds, the right panel.
    seconds: std::ops::Range<f64>,
}

impl Ranges {
    /// Ranges holding every run of `groups` (each with at least one generation).
    fn new(groups: &[Group]) -> Ranges {
        let runs = || groups.iter().flat_map(|g| &g.runs);
        let all_best = || runs().flat_map(|r| r.best[..r.generations()].iter().copied());
        let lo = all_best().fold(f64::INFINITY, f64::min);
        let hi = all_best().fold(f64::NEG_INFINITY, f64::max);
        let pad = ((hi - lo) * 0.06).max(1e-3);
        let max_gen = runs().map(RunData::generations).max().unwrap_or(1);
        let t_min = runs()
            .map(|r| r.cumulative_seconds()[0])
            .fold(f64::INFINITY, f64::min)
            .max(1e-3);
        let t_max = runs()
            .map(|r| r.cumulative_seconds()[r.generations() - 1])
            .fold(0.0, f64::max)
            .max(t_min * 10.0);
        Ranges {
            fitness: (lo - pad)..(hi + pad),
            generations: 0.5..(max_gen as f64 + 0.5),
            seconds: (t_min / 1.25)..(t_max * 1.25),
        }
    }
}

/// Checks that there is something to draw, every run has a generation, and the size is usable.
fn check(groups: &[Group], opts: &CompareOptions) -> Result<(), FigureError> {
    if groups.iter().all(|g| g.runs.is_empty()) {
        return Err(FigureError::NoData("no runs to compare"));
    }
    if let Some(r) = groups
        .iter()
        .flat_map(|g| &g.runs)
        .find(|r| r.generations() == 0)
    {
        return Err(FigureError::Invalid(format!(
            "{}: no generation recorded",
            r.dir.display()
        )));
    }
    if opts.width < 600 || opts.height < 300 {
        return Err(FigureError::Invalid(format!(
            "figure size {}x{} is too small (at least 600x300)",
            opts.width, opts.height
        )));
    }
    Ok(())
}

/// The font of the panels' captions.
fn caption_font() -> FontDesc<'static> {
    (FAMILY, 17).into_font()
}

/// A run's line.
fn thin(c: RGBColor) -> ShapeStyle {
    c.mix(0.3).stroke_width(1)
}

/// A group's median line.
fn thick(c: RGBColor) -> ShapeStyle {
    c.stroke_width(3)
}

/// The left panel with its axes: best fitness of each generation.
fn generation_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    ranges: &Ranges,
) -> Result<GenerationChart<'a, 'b>, FigureError> {
    let integers = |x: &f64| {
        if (x - x.round()).abs() < 1e-6 {
            format!("{x:.0}")
        } else {
            String::new()
        }
    };
    panel(
        area,
        "best of each generation",
        (ranges.generations.clone(), ranges.fitness.clone()),
        ("generation", "best fitness (px/step)"),
        &integers,
    )
}

/// The right panel with its axes: best-so-far fitness against wall-clock seconds.
fn seconds_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    ranges: &Ranges,
) -> Result<SecondsChart<'a, 'b>, FigureError> {
    panel(
        area,
        "best so far, against wall-clock time",
        (ranges.seconds.clone().log_scale(), ranges.fitness.clone()),
        (
            "cumulative wall-clock seconds (log scale)",
            "best-so-far fitness (px/step)",
        ),
        &seconds_label,
    )
}

/// A panel on `area` with its caption and axes over `(x, y)`, described by
/// `descs`, the x ticks labelled by `x_label`.
fn panel<'a, 'b, X>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
    (x, y): (X, std::ops::Range<f64>),
    (x_desc, y_desc): (&str, &str),
    x_label: &dyn Fn(&f64) -> String,
) -> Result<
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<X::CoordDescType, RangedCoordf64>>,
    FigureError,
>
where
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(area)
        .caption(caption, caption_font())
        .margin(10)
        .margin_right(20)
        .x_label_area_size(46)
        .y_label_area_size(64)
        .build_cartesian_2d(x, y)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(x_label)
        .draw()
        .map_err(draw_err)?;
    Ok(chart)
}

/// Every run's thin line, then every group's thick median line (labelled for
/// the legend), in both panels: the runs first, so that no median line is
/// hidden under one.
fn draw_lines(
    groups: &[Group],
    per_gen: &mut GenerationChart<'_, '_>,
    per_second: &mut SecondsChart<'_, '_>,
) -> Result<(), FigureError> {
    let coloured = || groups.iter().zip(COLOURS.iter().copied().cycle());
    for (g, colour) in coloured() {
        for r in &g.runs {
            let best = r.best[..r.generations()].iter().copied();
            per_gen
                .draw_series(LineSeries::new(by_generation(best), thin(colour)))
                .map_err(draw_err)?;
            per_second
                .draw_series(LineSeries::new(steps(r), thin(colour)))
                .map_err(draw_err)?;
        }
    }
    for (g, colour) in coloured() {
        let n = g.runs.len();
        let label = if n == 1 {
            format!("{} (1 run)", g.name)
        } else {
            format!("{} ({n} runs, median)", g.name)
        };
        let median = by_generation(median_per_generation(g));
        per_gen
            .draw_series(LineSeries::new(median, thick(colour)))
            .map_err(draw_err)?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], thick(colour)));
        per_second
            .draw_series(LineSeries::new(median_per_second(g), thick(colour)))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Values of generations 1, 2, … as (generation, value) points.
fn by_generation(values: impl IntoIterator<Item = f64>) -> impl Iterator<Item = (f64, f64)> {
    values
        .into_iter()
        .enumerate()
        .map(|(i, v)| (i as f64 + 1.0, v))
}

/// Draws the figure into an SVG string.
pub(super) fn draw(groups: &[Group], opts: &CompareOptions) -> Result<String, FigureError> {
    register_font()?;
    check(groups, opts)?;
    let ranges = Ranges::new(groups);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (opts.width, opts.height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let root = root
            .titled(&opts.title, (FAMILY, 22).into_font().style(FontStyle::Bold))
            .map_err(draw_err)?;
        let (left, right) = root.split_horizontally(opts.width / 2);
        let mut per_gen = generation_chart(&left, &ranges)?;
        let mut per_second = seconds_chart(&right, &ranges)?;
        draw_lines(groups, &mut per_gen, &mut per_second)?;
        draw_series_legend(&mut per_gen)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

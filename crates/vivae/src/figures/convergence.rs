//! The convergence figure (the paper's Fig. 8): every generation's fitnesses
//! sorted, generation on x, rank on y (1 = best, at the top), fitness as
//! colour; below it the best and mean fitness per generation.

use plotters::prelude::*;
use vivae_neat::stats;

use super::{
    FAMILY, Figure, FigureError, axis_font, draw_err, draw_series_legend, label_font,
    register_font, svg_to_png, viridis,
};

/// Number of colour levels of the heat map (cells of equal level are merged).
const LEVELS: usize = 256;

/// What the convergence figure shows and how large it is.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceOptions {
    /// Figure title.
    pub title: String,
    /// Number of the first generation in the data (x-axis labels).
    pub first_generation: u32,
    /// Width in SVG units (the PNG is `PNG_SCALE` times larger).
    pub width: u32,
    /// Height in SVG units.
    pub height: u32,
}

impl Default for ConvergenceOptions {
    fn default() -> Self {
        ConvergenceOptions {
            title: "Fitness of every individual, sorted, per generation".to_string(),
            first_generation: 1,
            width: 900,
            height: 760,
        }
    }
}

/// Axis label of a generation tick: only whole generations are labelled
/// (short runs would otherwise repeat rounded labels at fractional ticks).
fn generation_label(x: &f64) -> String {
    if (x - x.round()).abs() < 1e-6 {
        format!("{x:.0}")
    } else {
        String::new()
    }
}

/// Per-generation summary used by the curves.
struct GenStats {
    best: f64,
    mean: f64,
}

/// How the heat map cells go into the SVG.
#[derive(Clone, Copy, PartialEq)]
enum Cells {
    /// One `<rect>` per run of equal colour in a column (what the PNG is rendered from).
    Rects,
    /// One embedded PNG image with a pixel per cell (keeps the SVG file small:
    /// 400 generations × 100 individuals would otherwise be ~40 000 elements).
    Image,
}

/// Renders the figure from each generation's fitnesses (any order; non-finite values are skipped).
pub fn render(generations: &[Vec<f64>], opts: &ConvergenceOptions) -> Result<Figure, FigureError> {
    let svg = render_svg(generations, opts)?;
    let png = svg_to_png(&draw(generations, opts, Cells::Rects)?)?;
    Ok(Figure { svg, png })
}

/// Renders the figure as an SVG document (the heat map as an embedded image).
pub fn render_svg(
    generations: &[Vec<f64>],
    opts: &ConvergenceOptions,
) -> Result<String, FigureError> {
    draw(generations, opts, Cells::Image)
}

/// Every generation's fitnesses sorted best-first, and the scales drawn from them.
struct Sorted {
    /// Per generation, its finite fitnesses best-first.
    columns: Vec<Vec<f64>>,
    /// The most individuals in a generation.
    ranks: usize,
    /// The colour scale's ends (never equal).
    lo: f64,
    hi: f64,
    /// Per generation, best and mean (`None` for a generation without finite fitness).
    stats: Vec<Option<GenStats>>,
    /// Number of the first generation.
    g0: f64,
}

impl Sorted {
    /// Sorts `generations` best-first (non-finite fitnesses dropped: they have
    /// no colour) and checks that there is something to draw at `opts`' size.
    fn new(generations: &[Vec<f64>], opts: &ConvergenceOptions) -> Result<Sorted, FigureError> {
        let columns: Vec<Vec<f64>> = generations
            .iter()
            .map(|g| {
                let finite: Vec<f64> = g.iter().copied().filter(|f| f.is_finite()).collect();
                stats::sorted_descending(&finite)
            })
            .collect();
        let ranks = columns.iter().map(Vec::len).max().unwrap_or(0);
        if columns.is_empty() || ranks == 0 {
            return Err(FigureError::NoData("no finite fitness in any generation"));
        }
        if opts.width < 300 || opts.height < 300 {
            return Err(FigureError::Invalid(format!(
                "figure size {}x{} is too small (at least 300x300)",
                opts.width, opts.height
            )));
        }
        let lo = columns
            .iter()
            .flatten()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let hi = columns
            .iter()
            .flatten()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        // A flat population still needs a non-empty colour range.
        let (lo, hi) = if hi - lo > 1e-12 {
            (lo, hi)
        } else {
            (lo - 0.5, hi + 0.5)
        };
        let stats = columns
            .iter()
            .map(|g| stats::mean(g).map(|mean| GenStats { best: g[0], mean }))
            .collect();
        Ok(Sorted {
            columns,
            ranks,
            lo,
            hi,
            stats,
            g0: f64::from(opts.first_generation),
        })
    }

    /// The colour level of fitness `f`.
    fn level(&self, f: f64) -> usize {
        (((f - self.lo) / (self.hi - self.lo)) * (LEVELS - 1) as f64).round() as usize
    }

    /// The x range of the generation axes.
    fn x_range(&self) -> std::ops::Range<f64> {
        (self.g0 - 0.5)..(self.g0 + self.columns.len() as f64 - 0.5)
    }
}

/// The colour of level `l`.
fn colour_of_level(l: usize) -> RGBColor {
    viridis(l as f64 / (LEVELS - 1) as f64)
}

/// A drawing area of the figure.
type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A pixel range `(x, y)` of a drawing area.
type PixelRange = (std::ops::Range<i32>, std::ops::Range<i32>);

/// Draws the figure into an SVG string.
fn draw(
    generations: &[Vec<f64>],
    opts: &ConvergenceOptions,
    cells: Cells,
) -> Result<String, FigureError> {
    register_font()?;
    let data = Sorted::new(generations, opts)?;
    let mut svg = String::new();
    let heat_px;
    {
        let root = SVGBackend::with_string(&mut svg, (opts.width, opts.height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let root = root
            .titled(&opts.title, (FAMILY, 22).into_font().style(FontStyle::Bold))
            .map_err(draw_err)?;
        let top_height = root.dim_in_pixel().1 * 60 / 100;
        let (top, bottom) = root.split_vertically(top_height);
        let (heat_area, bar_area) = top.split_horizontally(opts.width - 110);
        heat_px = draw_heat_map(&heat_area, &data, cells)?;
        draw_colour_bar(&bar_area, &data)?;
        draw_curves(&bottom, &data)?;
        root.present().map_err(draw_err)?;
    }
    if cells == Cells::Image {
        embed_heat_image(&mut svg, &data, heat_px)?;
    }
    Ok(svg)
}

/// The heat map: one column per generation, ranks top (best) to bottom; its
/// cells drawn as rectangles with [`Cells::Rects`], else left to
/// [`embed_heat_image`]. Returns the plotting area's pixel range.
fn draw_heat_map(area: &Area<'_>, data: &Sorted, cells: Cells) -> Result<PixelRange, FigureError> {
    let mut heat = ChartBuilder::on(area)
        .margin_left(10)
        .margin_right(10)
        .margin_top(6)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(data.x_range(), (data.ranks as f64 + 0.5)..0.5)
        .map_err(draw_err)?;
    heat.configure_mesh()
        .disable_mesh()
        .x_desc("generation")
        .y_desc("rank (1 = best)")
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(&generation_label)
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()
        .map_err(draw_err)?;
    // Runs of equal colour within a column become one rectangle: the
    // sorted column is smooth, so this keeps the SVG small.
    let heat_px = heat.plotting_area().get_pixel_range();
    let mut rects = Vec::new();
    for (gi, column) in data
        .columns
        .iter()
        .enumerate()
        .filter(|_| cells == Cells::Rects)
    {
        let x = data.g0 + gi as f64;
        let mut start = 0;
        while start < column.len() {
            let l = data.level(column[start]);
            let mut end = start + 1;
            while end < column.len() && data.level(column[end]) == l {
                end += 1;
            }
            rects.push(Rectangle::new(
                [(x - 0.5, start as f64 + 0.5), (x + 0.5, end as f64 + 0.5)],
                colour_of_level(l).filled(),
            ));
            start = end;
        }
    }
    heat.draw_series(rects).map_err(draw_err)?;
    Ok(heat_px)
}

/// The colour bar with the fitness scale.
fn draw_colour_bar(area: &Area<'_>, data: &Sorted) -> Result<(), FigureError> {
    let (lo, hi) = (data.lo, data.hi);
    let mut bar = ChartBuilder::on(area)
        .margin_top(6)
        .margin_right(8)
        .x_label_area_size(44)
        .y_label_area_size(0)
        .right_y_label_area_size(58)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(draw_err)?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("fitness (px/step)")
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .draw()
        .map_err(draw_err)?;
    let step = (hi - lo) / LEVELS as f64;
    bar.draw_series((0..LEVELS).map(|l| {
        let y = lo + l as f64 * step;
        Rectangle::new(
            [(0.0, y), (1.0, y + step * 1.02)],
            colour_of_level(l).filled(),
        )
    }))
    .map_err(draw_err)?;
    Ok(())
}

/// The colour of the best-fitness curve (report.html's plot uses it too).
pub(crate) fn best_colour() -> RGBColor {
    viridis(0.15)
}

/// The colour of the mean-fitness curve (report.html's plot uses it too).
pub(crate) const MEAN_COLOUR: RGBColor = RGBColor(230, 97, 1);

/// `#rrggbb` of `c`, for web pages.
pub(crate) fn hex(c: RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// The best and mean curves, on the same generation axis as the heat map.
fn draw_curves(area: &Area<'_>, data: &Sorted) -> Result<(), FigureError> {
    let best_hi = data
        .stats
        .iter()
        .flatten()
        .map(|s| s.best)
        .fold(f64::NEG_INFINITY, f64::max);
    let mean_lo = data
        .stats
        .iter()
        .flatten()
        .map(|s| s.mean)
        .fold(f64::INFINITY, f64::min);
    let pad = ((best_hi - mean_lo) * 0.08).max(1e-3);
    let mut curves = ChartBuilder::on(area)
        .margin_left(10)
        .margin_right(120)
        .margin_top(14)
        .margin_bottom(6)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(data.x_range(), (mean_lo - pad)..(best_hi + pad))
        .map_err(draw_err)?;
    curves
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc("generation")
        .y_desc("fitness (px/step)")
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(&generation_label)
        .draw()
        .map_err(draw_err)?;
    let points = |f: fn(&GenStats) -> f64| {
        data.stats
            .iter()
            .enumerate()
            .filter_map(|(gi, s)| s.as_ref().map(|s| (data.g0 + gi as f64, f(s))))
            .collect::<Vec<_>>()
    };
    for (label, colour, values) in [
        ("best", best_colour(), points(|s| s.best)),
        ("mean", MEAN_COLOUR, points(|s| s.mean)),
    ] {
        curves
            .draw_series(LineSeries::new(values, colour.stroke_width(2)))
            .map_err(draw_err)?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 22, y)], colour.stroke_width(2))
            });
    }
    draw_series_legend(&mut curves)
}

/// Puts the heat map into `svg` as one embedded PNG image over the pixel
/// range `heat_px`, with a pixel per (generation, rank) cell, rank 1 in the top row.
fn embed_heat_image(
    svg: &mut String,
    data: &Sorted,
    heat_px: PixelRange,
) -> Result<(), FigureError> {
    let mut image = tiny_skia::Pixmap::new(data.columns.len() as u32, data.ranks as u32)
        .ok_or_else(|| FigureError::Invalid("heat map too large".to_string()))?;
    let width = data.columns.len();
    let pixels = image.pixels_mut();
    for (gi, column) in data.columns.iter().enumerate() {
        for (r, &f) in column.iter().enumerate() {
            let c = colour_of_level(data.level(f));
            pixels[r * width + gi] =
                tiny_skia::ColorU8::from_rgba(c.0, c.1, c.2, 255).premultiply();
        }
    }
    let png = super::encode_png_fast(&image)?;
    let (xs, ys) = heat_px;
    let element = format!(
        "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" \
         image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\" \
         href=\"data:image/png;base64,{}\"/>\n",
        xs.start,
        ys.start,
        xs.end - xs.start,
        ys.end - ys.start,
        base64(&png)
    );
    // After the white background (the first element), before the axes.
    let at = svg
        .find("/>\n")
        .map(|i| i + 3)
        .ok_or_else(|| FigureError::Draw("unexpected SVG from plotters".to_string()))?;
    svg.insert_str(at, &element);
    Ok(())
}

/// Standard base64 with padding (for the embedded heat-map image).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};

    /// A synthetic run: fitness rising over generations with spread in the population.
    fn synthetic(gens: usize, pop: usize) -> Vec<Vec<f64>> {
        (0..gens)
            .map(|g| {
                let progress = 1.0 - (-(g as f64) / 40.0).exp();
                (0..pop)
                    .map(|i| {
                        // Deterministic pseudo-random spread per individual.
                        let h = ((g * 7919 + i * 104_729) % 1000) as f64 / 1000.0;
                        0.3 + 3.9 * progress * h.powf(0.6)
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn renders_png_and_svg_with_labels() {
        let data = synthetic(60, 40);
        let fig = render(&data, &ConvergenceOptions::default()).unwrap();
        assert_eq!(png_size(&fig.png), (1800, 1520));
        assert!(distinct_colours(&fig.png) > 100);
        for label in [
            "generation",
            "rank (1 = best)",
            "fitness (px/step)",
            "best",
            "mean",
            "sorted",
        ] {
            assert!(fig.svg.contains(label), "missing {label:?}");
        }
    }

    #[test]
    fn equal_colour_runs_are_merged() {
        // Generations of identical fitness: one rectangle per column.
        let opts = ConvergenceOptions::default();
        let flat = draw(&[vec![2.0; 50], vec![1.0; 50]], &opts, Cells::Rects).unwrap();
        let many = draw(&synthetic(2, 50), &opts, Cells::Rects).unwrap();
        assert!(flat.matches("<rect").count() + 40 < many.matches("<rect").count());
    }

    #[test]
    fn svg_embeds_one_pixel_per_cell() {
        let svg = render_svg(&synthetic(400, 100), &ConvergenceOptions::default()).unwrap();
        assert_eq!(svg.matches("<image").count(), 1);
        assert!(svg.len() < 400_000, "SVG is {} bytes", svg.len());
        let start = svg.find("base64,").unwrap() + 7;
        let end = start + svg[start..].find('"').unwrap();
        let png = unbase64(&svg[start..end]);
        assert_eq!(png_size(&png), (400, 100));
    }

    /// Inverse of `base64`, for the test.
    fn unbase64(s: &str) -> Vec<u8> {
        let value = |c: u8| match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            _ => 63,
        };
        let mut out = Vec::new();
        for chunk in s.as_bytes().chunks(4) {
            let pad = chunk.iter().filter(|&&c| c == b'=').count();
            let n = chunk.iter().fold(0u32, |n, &c| {
                (n << 6) | u32::from(if c == b'=' { 0 } else { value(c) })
            });
            out.extend_from_slice(&n.to_be_bytes()[1..4 - pad]);
        }
        out
    }

    #[test]
    fn base64_matches_the_standard() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(unbase64("Zm9vYmE="), b"fooba");
    }

    #[test]
    fn bad_input_is_an_error() {
        let opts = ConvergenceOptions::default();
        assert!(matches!(
            render_svg(&[], &opts),
            Err(FigureError::NoData(_))
        ));
        assert!(matches!(
            render_svg(&[vec![f64::NAN]], &opts),
            Err(FigureError::NoData(_))
        ));
        let tiny = ConvergenceOptions {
            width: 10,
            ..ConvergenceOptions::default()
        };
        assert!(matches!(
            render_svg(&[vec![1.0]], &tiny),
            Err(FigureError::Invalid(_))
        ));
        // A single individual in a single generation is still a figure.
        assert!(render_svg(&[vec![1.0]], &opts).is_ok());
    }

    /// Writes the figure for eyeballing: `VIVAE_FIGURE_DIR=/tmp cargo test ... -- --ignored`.
    #[test]
    #[ignore]
    fn write_sample() {
        let dir = std::env::var("VIVAE_FIGURE_DIR").unwrap_or_else(|_| "/tmp".into());
        let fig = render(&synthetic(400, 100), &ConvergenceOptions::default()).unwrap();
        std::fs::write(format!("{dir}/convergence.png"), fig.png).unwrap();
        std::fs::write(format!("{dir}/convergence.svg"), fig.svg).unwrap();
    }
}

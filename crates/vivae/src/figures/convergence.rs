//! The convergence figure (the paper's Fig. 8): every generation's fitnesses
//! sorted, generation on x, rank on y (1 = best, at the top), fitness as
//! colour; below it the best and mean fitness per generation.

use plotters::prelude::*;
use vivae_neat::stats;
use vivae_sim::draw::MAX_PIXELS;

use super::{
    FAMILY, Figure, FigureError, PNG_SCALE, axis_font, base64, draw_err, draw_series_legend,
    draw_svg_over, encode_png_fast, label_font, register_font, viridis, white_canvas,
};

/// Number of colour levels of the heat map.
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

/// Renders the figure from each generation's fitnesses (any order; non-finite values are skipped).
pub fn render(generations: &[Vec<f64>], opts: &ConvergenceOptions) -> Result<Figure, FigureError> {
    let data = Sorted::new(generations, opts)?;
    let (mut svg, heat_px) = draw(&data, opts)?;
    let heat = heat_pixmap(&data)?;
    let png = render_png(&svg, &heat, heat_px.clone(), opts)?;
    embed_heat_image(&mut svg, &heat, heat_px)?;
    Ok(Figure { svg, png })
}

/// Renders the figure as an SVG document (the heat map as an embedded image).
pub fn render_svg(
    generations: &[Vec<f64>],
    opts: &ConvergenceOptions,
) -> Result<String, FigureError> {
    let data = Sorted::new(generations, opts)?;
    let (mut svg, heat_px) = draw(&data, opts)?;
    embed_heat_image(&mut svg, &heat_pixmap(&data)?, heat_px)?;
    Ok(svg)
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

/// Draws the figure into an SVG string, all but the heat map's cells;
/// returns it and the pixel range the cells fill.
fn draw(data: &Sorted, opts: &ConvergenceOptions) -> Result<(String, PixelRange), FigureError> {
    register_font()?;
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
        heat_px = draw_heat_map(&heat_area, data)?;
        draw_colour_bar(&bar_area, data)?;
        draw_curves(&bottom, data)?;
        root.present().map_err(draw_err)?;
    }
    Ok((svg, heat_px))
}

/// The heat map's axes: one column per generation, ranks top (best) to
/// bottom. Returns the plotting area's pixel range, which the cells fill
/// ([`embed_heat_image`] in the SVG, [`render_png`] in the PNG).
fn draw_heat_map(area: &Area<'_>, data: &Sorted) -> Result<PixelRange, FigureError> {
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
    Ok(heat.plotting_area().get_pixel_range())
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

/// The heat map as an image with a pixel per (generation, rank) cell, rank 1
/// in the top row (a generation with fewer finite fitnesses leaves its
/// lowest cells transparent).
fn heat_pixmap(data: &Sorted) -> Result<tiny_skia::Pixmap, FigureError> {
    let too_large = || FigureError::Invalid("heat map too large".to_string());
    if (data.columns.len() * data.ranks) as f64 > MAX_PIXELS {
        return Err(too_large());
    }
    let mut image = tiny_skia::Pixmap::new(data.columns.len() as u32, data.ranks as u32)
        .ok_or_else(too_large)?;
    let width = data.columns.len();
    let pixels = image.pixels_mut();
    for (gi, column) in data.columns.iter().enumerate() {
        for (r, &f) in column.iter().enumerate() {
            let c = colour_of_level(data.level(f));
            pixels[r * width + gi] =
                tiny_skia::ColorU8::from_rgba(c.0, c.1, c.2, 255).premultiply();
        }
    }
    Ok(image)
}

/// The PNG of the figure, as the SVG shows it: the `heat` image scaled over
/// the pixel range `heat_px` (each pixel taking the cell under its centre,
/// as a pixelated image is shown), then `svg` (the rest of the figure)
/// drawn over it at [`PNG_SCALE`], its axes over the cells' edges.
///
/// Painting the cells directly rather than as thousands of SVG rectangles for
/// resvg to parse and fill takes the default run's figure from 110 to 23 ms.
fn render_png(
    svg: &str,
    heat: &tiny_skia::Pixmap,
    heat_px: PixelRange,
    opts: &ConvergenceOptions,
) -> Result<Vec<u8>, FigureError> {
    let scale = PNG_SCALE;
    let mut base = white_canvas(f64::from(opts.width), f64::from(opts.height))?;
    let (xs, ys) = heat_px;
    let to_cells = tiny_skia::Transform::from_row(
        (xs.end - xs.start) as f32 * scale / heat.width() as f32,
        0.0,
        0.0,
        (ys.end - ys.start) as f32 * scale / heat.height() as f32,
        xs.start as f32 * scale,
        ys.start as f32 * scale,
    );
    let nearest = tiny_skia::PixmapPaint {
        quality: tiny_skia::FilterQuality::Nearest,
        ..tiny_skia::PixmapPaint::default()
    };
    base.draw_pixmap(0, 0, heat.as_ref(), &nearest, to_cells, None);
    let background = background_element(svg)?;
    draw_svg_over(
        &[&svg[..background.start], &svg[background.end..]].concat(),
        &mut base,
        scale,
    )?;
    encode_png_fast(&base)
}

/// The byte range of the element after `svg`'s opening tag: plotters'
/// white background (the heat map goes right after it, under the axes).
fn background_element(svg: &str) -> Result<std::ops::Range<usize>, FigureError> {
    let open_end = svg.find(">\n").map(|i| i + 2);
    let background =
        open_end.and_then(|start| svg[start..].find("/>\n").map(|i| start..start + i + 3));
    match background {
        Some(background) if svg[background.clone()].starts_with("<rect") => Ok(background),
        _ => Err(FigureError::Draw(
            "unexpected SVG from plotters".to_string(),
        )),
    }
}

/// Puts the `heat` image into `svg` over the pixel range `heat_px`.
fn embed_heat_image(
    svg: &mut String,
    heat: &tiny_skia::Pixmap,
    heat_px: PixelRange,
) -> Result<(), FigureError> {
    let png = encode_png_fast(heat)?;
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
    let background = background_element(svg)?;
    svg.insert_str(background.end, &element);
    Ok(())
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
    fn png_cells_fill_the_heat_map_as_the_svg_image_does() {
        // One generation flat, one sorted from 4 down to 1, and one with a
        // single finite fitness, whose three lower cells stay blank.
        let gens = vec![
            vec![1.0; 4],
            vec![2.0, 4.0, 1.0, 3.0],
            vec![f64::NAN, 4.0, f64::NAN, f64::NAN],
        ];
        let opts = ConvergenceOptions::default();
        let png = tiny_skia::Pixmap::decode_png(&render(&gens, &opts).unwrap().png).unwrap();
        let data = Sorted::new(&gens, &opts).unwrap();
        let (_, (xs, ys)) = draw(&data, &opts).unwrap();
        // The PNG pixel at the centre of cell (generation g, rank r), and
        // one at a fraction of a cell from its corner.
        let at = |g: f32, r: f32| {
            let x = (xs.start as f32 + g * (xs.end - xs.start) as f32 / 3.0) * PNG_SCALE;
            let y = (ys.start as f32 + r * (ys.end - ys.start) as f32 / 4.0) * PNG_SCALE;
            let p = png.pixel(x as u32, y as u32).unwrap();
            (p.red(), p.green(), p.blue(), p.alpha())
        };
        let colour = |f: f64| {
            let c = colour_of_level(data.level(f));
            (c.0, c.1, c.2, 255)
        };
        for r in 0..4 {
            assert_eq!(at(0.5, r as f32 + 0.5), colour(1.0), "rank {}", r + 1);
            assert_eq!(at(0.02, r as f32 + 0.02), colour(1.0), "rank {}", r + 1);
        }
        for (r, f) in [4.0, 3.0, 2.0, 1.0].into_iter().enumerate() {
            assert_eq!(at(1.5, r as f32 + 0.5), colour(f), "rank {}", r + 1);
            assert_eq!(at(1.98, r as f32 + 0.98), colour(f), "rank {}", r + 1);
        }
        assert_eq!(at(2.5, 0.5), colour(4.0));
        for r in 1..4 {
            assert_eq!(
                at(2.5, r as f32 + 0.5),
                (255, 255, 255, 255),
                "blank rank {}",
                r + 1
            );
        }
        assert_ne!(colour(1.0), colour(4.0));
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
        // A PNG past the pixel cap is refused, not allocated.
        let huge = ConvergenceOptions {
            width: 20_000,
            height: 20_000,
            ..ConvergenceOptions::default()
        };
        assert!(matches!(
            render(&[vec![1.0]], &huge),
            Err(FigureError::Invalid(_))
        ));
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

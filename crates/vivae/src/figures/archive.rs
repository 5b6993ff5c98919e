//! The MAP-Elites archive as a heat map: one square per cell of a 2-D grid,
//! coloured by its elite's fitness (viridis), empty cells light grey.

use plotters::prelude::*;

use super::{FAMILY, Figure, FigureError, draw_err, register_font, svg_to_png, viridis};

/// A 2-D grid archive to draw: what MAP-Elites' file in the library makes.
pub use vivae_lab::search::GridFigure as ArchiveGrid;

/// Colour of empty cells.
const EMPTY: RGBColor = RGBColor(235, 235, 235);

/// Renders the archive (SVG and PNG).
pub fn render(grid: &ArchiveGrid) -> Result<Figure, FigureError> {
    let svg = draw(grid)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

fn draw(g: &ArchiveGrid) -> Result<String, FigureError> {
    register_font()?;
    let cells = g.bins[0] * g.bins[1];
    if cells == 0 || g.elites.iter().any(|&(c, _)| c >= cells) {
        return Err(FigureError::Invalid(format!(
            "{} elites on a {}x{} grid",
            g.elites.len(),
            g.bins[0],
            g.bins[1]
        )));
    }
    let finite = g.elites.iter().map(|e| e.1).filter(|f| f.is_finite());
    let lo = finite.clone().fold(f64::INFINITY, f64::min);
    let hi = finite.fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if hi - lo > 1e-12 {
        (lo, hi)
    } else {
        (lo - 0.5, hi + 0.5)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (760, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let root = (root.titled(&g.title, (FAMILY, 20).into_font().style(FontStyle::Bold)))
            .map_err(draw_err)?;
        let (map, bar) = root.split_horizontally(640);
        let mut chart = ChartBuilder::on(&map)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(g.lower[0]..g.upper[0], g.lower[1]..g.upper[1])
            .map_err(draw_err)?;
        (chart.configure_mesh().disable_mesh())
            .x_desc(g.axes[0].as_str())
            .y_desc(g.axes[1].as_str())
            .axis_desc_style((FAMILY, 18).into_font())
            .label_style((FAMILY, 15).into_font())
            .draw()
            .map_err(draw_err)?;
        let mut colour = vec![None; cells];
        for &(c, f) in &g.elites {
            colour[c] = Some(viridis(((f - lo) / (hi - lo)).clamp(0.0, 1.0)));
        }
        let w = [0, 1].map(|d| (g.upper[d] - g.lower[d]) / g.bins[d] as f64);
        let squares = colour.iter().enumerate().map(|(c, col)| {
            let (i, j) = ((c / g.bins[1]) as f64, (c % g.bins[1]) as f64);
            let (x, y) = (g.lower[0] + i * w[0], g.lower[1] + j * w[1]);
            Rectangle::new(
                [(x, y), (x + w[0], y + w[1])],
                col.unwrap_or(EMPTY).filled(),
            )
        });
        chart.draw_series(squares).map_err(draw_err)?;
        draw_bar(&bar, lo, hi)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// The colour bar of the fitness scale.
fn draw_bar(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    lo: f64,
    hi: f64,
) -> Result<(), FigureError> {
    let mut bar = ChartBuilder::on(area)
        .margin_top(12)
        .margin_bottom(60)
        .margin_right(8)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(draw_err)?;
    (bar.configure_mesh().disable_mesh().disable_x_axis())
        .y_desc("fitness")
        .axis_desc_style((FAMILY, 16).into_font())
        .label_style((FAMILY, 14).into_font())
        .draw()
        .map_err(draw_err)?;
    let steps = 64;
    let strips = (0..steps).map(|k| {
        let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        let y = |t: f64| lo + t * (hi - lo);
        Rectangle::new([(0.0, y(a)), (1.0, y(b))], viridis(a).filled())
    });
    bar.draw_series(strips).map_err(draw_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};

    #[test]
    fn archive_heat_map_draws_filled_and_empty_cells() {
        let grid = ArchiveGrid {
            title: "archive".into(),
            axes: ["side".into(), "speed".into()],
            lower: [-1.0, 0.0],
            upper: [1.0, 1.0],
            bins: [4, 3],
            elites: vec![(0, 0.5), (5, 2.0), (11, 1.0)],
        };
        let f = render(&grid).unwrap();
        assert!(png_size(&f.png).0 > 700);
        assert!(distinct_colours(&f.png) > 10);
        let bad = ArchiveGrid {
            elites: vec![(12, 1.0)],
            ..grid
        };
        assert!(render(&bad).is_err(), "a cell outside the grid is refused");
    }
}

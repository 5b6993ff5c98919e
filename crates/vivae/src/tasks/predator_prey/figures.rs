//! Figures of a predator–prey run (two co-evolved populations): the CIAO
//! matrix as a heat map (Cliff & Miller 1995: each generation's best hunter
//! against each generation's best prey) and both sides' curves over the
//! generations (best and mean fitness, catch rate, master tournament).

use plotters::prelude::*;
use vivae_lab::tasks::predator_prey::coevo::CiaoCell;

use crate::figures::{
    FAMILY, Figure, FigureError, axis_font, draw_err, label_font, register_font, svg_to_png,
    viridis,
};

/// Colour of the hunters' curves and robot (red, as the viewer draws them).
pub const HUNTER_COLOUR: RGBColor = RGBColor(214, 39, 40);
/// Colour of the prey's curves and robot (blue).
pub const PREY_COLOUR: RGBColor = RGBColor(31, 119, 180);
/// Colour of a CIAO cell not played (a partial matrix).
const EMPTY: RGBColor = RGBColor(235, 235, 235);

/// One generation of one side (a row of `hunters.csv` or `prey.csv`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideRow {
    /// The generation (0-based).
    pub generation: u32,
    /// The best genome's fitness.
    pub best: f64,
    /// The population's mean fitness.
    pub mean: f64,
    /// Share of the side's games that ended in a catch.
    pub catch_rate: f64,
}

/// Renders the CIAO heat map of `generations` generations: hunter generation
/// on x, prey generation on y, the hunter's fitness as colour on the fixed
/// scale [0, 2] (1 and above: a catch; a dot marks each catch, up to 140 generations).
pub fn ciao(cells: &[CiaoCell], generations: u32) -> Result<Figure, FigureError> {
    let svg = draw_ciao(cells, generations)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

fn draw_ciao(cells: &[CiaoCell], n: u32) -> Result<String, FigureError> {
    register_font()?;
    if n == 0 {
        return Err(FigureError::NoData("a CIAO matrix of no generations"));
    }
    if let Some(c) = cells.iter().find(|c| c.hunter >= n || c.prey >= n) {
        return Err(FigureError::Invalid(format!(
            "CIAO cell ({}, {}) outside {n} generations",
            c.hunter, c.prey
        )));
    }
    let mut grid = vec![None; (n * n) as usize];
    for c in cells {
        grid[(c.hunter * n + c.prey) as usize] = Some((c.hunter_fitness, c.caught));
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (820, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let title = "CIAO: each generation's best hunter against each generation's best prey";
        let root = (root.titled(title, (FAMILY, 19).into_font().style(FontStyle::Bold)))
            .map_err(draw_err)?;
        let (map, bar) = root.split_horizontally(700);
        let top = f64::from(n) - 0.5;
        let mut chart = ChartBuilder::on(&map)
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(64)
            .build_cartesian_2d(-0.5..top, -0.5..top)
            .map_err(draw_err)?;
        (chart.configure_mesh().disable_mesh())
            .x_desc("hunter generation")
            .y_desc("prey generation")
            .axis_desc_style(label_font())
            .label_style(axis_font())
            .x_label_formatter(&whole)
            .y_label_formatter(&whole)
            .draw()
            .map_err(draw_err)?;
        let squares = grid.iter().enumerate().map(|(k, cell)| {
            let (h, p) = ((k as u32 / n) as f64, (k as u32 % n) as f64);
            let colour = cell.map_or(EMPTY, |(f, _)| viridis(f / 2.0));
            Rectangle::new([(h - 0.5, p - 0.5), (h + 0.5, p + 0.5)], colour.filled())
        });
        chart.draw_series(squares).map_err(draw_err)?;
        // Small dots: a fifth of a cell, none where cells are too small to hold one.
        let size = (140 / n).min(4) as i32;
        let dots = grid
            .iter()
            .enumerate()
            .filter(|_| size > 0)
            .filter_map(|(k, cell)| {
                let (h, p) = ((k as u32 / n) as f64, (k as u32 % n) as f64);
                matches!(cell, Some((_, true))).then(|| Circle::new((h, p), size, WHITE.filled()))
            });
        chart.draw_series(dots).map_err(draw_err)?;
        draw_ciao_bar(&bar)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// A tick label of a whole generation (none between them).
fn whole(x: &f64) -> String {
    if (x - x.round()).abs() < 1e-6 && *x >= 0.0 {
        format!("{x:.0}")
    } else {
        String::new()
    }
}

/// The colour bar of the hunter-fitness scale [0, 2].
fn draw_ciao_bar(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
) -> Result<(), FigureError> {
    let mut bar = ChartBuilder::on(area)
        .margin_top(12)
        .margin_bottom(62)
        .margin_right(8)
        .y_label_area_size(66)
        .build_cartesian_2d(0.0..1.0, 0.0..2.0)
        .map_err(draw_err)?;
    (bar.configure_mesh().disable_mesh().disable_x_axis())
        .y_desc("hunter fitness (≥ 1: caught, dot)")
        .axis_desc_style((FAMILY, 15).into_font())
        .label_style(axis_font())
        .draw()
        .map_err(draw_err)?;
    let steps = 64;
    let strips = (0..steps).map(|k| {
        let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        Rectangle::new([(0.0, 2.0 * a), (1.0, 2.0 * b)], viridis(a).filled())
    });
    bar.draw_series(strips).map_err(draw_err)?;
    bar.draw_series([PathElement::new(
        vec![(0.0, 1.0), (1.0, 1.0)],
        WHITE.stroke_width(2),
    )])
    .map_err(draw_err)?;
    Ok(())
}

/// Renders both sides' curves over the generations: best and mean fitness,
/// catch rate, and each generation's champion's master tournament fitness
/// (`master[0]` hunters, `master[1]` prey; Floreano & Nolfi 1997).
pub fn curves(
    hunters: &[SideRow],
    prey: &[SideRow],
    master: [&[f64]; 2],
) -> Result<Figure, FigureError> {
    let svg = draw_curves(hunters, prey, master)?;
    let png = svg_to_png(&svg)?;
    Ok(Figure { svg, png })
}

/// One line of a panel: label, colour, dashed or not, points.
type Line = (String, RGBColor, bool, Vec<(f64, f64)>);

fn draw_curves(
    hunters: &[SideRow],
    prey: &[SideRow],
    master: [&[f64]; 2],
) -> Result<String, FigureError> {
    register_font()?;
    if hunters.is_empty() || prey.is_empty() {
        return Err(FigureError::NoData("no generations of hunters and prey"));
    }
    let n = hunters.len().max(prey.len()) as f64;
    let pts = |rows: &[SideRow], f: fn(&SideRow) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .map(|r| (f64::from(r.generation), f(r)))
            .collect()
    };
    let series = |v: &[f64]| -> Vec<(f64, f64)> {
        v.iter().enumerate().map(|(g, &f)| (g as f64, f)).collect()
    };
    let (h, p) = (HUNTER_COLOUR, PREY_COLOUR);
    let fitness: Vec<Line> = vec![
        ("hunters best".into(), h, false, pts(hunters, |r| r.best)),
        ("hunters mean".into(), h, true, pts(hunters, |r| r.mean)),
        ("prey best".into(), p, false, pts(prey, |r| r.best)),
        ("prey mean".into(), p, true, pts(prey, |r| r.mean)),
    ];
    let catches: Vec<Line> = vec![
        (
            "in the hunters' games".into(),
            h,
            false,
            pts(hunters, |r| r.catch_rate),
        ),
        (
            "in the prey's games".into(),
            p,
            false,
            pts(prey, |r| r.catch_rate),
        ),
    ];
    let tournament: Vec<Line> = vec![
        ("hunter champions".into(), h, false, series(master[0])),
        ("prey champions".into(), p, false, series(master[1])),
    ];
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 980)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let title = "Hunters and prey over the generations";
        let root = (root.titled(title, (FAMILY, 20).into_font().style(FontStyle::Bold)))
            .map_err(draw_err)?;
        let panels = root.split_evenly((3, 1));
        let specs = [
            ("fitness (hunter + prey = 2)", 0.0..2.0, &fitness),
            ("catch rate", 0.0..1.0, &catches),
            ("master tournament fitness", 0.0..2.0, &tournament),
        ];
        for (area, (desc, range, lines)) in panels.iter().zip(specs) {
            draw_panel(area, n, desc, range, lines)?;
        }
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// One panel of the curves: generation on x, `desc` on y over `range`;
/// its legend on the right, off the curves.
fn draw_panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    n: f64,
    desc: &str,
    range: std::ops::Range<f64>,
    lines: &[Line],
) -> Result<(), FigureError> {
    let (plot, legend) = area.split_horizontally(area.dim_in_pixel().0 - 190);
    let mut chart = ChartBuilder::on(&plot)
        .margin_left(10)
        .margin_right(10)
        .margin_top(10)
        .x_label_area_size(44)
        .y_label_area_size(60)
        .build_cartesian_2d(-0.2..(n - 0.8).max(1.0), range)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .bold_line_style(RGBColor(225, 225, 225))
        .x_desc("generation")
        .y_desc(desc)
        .axis_desc_style(label_font())
        .label_style(axis_font())
        .x_label_formatter(&whole)
        .draw()
        .map_err(draw_err)?;
    for (k, (label, colour, dashed, points)) in lines.iter().enumerate() {
        let style = colour.stroke_width(2);
        if *dashed {
            chart.draw_series(DashedLineSeries::new(points.clone(), 6, 4, style))
        } else {
            chart.draw_series(LineSeries::new(points.clone(), style))
        }
        .map_err(draw_err)?;
        let y = 24 + 24 * k as i32;
        let keys: &[(i32, i32)] = if *dashed {
            &[(4, 14), (22, 32)]
        } else {
            &[(4, 32)]
        };
        for &(x0, x1) in keys {
            legend
                .draw(&PathElement::new(vec![(x0, y), (x1, y)], style))
                .map_err(draw_err)?;
        }
        legend
            .draw(&Text::new(label.as_str(), (40, y - 8), axis_font()))
            .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::test_util::{distinct_colours, png_size};

    fn cells(n: u32) -> Vec<CiaoCell> {
        (0..n)
            .flat_map(|h| {
                (0..n).map(move |p| CiaoCell {
                    hunter: h,
                    prey: p,
                    hunter_fitness: if h > p { 1.5 } else { 0.3 },
                    caught: h > p,
                })
            })
            .collect()
    }

    #[test]
    fn ciao_heat_map_draws_catches_and_misses_and_refuses_cells_outside() {
        let f = ciao(&cells(6), 6).unwrap();
        assert!(png_size(&f.png).0 > 1500);
        assert!(distinct_colours(&f.png) > 10);
        assert!(f.svg.contains("hunter generation") && f.svg.contains("prey generation"));
        assert!(ciao(&cells(6), 5).is_err(), "a cell outside the matrix");
        assert!(ciao(&[], 0).is_err());
    }

    #[test]
    fn curves_draw_both_sides_in_three_panels() {
        let rows: Vec<SideRow> = (0..5)
            .map(|g| SideRow {
                generation: g,
                best: 1.0 + f64::from(g) / 10.0,
                mean: 0.5,
                catch_rate: f64::from(g) / 5.0,
            })
            .collect();
        let m = [0.4, 0.8, 1.2, 1.0, 1.1];
        let f = curves(&rows, &rows, [&m, &m]).unwrap();
        for label in [
            "hunters best",
            "prey mean",
            "catch rate",
            "master tournament",
        ] {
            assert!(f.svg.contains(label), "{label}");
        }
        assert!(curves(&[], &rows, [&m, &m]).is_err());
    }
}

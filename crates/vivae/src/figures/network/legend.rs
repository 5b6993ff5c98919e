//! The legend along the bottom of the network figure: what lines, rings and
//! node colours mean.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{Root, WHEEL_RING};
use crate::figures::controller::{blend, px};
use crate::figures::{FigureError, NEGATIVE, POSITIVE, draw_err};

/// Legend along the bottom edge: what lines and nodes mean, and above it
/// self-loops and the bias colour scale.
pub(super) fn draw_legend(
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
pub(super) fn draw_legend_items(
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

//! The hill both MountainCar tasks drive on, as Gymnasium draws it (its
//! height 0.45·sin 3x + 0.55 from wall to wall), and the car on it: the
//! pictures of their report animations ([`super::sketch`]).

use vivae_neat::math::{atan2, cos, sin};

use super::sketch::{Shape, Sketch};

/// The left wall's position (both tasks' `min_position`).
const MIN_POSITION: f64 = -1.2;
/// The right wall's position (both tasks' `max_position`).
const MAX_POSITION: f64 = 0.6;

/// Gymnasium's picture of a MountainCar (either task): the hill (height 0.45·sin 3x +
/// 0.55) from wall to wall, the flag at `goal`, and over it what `frame`
/// draws of a step (the car, by [`car`]).
pub fn sketch(goal: f64, frame: fn(&[f64], &[f64], &mut Vec<Shape>)) -> Sketch {
    let hill = (0..=180)
        .map(|k| {
            let x = MIN_POSITION + (MAX_POSITION - MIN_POSITION) * f64::from(k) / 180.0;
            [x, height(x)]
        })
        .collect();
    let (foot, top) = ([goal, height(goal)], [goal, height(goal) + 0.15]);
    Sketch {
        view: [MIN_POSITION, 0.0, MAX_POSITION, 1.2],
        backdrop: vec![
            Shape::Line {
                points: hill,
                width: 0.006,
                colour: "#000000",
            },
            Shape::segment(foot, top, 0.004, "#000000"),
            Shape::Polygon {
                points: vec![top, [goal + 0.075, top[1] - 0.03], [goal, top[1] - 0.06]],
                colour: "#cccc00",
            },
        ],
        frame,
    }
}

/// The hill's height at `x`.
fn height(x: f64) -> f64 {
    0.45 * sin(3.0 * x) + 0.55
}

/// The car at `position`, along the hill's slope there, and its `push`
/// (−1 to 1, + to the right) as an arrow behind it.
pub fn car(position: f64, push: f64, shapes: &mut Vec<Shape>) {
    let (length, tall, clearance) = (0.12, 0.06, 0.03);
    let angle = atan2(1.35 * cos(3.0 * position), 1.0);
    let (ux, uy) = (cos(angle), sin(angle));
    let (nx, ny) = (-uy, ux);
    let ground = [position, height(position)];
    let at = |along: f64, up: f64| {
        [
            ground[0] + ux * along + nx * up,
            ground[1] + uy * along + ny * up,
        ]
    };
    shapes.push(Shape::bar(
        at(-length / 2.0, clearance + tall / 2.0),
        angle,
        length,
        tall,
        "#000000",
    ));
    for along in [-length / 3.0, length / 3.0] {
        shapes.push(Shape::Circle {
            centre: at(along, clearance),
            radius: 0.3 * tall,
            colour: "#808080",
        });
    }
    let side = -push.signum();
    let (start, end) = (length / 2.0 + 0.01 + 0.12 * push.abs(), length / 2.0 + 0.01);
    let middle = clearance + tall / 2.0;
    shapes.extend(Shape::arrow(
        at(side * start, middle),
        at(side * end, middle),
        0.012,
        "#d32f2f",
    ));
}

//! A plain task's episode as pictures, step by step, for report.html to
//! animate: shapes in the task's own coordinates (y up). A task declares
//! its [`Sketch`] (`Plain::sketch`: the box to show, what stays still, and
//! what one step shows, drawn from the network's inputs and outputs that the
//! episode's trace holds); [`Film::of`] draws every step of a trace's rows,
//! and the report draws any film the same way, whatever the task.

use serde::ser::{Serialize, SerializeTuple, Serializer};
use vivae_neat::math::{cos, sin};

/// A shape of a picture, in the task's coordinates (y up). It is written
/// as `[kind, colour, size, [x0, y0, x1, y1, …]]` (kind `line`, `polygon`
/// or `circle`; size the line's width, the circle's radius, 0 for a
/// polygon): a film has thousands, and names would be most of the page.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A line through `points`, `width` thick.
    Line {
        /// The points it passes through, in order.
        points: Vec<[f64; 2]>,
        /// Its thickness.
        width: f64,
        /// Its colour, `#rrggbb`.
        colour: &'static str,
    },
    /// A filled polygon.
    Polygon {
        /// Its corners, in order.
        points: Vec<[f64; 2]>,
        /// Its colour, `#rrggbb`.
        colour: &'static str,
    },
    /// A filled disc.
    Circle {
        /// Its centre.
        centre: [f64; 2],
        /// Its radius.
        radius: f64,
        /// Its colour, `#rrggbb`.
        colour: &'static str,
    },
}

impl Shape {
    /// A line from `a` to `b`.
    pub fn segment(a: [f64; 2], b: [f64; 2], width: f64, colour: &'static str) -> Shape {
        Shape::Line {
            points: vec![a, b],
            width,
            colour,
        }
    }

    /// A `length` × `width` bar from `from` along `angle` (radians,
    /// anticlockwise from the x axis), as a polygon.
    pub fn bar(from: [f64; 2], angle: f64, length: f64, width: f64, colour: &'static str) -> Shape {
        let (s, c) = (sin(angle), cos(angle));
        let (dx, dy) = (c * length, s * length);
        let (nx, ny) = (-s * width / 2.0, c * width / 2.0);
        Shape::Polygon {
            points: vec![
                [from[0] + nx, from[1] + ny],
                [from[0] + dx + nx, from[1] + dy + ny],
                [from[0] + dx - nx, from[1] + dy - ny],
                [from[0] - nx, from[1] - ny],
            ],
            colour,
        }
    }

    /// An arrow from `from` to `to`, its shaft `width` thick and its head
    /// three widths long.
    pub fn arrow(from: [f64; 2], to: [f64; 2], width: f64, colour: &'static str) -> Vec<Shape> {
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let length = (dx * dx + dy * dy).sqrt();
        if length == 0.0 {
            return Vec::new();
        }
        let (ux, uy) = (dx / length, dy / length);
        let head = (3.0 * width).min(length);
        let base = [to[0] - ux * head, to[1] - uy * head];
        let (nx, ny) = (-uy * width * 1.2, ux * width * 1.2);
        vec![
            Shape::segment(from, base, width, colour),
            Shape::Polygon {
                points: vec![
                    to,
                    [base[0] + nx, base[1] + ny],
                    [base[0] - nx, base[1] - ny],
                ],
                colour,
            },
        ]
    }

    /// A curved arrow around `centre` at `radius`, centred on the direction
    /// `at` (radians), turning anticlockwise for a positive `amount` and
    /// clockwise for a negative one, over `amount` half turns (|amount| ≤ 1).
    pub fn turn(
        centre: [f64; 2],
        radius: f64,
        at: f64,
        amount: f64,
        width: f64,
        colour: &'static str,
    ) -> Vec<Shape> {
        let span = std::f64::consts::PI * amount.clamp(-1.0, 1.0);
        // The head's length in radians along the arc.
        let head = (3.0 * width / radius).min(span.abs());
        if head == 0.0 {
            return Vec::new();
        }
        let point = |a: f64, r: f64| [centre[0] + r * cos(a), centre[1] + r * sin(a)];
        let (from, to) = (at - span / 2.0, at + span / 2.0);
        let base = to - head * span.signum();
        let points = (0..=ARC)
            .map(|k| point(from + (base - from) * f64::from(k) / f64::from(ARC), radius))
            .collect();
        vec![
            Shape::Line {
                points,
                width,
                colour,
            },
            Shape::Polygon {
                points: vec![
                    point(to, radius),
                    point(base, radius + 1.2 * width),
                    point(base, radius - 1.2 * width),
                ],
                colour,
            },
        ]
    }

    /// The shape with every coordinate and size rounded to `1/scale`.
    fn rounded(self, scale: f64) -> Shape {
        let r = |v: f64| (v * scale).round() / scale;
        let p = |points: Vec<[f64; 2]>| points.into_iter().map(|q| q.map(r)).collect();
        match self {
            Shape::Line {
                points,
                width,
                colour,
            } => Shape::Line {
                points: p(points),
                width: r(width),
                colour,
            },
            Shape::Polygon { points, colour } => Shape::Polygon {
                points: p(points),
                colour,
            },
            Shape::Circle {
                centre,
                radius,
                colour,
            } => Shape::Circle {
                centre: centre.map(r),
                radius: r(radius),
                colour,
            },
        }
    }
}

impl Serialize for Shape {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let (kind, colour, size, points) = match self {
            Shape::Line {
                points,
                width,
                colour,
            } => ("line", colour, *width, &points[..]),
            Shape::Polygon { points, colour } => ("polygon", colour, 0.0, &points[..]),
            Shape::Circle {
                centre,
                radius,
                colour,
            } => ("circle", colour, *radius, std::slice::from_ref(centre)),
        };
        let flat: Vec<f64> = points.iter().flatten().copied().collect();
        let mut t = serializer.serialize_tuple(4)?;
        t.serialize_element(kind)?;
        t.serialize_element(colour)?;
        t.serialize_element(&size)?;
        t.serialize_element(&flat)?;
        t.end()
    }
}

/// Segments of [`Shape::turn`]'s arc.
const ARC: u32 = 8;

/// How a task's episodes look.
#[derive(Debug, Clone)]
pub struct Sketch {
    /// The box shown: left, bottom, right, top.
    pub view: [f64; 4],
    /// What every step shows the same (a track, a hill).
    pub backdrop: Vec<Shape>,
    /// What one step shows, from the network's inputs (the observation) and
    /// outputs (its action) at that step, pushed onto the shapes given.
    pub frame: fn(inputs: &[f64], outputs: &[f64], shapes: &mut Vec<Shape>),
}

/// One step's picture.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Frame {
    /// The episode it belongs to (from 0).
    pub episode: u32,
    /// The reward the step earned.
    pub reward: f64,
    /// What it shows over the backdrop.
    pub shapes: Vec<Shape>,
}

/// Every step of an evaluation's episodes as pictures.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Film {
    /// The box shown: left, bottom, right, top.
    pub view: [f64; 4],
    /// What every step shows the same.
    pub backdrop: Vec<Shape>,
    /// The steps' pictures, episode after episode.
    pub frames: Vec<Frame>,
}

/// Pictures are rounded to the power of ten at or below this part of the
/// view's width (finer than a pixel at any size the page draws, and short
/// numbers keep the page small).
const PRECISION: f64 = 1e-4;

impl Film {
    /// The pictures of a trace's steps (its rows: episode, the network's
    /// inputs, its outputs, the reward), as `sketch` draws them.
    pub fn of(sketch: &Sketch, rows: &[(u32, Vec<f64>, Vec<f64>, f64)]) -> Film {
        let finest = PRECISION * (sketch.view[2] - sketch.view[0]).abs();
        let mut scale = 1.0;
        while 1.0 / scale > finest && scale < 1e12 {
            scale *= 10.0;
        }
        let round = |shapes: Vec<Shape>| shapes.into_iter().map(|s| s.rounded(scale)).collect();
        let frames = (rows.iter())
            .map(|(episode, inputs, outputs, reward)| {
                let mut shapes = Vec::new();
                (sketch.frame)(inputs, outputs, &mut shapes);
                Frame {
                    episode: *episode,
                    reward: *reward,
                    shapes: round(shapes),
                }
            })
            .collect();
        Film {
            view: sketch.view,
            backdrop: round(sketch.backdrop.clone()),
            frames,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_film_has_a_rounded_frame_for_every_step_of_the_trace() {
        fn frame(inputs: &[f64], outputs: &[f64], shapes: &mut Vec<Shape>) {
            shapes.push(Shape::Circle {
                centre: [inputs[0], outputs[0]],
                radius: 0.1,
                colour: "#000000",
            });
        }
        let sketch = Sketch {
            view: [-1.0, -1.0, 1.0, 1.0],
            backdrop: vec![Shape::segment(
                [-1.0, 0.0],
                [1.0, 0.123456],
                0.01,
                "#111111",
            )],
            frame,
        };
        let rows = [
            (0, vec![0.123456, 1.0], vec![0.5], 1.0),
            (1, vec![-0.5, 1.0], vec![-0.25], -2.0),
        ];
        let film = Film::of(&sketch, &rows);
        assert_eq!(film.frames.len(), 2);
        assert_eq!(film.frames[1].episode, 1);
        assert_eq!(film.frames[1].reward, -2.0);
        let Shape::Circle { centre, .. } = &film.frames[0].shapes[0] else {
            panic!("{film:?}")
        };
        assert!(centre[0] == 0.1235 && centre[1] == 0.5, "{centre:?}");
        let Shape::Line { points, .. } = &film.backdrop[0] else {
            panic!("{film:?}")
        };
        assert!(points[1][1] == 0.1235, "{points:?}");
    }

    #[test]
    fn a_shape_is_written_as_kind_colour_size_and_points() {
        let shapes = [
            Shape::segment([0.5, 1.0], [2.0, -1.5], 0.25, "#123456"),
            Shape::Polygon {
                points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                colour: "#000000",
            },
            Shape::Circle {
                centre: [3.0, 4.0],
                radius: 0.5,
                colour: "#ffffff",
            },
        ];
        assert_eq!(
            serde_json::to_string(&shapes).unwrap(),
            r##"[["line","#123456",0.25,[0.5,1.0,2.0,-1.5]],["polygon","#000000",0.0,[0.0,0.0,1.0,0.0,0.0,1.0]],["circle","#ffffff",0.5,[3.0,4.0]]]"##
        );
    }

    #[test]
    fn a_bar_and_an_arrow_point_where_asked() {
        let Shape::Polygon { points, .. } = Shape::bar([1.0, 2.0], 0.0, 3.0, 0.2, "#000000") else {
            panic!()
        };
        assert_eq!(points, vec![[1.0, 2.1], [4.0, 2.1], [4.0, 1.9], [1.0, 1.9]]);
        let arrow = Shape::arrow([0.0, 0.0], [0.0, -1.0], 0.1, "#000000");
        let Shape::Polygon { points, .. } = &arrow[1] else {
            panic!("{arrow:?}")
        };
        assert_eq!(points[0], [0.0, -1.0]);
        assert!(Shape::arrow([1.0, 1.0], [1.0, 1.0], 0.1, "#000000").is_empty());
        // A quarter turn anticlockwise around the origin, centred on the x axis: its head above it.
        let turn = Shape::turn([0.0, 0.0], 1.0, 0.0, 0.5, 0.05, "#000000");
        let Shape::Polygon { points, .. } = &turn[1] else {
            panic!("{turn:?}")
        };
        let tip = points[0];
        let expected = std::f64::consts::FRAC_PI_4;
        assert!((tip[0] - cos(expected)).abs() < 1e-12 && (tip[1] - sin(expected)).abs() < 1e-12);
        let back = Shape::turn([0.0, 0.0], 1.0, 0.0, -0.5, 0.05, "#000000");
        let Shape::Polygon { points, .. } = &back[1] else {
            panic!("{back:?}")
        };
        assert!(points[0][1] < 0.0, "{back:?}");
        assert!(Shape::turn([0.0, 0.0], 1.0, 0.0, 0.0, 0.05, "#000000").is_empty());
    }
}

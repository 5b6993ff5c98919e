//! The swerve: one robot passing what was in its way (a block placed for the
//! episode, or a scripted robot coming the other way), zoomed in, its path
//! seeing beside its path with the distance rays blinded (`vivae replay
//! --swerve`).
//!
//! The meeting drawn is the one blinding changes most: the block or
//! scripted robot that a robot touches with its rays blinded and passes
//! widest seeing. Without rays (or with them blinded already) it is the
//! closest pass of the one episode.

use std::fmt::Write as _;

use vivae_lab::tasks::driving::episode::Episode;
use vivae_neat::Genome;
use vivae_sim::draw::{self, DrawOptions, robot_color};
use vivae_sim::geometry::Shape;
use vivae_sim::{DVec2, World};

use crate::figures::{Figure, FigureError};

/// World px shown across the zoomed window.
const WINDOW: f64 = 180.0;
/// SVG units per world px.
const ZOOM: f64 = 4.0;
/// Clearance (px) at or below which two bodies count as touching.
const TOUCH: f64 = 0.5;
/// Clearance (px) up to which a robot passes beside what it meets (a road
/// is 60 px wide: farther, it was elsewhere on the road or the course).
const BESIDE: f64 = 30.0;

/// One robot meeting one thing.
#[derive(Debug, Clone, PartialEq)]
pub struct Meeting {
    /// The learner (0-based).
    pub robot: usize,
    /// What it met: `"block N"` (a placed block) or `"scripted robot N"`.
    pub what: String,
    /// Least clearance seeing (px between the bodies) and its step.
    pub seeing: (f64, usize),
    /// Least clearance with the rays blinded and its step, when the run has rays.
    pub blinded: Option<(f64, usize)>,
}

/// A finished episode's paths: learners' and scripted robots'.
struct Paths {
    world: World,
}

impl Paths {
    fn run(experiment: &Episode, genome: &Genome) -> Result<Paths, FigureError> {
        let c = (experiment.robot_controller(genome))
            .map_err(|e| FigureError::Invalid(e.to_string()))?;
        Ok(Paths {
            world: experiment.run_world(&c, true).1,
        })
    }

    fn robot(&self, i: usize) -> &[DVec2] {
        &self.world.trajectories().expect("recorded")[i]
    }

    fn traffic(&self, j: usize) -> &[DVec2] {
        &self.world.traffic_trajectories().expect("recorded")[j]
    }
}

/// What a robot can meet: a placed block or a scripted robot.
#[derive(Debug, Clone)]
enum Thing {
    Block(usize, Shape),
    Traffic(usize),
}

impl Thing {
    fn name(&self) -> String {
        match self {
            Thing::Block(k, _) => format!("block {}", k + 1),
            Thing::Traffic(j) => format!("scripted robot {}", j + 1),
        }
    }

    /// Where it is at `step` of `paths`.
    fn at(&self, paths: &Paths, step: usize) -> DVec2 {
        match self {
            Thing::Block(_, b) => b.bbox.center(),
            Thing::Traffic(j) => paths.traffic(*j)[step],
        }
    }

    /// Least clearance (px) of robot `i` of `paths`, radius `r`, and its step.
    fn closest(&self, paths: &Paths, i: usize, r: f64) -> (f64, usize) {
        let mut best = (f64::INFINITY, 0);
        for (step, &p) in paths.robot(i).iter().enumerate() {
            let gap = match self {
                Thing::Block(_, b) if b.contains(p) => -r,
                Thing::Block(_, b) => b.closest_boundary_point(p).1 - r,
                Thing::Traffic(j) => paths.traffic(*j)[step].distance(p) - 2.0 * r,
            };
            if gap < best.0 {
                best = (gap, step);
            }
        }
        best
    }
}

/// The things of `world` a robot can meet: its placed blocks and scripted robots.
fn things(world: &World) -> Vec<Thing> {
    let sc = world.scenario();
    let fixed = &sc.fixed_obstacles;
    let first = fixed.len() - sc.placed_obstacles.min(fixed.len());
    let blocks = (fixed[first..].iter().enumerate()).map(|(k, o)| Thing::Block(k, o.shape.clone()));
    blocks
        .chain((0..world.traffic().len()).map(Thing::Traffic))
        .collect()
}

/// The swerve of `genome` on `experiment` (a placement fixed): the figure
/// and the meeting it shows; `None` when the scenario has nothing to meet.
pub fn swerve(
    experiment: &Episode,
    genome: &Genome,
    title: &str,
) -> Result<Option<(Figure, Meeting)>, FigureError> {
    let seeing = Paths::run(experiment, genome)?;
    let blind = match experiment.blind_rays() {
        true => None,
        false => experiment.clone().with_blind_rays().ok(),
    };
    let blinded = blind.map(|e| Paths::run(&e, genome)).transpose()?;
    let r = seeing.world.params().robot_radius;
    let mut best: Option<(f64, Meeting, Thing)> = None;
    for thing in things(&seeing.world) {
        for i in 0..seeing.world.robots().len() {
            let s = thing.closest(&seeing, i, r);
            let b = blinded.as_ref().map(|p| thing.closest(p, i, r));
            // Blinding's effect first (touched blinded, passed beside seeing,
            // the widest pass); then the closest pass beside; then the closest.
            let beside = s.0 > TOUCH && s.0 <= BESIDE;
            let score = match b {
                Some(b) if b.0 <= TOUCH && beside => 3e6 + s.0,
                _ if beside => 2e6 - s.0,
                _ => -s.0,
            };
            if best.as_ref().is_none_or(|(top, _, _)| score > *top) {
                let m = Meeting {
                    robot: i,
                    what: thing.name(),
                    seeing: s,
                    blinded: b,
                };
                best = Some((score, m, thing.clone()));
            }
        }
    }
    let Some((_, meeting, thing)) = best else {
        return Ok(None);
    };
    let svg = draw_svg(
        experiment,
        &seeing,
        blinded.as_ref(),
        &meeting,
        &thing,
        title,
    );
    let png = draw::svg_to_png(&svg, 1.0).map_err(|e| FigureError::Png(e.to_string()))?;
    Ok(Some((Figure { svg, png }, meeting)))
}

/// `points` as an SVG polyline's points.
fn points(points: &[DVec2]) -> String {
    let mut s = String::new();
    for p in points {
        let _ = write!(s, "{:.1},{:.1} ", p.x, p.y);
    }
    s
}

fn draw_svg(
    experiment: &Episode,
    seeing: &Paths,
    blinded: Option<&Paths>,
    m: &Meeting,
    thing: &Thing,
    title: &str,
) -> String {
    let world = experiment.world();
    let (w, h) = (world.scenario().width(), world.scenario().height());
    let centre = thing.at(seeing, m.seeing.1);
    let half = WINDOW / 2.0;
    let x0 = (centre.x - half).clamp(0.0, (w - WINDOW).max(0.0));
    let y0 = (centre.y - half).clamp(0.0, (h - WINDOW).max(0.0));
    let side = WINDOW * ZOOM;
    let lines = caption(m, blinded.is_some(), title);
    let band = 22.0 * lines.len() as f64 + 8.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{side}" height="{}" viewBox="0 0 {side} {}">"##,
        side + band,
        side + band
    );
    let _ = writeln!(
        s,
        r##"<rect x="0" y="0" width="{side}" height="{band}" fill="#ffffff"/>"##
    );
    for (k, line) in lines.iter().enumerate() {
        let _ = writeln!(
            s,
            r##"<text x="8" y="{}" font-family="DejaVu Sans" font-size="15" fill="#000000">{}</text>"##,
            20.0 + 22.0 * k as f64,
            xml_escape(line)
        );
    }
    // The course at the start of the episode (blocks are placed for its
    // whole length), the window of it cut out by a nested viewBox.
    let options = DrawOptions {
        trajectories: false,
        legend: false,
        ..DrawOptions::default()
    };
    let course = draw::render_svg(world, &options);
    let inner = course
        .split_once('\n')
        .map_or("", |(_, rest)| rest)
        .trim_end()
        .trim_end_matches("</svg>");
    let _ = writeln!(
        s,
        r##"<svg x="0" y="{band}" width="{side}" height="{side}" viewBox="{x0:.1} {y0:.1} {WINDOW} {WINDOW}">"##
    );
    s += inner;
    overlay(&mut s, world, seeing, blinded, m, thing);
    s += "</svg>\n</svg>\n";
    s
}

/// The figure's caption: title, the meeting seeing and blinded, the legend.
fn caption(m: &Meeting, blinded: bool, title: &str) -> Vec<String> {
    let clearance = |(gap, step): (f64, usize)| match gap <= TOUCH {
        true => format!("touches at step {step}"),
        false => format!("passes {gap:.1} px clear at step {step}"),
    };
    let mut lines = vec![
        title.to_string(),
        format!(
            "robot {} and {}: seeing, it {}",
            m.robot + 1,
            m.what,
            clearance(m.seeing)
        ),
    ];
    if let Some(b) = m.blinded {
        lines.push(format!("rays blinded, it {}", clearance(b)));
    }
    let legend = match blinded {
        true => {
            "solid: seeing; dashed: rays blinded; dots: closest approach; magenta ring: what is met"
        }
        false => "solid: the path; dot: closest approach; magenta ring: what is met",
    };
    lines.push(legend.to_string());
    lines
}

/// The paths drawn over the course: the scripted robot met (if one), the
/// ring round what is met, the robot's path blinded and seeing.
fn overlay(
    s: &mut String,
    world: &World,
    seeing: &Paths,
    blinded: Option<&Paths>,
    m: &Meeting,
    thing: &Thing,
) {
    let r = world.params().robot_radius;
    let color = robot_color(m.robot);
    // A scripted robot's path near the meeting, where it was then.
    if let Thing::Traffic(j) = thing {
        let path = seeing.traffic(*j);
        let (a, b) = (
            m.seeing.1.saturating_sub(60),
            (m.seeing.1 + 60).min(path.len()),
        );
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="#404040" stroke-width="0.8" stroke-dasharray="2 2"/>"##,
            points(&path[a..b])
        );
    }
    let at = thing.at(seeing, m.seeing.1);
    let _ = writeln!(
        s,
        r##"<circle cx="{:.1}" cy="{:.1}" r="{:.1}" fill="none" stroke="#ff00ff" stroke-width="1.2"/>"##,
        at.x,
        at.y,
        r + 8.0
    );
    if let (Some(p), Some(b)) = (blinded, m.blinded) {
        let path = p.robot(m.robot);
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="#000000" stroke-width="1" stroke-dasharray="3 2"/>"##,
            points(path)
        );
        let q = path[b.1];
        let _ = writeln!(
            s,
            r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="none" stroke="#000000" stroke-width="0.8" stroke-dasharray="1.5 1"/>"##,
            q.x, q.y
        );
    }
    let path = seeing.robot(m.robot);
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1.4"/>"##,
        points(path)
    );
    let q = path[m.seeing.1];
    let _ = writeln!(
        s,
        r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="{color}" fill-opacity="0.5" stroke="#000000" stroke-width="0.6"/>"##,
        q.x, q.y
    );
}

fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

//! Behaviour as numbers: collisions, completed turns, loops and the side of
//! the road the robots keep to, measured over a recorded episode.
//!
//! The paper judged its controllers by eye (Figs. 5–6); these measures make
//! the same judgements reproducible. Definitions
//! (docs/explanation/behaviour-measures.md):
//!
//! * **collisions** — contacts that begin, per 1,000 robot-steps: a robot
//!   touching another robot (a learner or a scripted one) or an obstacle
//!   (fixed, movable or placed for the episode) at a step when that pair was
//!   not touching at the step before. Touching: the gap between the outlines
//!   is at most [`TOUCH`] px after the step's contact resolution.
//! * **contacts by kind** — the same per 1,000 robot-steps for each kind
//!   ([`crate::tasks::driving::contacts`]): robot–robot, robot–scripted
//!   robot, robot–obstacle, and robot–wall (not in `collisions`).
//! * **turns** — each robot's heading is unwrapped over the episode; the robot
//!   is *straight* at step t when its heading moved less than [`STRAIGHT_DEG`]
//!   over the last [`STRAIGHT_WINDOW`] steps. Between two straight stretches
//!   the net heading change Δ is one manoeuvre: 45° ≤ |Δ| < 270° is a
//!   completed right (Δ > 0, clockwise on screen) or left turn.
//! * **loops** — a manoeuvre with |Δ| ≥ 270° (the paper's Fig. 6 failure: a
//!   full circle one way instead of a turn the other): ⌊(|Δ| + 90°) / 360°⌋
//!   loops. A manoeuvre still going at the end counts only as loops.
//! * **side** — on road, the robot's signed offset from the road's centre
//!   across its heading, in half-widths: (l − r) / (l + r), where l and r are
//!   the distances to the road's edge straight left and right of the robot
//!   (probed in 1 px steps up to [`SIDE_PROBE`] px). +1 = on the right edge,
//!   −1 = on the left edge; the mean over every robot-step where both edges
//!   are found. `None` when no step qualified.

use serde::Serialize;
use vivae_sim::DVec2;
use vivae_sim::{SurfaceKind, World, wrap_angle};

use crate::tasks::driving::contacts::{ContactCounter, ContactRates};

pub use crate::tasks::driving::contacts::TOUCH;
/// Steps over which a straight robot's heading stays within [`STRAIGHT_DEG`].
pub const STRAIGHT_WINDOW: usize = 25;
/// Heading change, in degrees, below which a robot drives straight.
pub const STRAIGHT_DEG: f64 = 10.0;
/// Farthest distance, in px, probed for a road edge beside a robot.
pub const SIDE_PROBE: u32 = 200;

/// Behaviour measures of one episode (definitions in the module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Behaviour {
    /// Contacts begun per 1,000 robot-steps (robot–robot and robot–obstacle).
    pub collisions: f64,
    /// Completed left turns, all robots.
    pub left_turns: u32,
    /// Completed right turns, all robots.
    pub right_turns: u32,
    /// Turns of 270° or more, all robots.
    pub loops: u32,
    /// Mean signed offset from the road's centre in half-widths, right positive.
    pub side: Option<f64>,
    /// Contacts begun per 1,000 robot-steps, by what was touched.
    pub contacts: ContactRates,
}

impl Behaviour {
    /// The measures as `key=value` pairs, as `replay` prints them.
    pub fn fields(&self) -> String {
        let side = self
            .side
            .map_or_else(|| "none".to_string(), |s| format!("{s:.4}"));
        format!(
            "collisions={:.3} left_turns={} right_turns={} loops={} side={side} {}",
            self.collisions,
            self.left_turns,
            self.right_turns,
            self.loops,
            self.contacts.fields()
        )
    }
}

/// Accumulates [`Behaviour`] step by step (allocates only on creation and
/// for the heading history).
#[derive(Debug, Clone)]
pub struct BehaviourMeter {
    /// Unwrapped heading of each robot at every observed step.
    headings: Vec<Vec<f64>>,
    /// Contacts by kind.
    contacts: ContactCounter,
    robot_steps: u64,
    side_sum: f64,
    side_steps: u64,
    /// Whether the side of the road is probed (the costliest measure).
    side: bool,
}

impl BehaviourMeter {
    /// A meter for `world`'s robots, observing up to `steps` steps.
    pub fn new(world: &World, steps: usize) -> Self {
        BehaviourMeter {
            headings: world
                .robots()
                .iter()
                .map(|r| {
                    let mut h = Vec::with_capacity(steps + 1);
                    h.push(r.heading);
                    h
                })
                .collect(),
            contacts: ContactCounter::new(world),
            robot_steps: 0,
            side_sum: 0.0,
            side_steps: 0,
            side: true,
        }
    }

    /// This meter probing the side of the road (the default) or not (then
    /// [`Behaviour::side`] is `None`).
    pub fn measuring_side(mut self, side: bool) -> Self {
        self.side = side;
        self
    }

    /// Takes the measures of `world` after one step.
    pub fn observe(&mut self, world: &World) {
        let robots = world.robots();
        let n = robots.len();
        self.contacts.observe(world);
        for (i, robot) in robots.iter().enumerate() {
            let history = &mut self.headings[i];
            let last = *history.last().expect("starts with the initial heading");
            history.push(last + wrap_angle(robot.heading - wrap_angle(last)));
            if let Some(s) = self
                .side
                .then(|| side_offset(world, robot.pos, robot.right()))
                .flatten()
            {
                self.side_sum += s;
                self.side_steps += 1;
            }
        }
        self.robot_steps += n as u64;
    }

    /// The measures of the steps observed.
    pub fn finish(&self) -> Behaviour {
        let (mut left_turns, mut right_turns, mut loops) = (0, 0, 0);
        for h in &self.headings {
            let m = manoeuvres(h);
            left_turns += m.left;
            right_turns += m.right;
            loops += m.loops;
        }
        Behaviour {
            collisions: if self.robot_steps == 0 {
                0.0
            } else {
                1000.0 * self.contacts.counts().collisions() as f64 / self.robot_steps as f64
            },
            contacts: ContactRates::of(self.contacts.counts(), self.robot_steps),
            left_turns,
            right_turns,
            loops,
            side: (self.side_steps > 0).then(|| self.side_sum / self.side_steps as f64),
        }
    }
}

/// Signed offset from the road's centre, in half-widths (right positive);
/// `None` off road or when an edge is farther than [`SIDE_PROBE`].
fn side_offset(world: &World, p: DVec2, right: DVec2) -> Option<f64> {
    let on_road = |q: DVec2| {
        world
            .surface_at(q)
            .is_some_and(|s| s.kind == SurfaceKind::Road)
    };
    if !on_road(p) {
        return None;
    }
    let edge = |dir: DVec2| (1..=SIDE_PROBE).find(|&s| !on_road(p + dir * f64::from(s)));
    let (r, l) = (f64::from(edge(right)?), f64::from(edge(-right)?));
    Some((l - r) / (l + r))
}

/// Completed turns and loops of one robot's unwrapped heading history.
#[derive(Debug, Default, PartialEq)]
struct Manoeuvres {
    left: u32,
    right: u32,
    loops: u32,
}

fn manoeuvres(h: &[f64]) -> Manoeuvres {
    let straight_rad = STRAIGHT_DEG.to_radians();
    let straight =
        |t: usize| t < STRAIGHT_WINDOW || (h[t] - h[t - STRAIGHT_WINDOW]).abs() < straight_rad;
    let mut m = Manoeuvres::default();
    let count_loops = |delta: f64| ((delta.abs().to_degrees() + 90.0) / 360.0).floor() as u32;
    // Heading at the last straight step before the manoeuvre in progress.
    let mut before: Option<f64> = None;
    for t in 0..h.len() {
        match (straight(t), before) {
            // The window's first heading: the robot was straight then.
            (false, None) => before = Some(h[t.saturating_sub(STRAIGHT_WINDOW)]),
            (true, Some(b)) => {
                let delta = h[t] - b;
                let deg = delta.abs().to_degrees();
                if deg >= 270.0 {
                    m.loops += count_loops(delta);
                } else if deg >= 45.0 {
                    if delta > 0.0 {
                        m.right += 1;
                    } else {
                        m.left += 1;
                    }
                }
                before = None;
            }
            _ => {}
        }
    }
    if let (Some(b), Some(&end)) = (before, h.last()) {
        m.loops += count_loops(end - b);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A heading history: `straight` steps, then `turn_deg` spread over `over` steps, then `straight` again.
    fn history(turn_deg: f64, over: usize) -> Vec<f64> {
        let mut h = vec![0.3; 100];
        for k in 1..=over {
            h.push(0.3 + turn_deg.to_radians() * k as f64 / over as f64);
        }
        let end = *h.last().unwrap();
        h.extend(std::iter::repeat_n(end, 100));
        h
    }

    #[test]
    fn a_quarter_turn_each_way_is_one_turn() {
        assert_eq!(
            manoeuvres(&history(90.0, 40)),
            Manoeuvres {
                left: 0,
                right: 1,
                loops: 0
            }
        );
        assert_eq!(
            manoeuvres(&history(-90.0, 40)),
            Manoeuvres {
                left: 1,
                right: 0,
                loops: 0
            }
        );
    }

    #[test]
    fn a_lane_wiggle_is_no_turn_and_a_circle_the_wrong_way_is_a_loop() {
        assert_eq!(manoeuvres(&history(20.0, 40)), Manoeuvres::default());
        // The paper's Fig. 6: 270° clockwise instead of 90° anticlockwise.
        assert_eq!(
            manoeuvres(&history(270.0, 120)),
            Manoeuvres {
                left: 0,
                right: 0,
                loops: 1
            }
        );
        assert_eq!(
            manoeuvres(&history(-720.0, 300)),
            Manoeuvres {
                left: 0,
                right: 0,
                loops: 2
            }
        );
    }

    #[test]
    fn circling_until_the_end_counts_as_loops_only() {
        let h: Vec<f64> = (0..400).map(|t| 0.05 * t as f64).collect();
        let full_circles = 0.05 * 399.0 / (2.0 * std::f64::consts::PI);
        let m = manoeuvres(&h);
        assert_eq!((m.left, m.right), (0, 0));
        assert_eq!(m.loops, (full_circles + 0.25).floor() as u32);
    }

    /// A 40 px wide road along x (y 100..140) and two robots on it.
    fn road_world() -> World {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="400" height="300">
            <rect id="road" x="0" y="100" width="400" height="40" inkscape:label="Road"/>
            <rect id="r1" x="40" y="114" width="12" height="12" inkscape:label="Robot"/>
            <rect id="r2" x="340" y="114" width="12" height="12" inkscape:label="Robot"/></svg>"#;
        let sc = vivae_sim::Scenario::from_svg(svg, "t.svg", &Default::default()).unwrap();
        World::new(&sc, &vivae_sim::PhysicsParams::default()).unwrap()
    }

    #[test]
    fn side_is_positive_right_of_the_centre_line_and_negative_left_of_it() {
        let east = std::f64::consts::FRAC_PI_2;
        let mut world = road_world();
        // Heading east, +y (down on screen) is the robot's right.
        world.set_pose(0, DVec2::new(100.0, 130.5), east);
        world.set_pose(1, DVec2::new(300.0, 109.5), east);
        let mut meter = BehaviourMeter::new(&world, 1);
        meter.observe(&world);
        let side = meter.finish().side.unwrap();
        // Robot 1: 31 px to the left edge, 10 to the right; robot 2 mirrored.
        let one = (31.0 - 10.0) / 41.0;
        assert!((side - (one - one) / 2.0).abs() < 1e-12, "{side}");
        let mut meter = BehaviourMeter::new(&world, 1);
        world.set_pose(1, DVec2::new(300.0, 130.5), east);
        meter.observe(&world);
        assert!((meter.finish().side.unwrap() - one).abs() < 1e-12);
    }

    #[test]
    fn robots_driving_head_on_collide_once() {
        let mut world = road_world();
        world.set_pose(0, DVec2::new(150.0, 120.0), std::f64::consts::FRAC_PI_2);
        world.set_pose(1, DVec2::new(250.0, 120.0), -std::f64::consts::FRAC_PI_2);
        let steps = 200;
        let mut meter = BehaviourMeter::new(&world, steps);
        for _ in 0..steps {
            world.step(&[[1.0, 1.0], [1.0, 1.0]]);
            meter.observe(&world);
        }
        let b = meter.finish();
        assert_eq!(b.collisions, 1000.0 / (2.0 * steps as f64), "{b:?}");
        assert_eq!((b.left_turns, b.right_turns, b.loops), (0, 0, 0));
    }

    #[test]
    fn wrap_stays_in_the_half_open_interval() {
        use std::f64::consts::PI;
        for a in [-7.0, -PI, -1.0, 0.0, 1.0, PI, 4.0, 13.0] {
            let w = wrap_angle(a);
            assert!(w > -PI && w <= PI, "{a} -> {w}");
            assert!(
                ((a - w) / (2.0 * PI)).fract().abs() < 1e-9
                    || ((a - w) / (2.0 * PI)).fract().abs() > 1.0 - 1e-9
            );
        }
    }
}

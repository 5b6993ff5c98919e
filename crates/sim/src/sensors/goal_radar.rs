//! The goal radar (Lehman & Stanley 2011's maze robot): pie slices around
//! the robot, the one the goal lies in reads 1, the others 0.

use std::f64::consts::{PI, TAU};

use glam::DVec2;

use super::{Sensor, SensorPlace, frame};
use crate::physics::{ParamError, check};
use crate::world::World;

/// Pie-slice goal radar: `n` equal slices of the full circle around the
/// robot, in reading order left to right by their centre angle; the last is
/// centred straight behind. With the paper's four: left, ahead, right, behind.
///
/// The slices see through walls and have no range, as in the paper: they
/// say only in which direction the goal lies.
#[derive(Clone, Debug, PartialEq)]
pub struct GoalRadar {
    /// Where the goal is, px.
    goal: DVec2,
    /// Slice width, radians.
    width: f64,
    places: Vec<SensorPlace>,
}

impl GoalRadar {
    /// `slices` equal pie slices pointing at `goal`; `slices` must be in 1..=360.
    pub fn new(goal: DVec2, slices: usize) -> Result<GoalRadar, ParamError> {
        check(
            "slices",
            slices as f64,
            (1..=360).contains(&slices),
            "must be in 1..=360",
        )?;
        check(
            "goal",
            goal.x,
            goal.x.is_finite() && goal.y.is_finite(),
            "must be finite",
        )?;
        let width = TAU / slices as f64;
        let places = (0..slices)
            .map(|j| SensorPlace {
                ring: 0,
                angle_index: j,
                distance: 0.0,
                angle: -PI + (j + 1) as f64 * width,
            })
            .collect();
        Ok(GoalRadar {
            goal,
            width,
            places,
        })
    }

    /// The paper's four slices (left, ahead, right, behind) pointing at `goal`.
    pub fn paper(goal: DVec2) -> Result<GoalRadar, ParamError> {
        GoalRadar::new(goal, 4)
    }

    /// Where the goal is, px.
    pub fn goal(&self) -> DVec2 {
        self.goal
    }

    /// The slice the direction `angle` (radians from ahead, negative = left,
    /// in [−π, π]) falls in: slice `j` spans `(c_j − w/2, c_j + w/2]` around
    /// its centre `c_j = −π + (j+1)·w`.
    pub fn slice_of(&self, angle: f64) -> usize {
        let n = self.places.len();
        let t = ((angle + PI) / self.width - 0.5).ceil() - 1.0;
        if t < 0.0 || t >= n as f64 {
            n - 1
        } else {
            t as usize
        }
    }
}

/// Reads 1 for the slice the goal lies in, 0 for the others.
impl Sensor for GoalRadar {
    fn name(&self) -> &'static str {
        "goal_radar"
    }

    fn rings(&self) -> usize {
        1
    }

    fn places(&self) -> &[SensorPlace] {
        &self.places
    }

    fn read(&self, world: &World, i: usize, out: &mut [f64]) {
        let (p, ahead, right) = frame(world, i);
        let d = self.goal - p;
        // Portable libm: the bits must not depend on the platform.
        let angle = libm::atan2(d.dot(right), d.dot(ahead));
        let hit = self.slice_of(angle);
        for (j, v) in out[..self.places.len()].iter_mut().enumerate() {
            *v = if j == hit { 1.0 } else { 0.0 };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LoadOptions, PhysicsParams, Scenario};

    fn world_facing_up() -> World {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"
            xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
            width="200" height="200">
            <rect id="r" inkscape:label="Robot" x="94" y="94" width="12" height="12"/>
            </svg>"#;
        let sc = Scenario::from_svg(svg, "t.svg", &LoadOptions::default()).unwrap();
        World::new(&sc, &PhysicsParams::default()).unwrap()
    }

    fn read(goal: DVec2) -> Vec<f64> {
        let radar = GoalRadar::paper(goal).unwrap();
        let mut out = vec![9.0; 4];
        radar.read(&world_facing_up(), 0, &mut out);
        out
    }

    #[test]
    fn the_slice_the_goal_lies_in_reads_one() {
        // The robot sits at (100, 100) facing up (−y); slices: left, ahead, right, behind.
        assert_eq!(read(DVec2::new(100.0, 10.0)), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(read(DVec2::new(190.0, 95.0)), [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(read(DVec2::new(100.0, 190.0)), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(read(DVec2::new(10.0, 105.0)), [1.0, 0.0, 0.0, 0.0]);
        // Ahead and a little to the right is still ahead; beyond 45° it is right.
        assert_eq!(read(DVec2::new(140.0, 50.0)), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(read(DVec2::new(160.0, 50.0)), [0.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn slices_tile_the_circle_left_to_right() {
        let radar = GoalRadar::paper(DVec2::ZERO).unwrap();
        let angles: Vec<f64> = radar.places().iter().map(|p| p.angle).collect();
        assert_eq!(angles, [-PI / 2.0, 0.0, PI / 2.0, PI]);
        assert_eq!(radar.slice_of(0.0), 1);
        assert_eq!(radar.slice_of(PI / 4.0 + 1e-9), 2);
        assert_eq!(radar.slice_of(-PI), 3);
        assert_eq!(radar.slice_of(PI), 3);
        assert_eq!(radar.slice_of(-3.0 * PI / 4.0 + 1e-9), 0);
        for (j, &a) in angles.iter().enumerate() {
            assert_eq!(radar.slice_of(a), j);
        }
    }

    #[test]
    fn bad_radars_are_refused() {
        assert_eq!(GoalRadar::new(DVec2::ZERO, 0).unwrap_err().field, "slices");
        let nan = DVec2::new(f64::NAN, 0.0);
        assert_eq!(GoalRadar::new(nan, 4).unwrap_err().field, "goal");
        assert_eq!(GoalRadar::new(DVec2::ZERO, 1).unwrap().slice_of(2.0), 0);
    }
}

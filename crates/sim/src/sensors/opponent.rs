//! The opponent radar: pie slices around the robot, like the maze's goal
//! radar ([`GoalRadar`]), pointing at the nearest robot of another team and
//! saying how near it is.

use super::{GoalRadar, Sensor, SensorPlace, frame};
use crate::physics::{ParamError, check};
use crate::world::World;

/// Opponent radar: `slices` equal pie slices of the full circle around the
/// robot, in reading order left to right by their centre angle, the last
/// centred behind (the slices of [`GoalRadar::new`]). The slice holding the
/// nearest robot of another team (`data-team`) reads `1 − d/range` for its
/// centre distance `d` (0 beyond `range`); every other slice reads 0, as do
/// all of them when the robot has no team or no opponent.
///
/// The slices see through walls, as the goal radar does.
#[derive(Clone, Debug, PartialEq)]
pub struct OpponentRadar {
    slices: GoalRadar,
    range: f64,
}

impl OpponentRadar {
    /// `slices` (1..=360) pie slices seeing opponents up to `range` px (> 0) away.
    pub fn new(slices: usize, range: f64) -> Result<OpponentRadar, ParamError> {
        check("range", range, range > 0.0, "must be > 0")?;
        Ok(OpponentRadar {
            slices: GoalRadar::new(glam::DVec2::ZERO, slices)?,
            range,
        })
    }

    /// How far it sees, px.
    pub fn range(&self) -> f64 {
        self.range
    }

    /// The nearest robot of another team than robot `i` and its distance
    /// (ties: the first in scenario order).
    pub fn nearest(world: &World, i: usize) -> Option<(usize, f64)> {
        let p = world.robots().get(i)?.pos;
        let mut best: Option<(usize, f64)> = None;
        for (j, r) in world.robots().iter().enumerate() {
            if world.opponents(i, j) {
                let d2 = r.pos.distance_squared(p);
                if best.is_none_or(|(_, b)| d2 < b) {
                    best = Some((j, d2));
                }
            }
        }
        best.map(|(j, d2)| (j, d2.sqrt()))
    }
}

impl Sensor for OpponentRadar {
    fn name(&self) -> &'static str {
        "opponent"
    }

    fn rings(&self) -> usize {
        1
    }

    fn places(&self) -> &[SensorPlace] {
        self.slices.places()
    }

    fn read(&self, world: &World, i: usize, out: &mut [f64]) {
        let out = &mut out[..self.len()];
        out.fill(0.0);
        let Some((j, d)) = OpponentRadar::nearest(world, i) else {
            return;
        };
        let (p, ahead, right) = frame(world, i);
        let v = world.robots()[j].pos - p;
        // Portable libm: the bits must not depend on the platform.
        let angle = libm::atan2(v.dot(right), v.dot(ahead));
        out[self.slices.slice_of(angle)] = (1.0 - d / self.range).max(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LoadOptions, PhysicsParams, Scenario};

    /// A robot at (100, 100) facing up, of team `me`, and robots of the
    /// given teams at the given places.
    fn world(me: &str, others: &[(&str, f64, f64)]) -> World {
        let rect = |id: String, team: &str, x: f64, y: f64| {
            format!(
                r#"<rect id="{id}" inkscape:label="Robot" data-team="{team}" x="{}" y="{}" width="12" height="12"/>"#,
                x - 6.0,
                y - 6.0
            )
        };
        let mut body = rect("me".into(), me, 100.0, 100.0);
        for (k, (team, x, y)) in others.iter().enumerate() {
            body += &rect(format!("r{k}"), team, *x, *y);
        }
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg"
            xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
            width="400" height="400">{body}</svg>"#
        );
        let sc = Scenario::from_svg(&svg, "t.svg", &LoadOptions::default()).unwrap();
        World::new(&sc, &PhysicsParams::default()).unwrap()
    }

    fn read(w: &World) -> Vec<f64> {
        let radar = OpponentRadar::new(4, 200.0).unwrap();
        let mut out = vec![9.0; 4];
        radar.read(w, 0, &mut out);
        out
    }

    #[test]
    fn the_slice_of_the_nearest_opponent_reads_its_nearness() {
        // Ahead 50 px: slice "ahead" reads 1 − 50/200.
        let w = world("hunter", &[("prey", 100.0, 50.0), ("prey", 300.0, 100.0)]);
        assert_eq!(read(&w), [0.0, 0.75, 0.0, 0.0]);
        // A team-mate nearer than the opponent is not seen.
        let w = world("hunter", &[("hunter", 100.0, 90.0), ("prey", 100.0, 200.0)]);
        assert_eq!(read(&w), [0.0, 0.0, 0.0, 0.5]);
        // Left, beyond range: the slice is found, the reading is 0.
        let w = world("hunter", &[("prey", 390.0, 100.0)]);
        assert_eq!(read(&w), [0.0, 0.0, 0.0, 0.0]);
        let w = world("hunter", &[("prey", 20.0, 100.0)]);
        assert_eq!(read(&w), [0.6, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn no_opponent_reads_zero() {
        assert_eq!(read(&world("prey", &[("prey", 100.0, 50.0)])), [0.0; 4]);
        let radar = OpponentRadar::new(4, 200.0).unwrap();
        assert_eq!(radar.places().len(), 4);
        assert_eq!(OpponentRadar::new(4, 0.0).unwrap_err().field, "range");
        assert_eq!(OpponentRadar::new(0, 1.0).unwrap_err().field, "slices");
    }
}

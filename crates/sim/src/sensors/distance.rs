//! Distance sensors (beyond the paper): rays over a field of view that see
//! robots, pucks, obstacles and walls.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::{Sensor, SensorPlace, check_fov, frame, local, spread};
use crate::geometry::{Aabb, ray_disc};
use crate::physics::{ParamError, check};
use crate::world::World;

/// Distance sensors: rays over a field of view (beyond the paper).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DistanceSensors {
    /// Number of rays, default 5.
    pub rays: usize,
    /// Field of view in degrees (default 180).
    pub fov: f64,
    /// Ray length from the robot's rim, px (default 100).
    pub range: f64,
}

impl Default for DistanceSensors {
    fn default() -> Self {
        DistanceSensors {
            rays: 5,
            fov: 180.0,
            range: 100.0,
        }
    }
}

impl DistanceSensors {
    /// Checks the layout; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "rays",
            self.rays as f64,
            (1..=10_000).contains(&self.rays),
            "must be in 1..=10000",
        )?;
        check_fov(self.fov)?;
        check("range", self.range, self.range > 0.0, "must be > 0")?;
        Ok(())
    }

    /// Ray angles from straight ahead in radians (negative = left), left to right.
    pub fn angles(&self) -> Vec<f64> {
        spread(self.rays, self.fov).collect()
    }

    /// The compiled sensor the world reads.
    pub fn grid(&self) -> DistanceGrid {
        DistanceGrid::at_angles(&self.angles(), self.range)
    }
}

impl DistanceGrid {
    /// Rays at any `angles` (radians from straight ahead, negative = left, in
    /// reading order) reaching `range` px beyond the robot's rim: e.g. the
    /// maze robot's six rangefinders, one of them looking back.
    pub fn at_angles(angles: &[f64], range: f64) -> DistanceGrid {
        DistanceGrid {
            dirs: angles.iter().map(|&a| local(1.0, a)).collect(),
            range,
            places: angles
                .iter()
                .enumerate()
                .map(|(angle_index, &angle)| SensorPlace {
                    ring: 0,
                    angle_index,
                    distance: range,
                    angle,
                })
                .collect(),
        }
    }
}

/// Compiled distance-sensor layout.
#[derive(Clone, Debug, PartialEq)]
pub struct DistanceGrid {
    /// Unit directions in the robot frame (x ahead, y right).
    pub dirs: Vec<DVec2>,
    /// Ray length from the robot's rim, px.
    pub range: f64,
    places: Vec<SensorPlace>,
}

/// Reads `1 − d/range` for the nearest robot, obstacle, puck or wall along
/// each ray, `d` measured from the robot's rim; 0 when nothing is in range.
impl Sensor for DistanceGrid {
    fn name(&self) -> &'static str {
        "distance"
    }

    fn rings(&self) -> usize {
        1
    }

    fn places(&self) -> &[SensorPlace] {
        &self.places
    }

    fn read(&self, world: &World, i: usize, out: &mut [f64]) {
        let (p, ahead, right) = frame(world, i);
        let r0 = world.params.robot_radius;
        let max_t = self.range + r0;
        let sc = &world.statics.scenario;
        for (o, v) in self.dirs.iter().zip(out.iter_mut()) {
            let d = ahead * o.x + right * o.y;
            let mut t = max_t;
            // Walls: the arena boundary, seen from inside.
            if d.x > 1e-12 {
                t = t.min((sc.width() - p.x) / d.x);
            } else if d.x < -1e-12 {
                t = t.min(-p.x / d.x);
            }
            if d.y > 1e-12 {
                t = t.min((sc.height() - p.y) / d.y);
            } else if d.y < -1e-12 {
                t = t.min(-p.y / d.y);
            }
            for (j, other) in world.robots.iter().enumerate() {
                if j != i
                    && let Some(h) = ray_disc(p, d, other.pos, r0)
                {
                    t = t.min(h);
                }
            }
            for pk in &world.pucks {
                if let Some(h) = ray_disc(p, d, pk.pos, pk.radius) {
                    t = t.min(h);
                }
            }
            let end = p + d * t;
            let ray_box = Aabb {
                min: p.min(end),
                max: p.max(end),
            };
            for ob in &sc.fixed_obstacles {
                if ob.shape.bbox.intersects(&ray_box)
                    && let Some(h) = ob.shape.ray_hit(p, d, t)
                {
                    t = t.min(h);
                }
            }
            for (ob, m) in sc.movable_obstacles.iter().zip(&world.movables) {
                let b = Aabb {
                    min: ob.shape.bbox.min + m.offset,
                    max: ob.shape.bbox.max + m.offset,
                };
                if b.intersects(&ray_box)
                    && let Some(h) = ob.shape.ray_hit(p - m.offset, d, t)
                {
                    t = t.min(h);
                }
            }
            let dist = (t - r0).max(0.0);
            *v = if t < max_t {
                (1.0 - dist / self.range).clamp(0.0, 1.0)
            } else {
                0.0
            };
        }
    }
}

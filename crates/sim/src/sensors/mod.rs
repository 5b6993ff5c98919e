//! Sensors (DESIGN §6): what a robot perceives, one slice of readings per robot.
//!
//! Each sensor type lives in its own file: a serde layout for configs and a
//! compiled form that implements [`Sensor`]. A new sensor type is a new file
//! here plus one line in the `pub use` list below.

mod distance;
mod goal_radar;
mod opponent;
mod surface;
mod surface_f32;

use std::fmt;

use glam::DVec2;

use crate::world::World;

pub use distance::{DistanceGrid, DistanceSensors};
pub use goal_radar::GoalRadar;
pub use opponent::OpponentRadar;
pub use surface::{SurfaceGrid, SurfaceSensors};

/// A sensor every robot carries: a fixed number of readings, each from a
/// place on a polar sheet in front of the robot.
///
/// Reading is allocation-free and deterministic; the places tell a
/// HyperNEAT substrate where each reading's input node sits.
pub trait Sensor: fmt::Debug + Send + Sync {
    /// Short name of the sensor type, e.g. `"surface"`.
    fn name(&self) -> &'static str;

    /// Number of readings per robot.
    fn len(&self) -> usize {
        self.places().len()
    }

    /// Whether the sensor has no reading.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of rings the places are arranged in (≥ 1).
    fn rings(&self) -> usize;

    /// Where each reading is taken, in reading order (ring-major, left to right).
    fn places(&self) -> &[SensorPlace];

    /// Writes robot `robot`'s readings, each in [0, 1], to `out[..self.len()]`
    /// (entries beyond are left untouched).
    fn read(&self, world: &World, robot: usize, out: &mut [f64]);

    /// [`Sensor::read`] in single precision, for controllers that step in f32.
    ///
    /// The default reads in f64 into `scratch` (at least [`Sensor::len`]
    /// long, or it panics) and rounds each reading to the nearest f32; a sensor may
    /// instead compute in f32 throughout (the surface sensors do: 16 lanes
    /// per AVX-512 vector), which gives the same bits at every SIMD level
    /// but not always those of the rounded f64 read.
    fn read_f32(&self, world: &World, robot: usize, out: &mut [f32], scratch: &mut [f64]) {
        let wide = &mut scratch[..self.len()];
        self.read(world, robot, wide);
        for (o, &v) in out.iter_mut().zip(wide.iter()) {
            *o = v as f32;
        }
    }

    /// Every robot's [`Sensor::read`] at once: robot `r`'s readings (for `r`
    /// in `0..robots`) to `out[r · stride..][..self.len()]`, the same bits.
    ///
    /// Panics unless `stride ≥ self.len()` and `out` holds
    /// `(robots − 1) · stride + self.len()` values. The default reads robot
    /// after robot; a sensor may read them together (the surface sensors do:
    /// one call lets the CPU overlap one robot's look-ups with the next's).
    fn read_robots(&self, world: &World, robots: usize, out: &mut [f64], stride: usize) {
        let len = self.len();
        check_batch(len, robots, out.len(), stride);
        for r in 0..robots {
            self.read(world, r, &mut out[r * stride..][..len]);
        }
    }

    /// [`Sensor::read_robots`] in single precision: each robot's
    /// [`Sensor::read_f32`] (`scratch` as there), the same bits.
    fn read_robots_f32(
        &self,
        world: &World,
        robots: usize,
        out: &mut [f32],
        stride: usize,
        scratch: &mut [f64],
    ) {
        let len = self.len();
        check_batch(len, robots, out.len(), stride);
        for r in 0..robots {
            self.read_f32(world, r, &mut out[r * stride..][..len], scratch);
        }
    }
}

/// Checks a batched read's buffer (see [`Sensor::read_robots`]): panics,
/// naming the sizes, unless it holds every robot's `len` readings.
#[inline]
pub(crate) fn check_batch(len: usize, robots: usize, out: usize, stride: usize) {
    assert!(
        stride >= len
            && (robots == 0
                || (robots - 1)
                    .checked_mul(stride)
                    .and_then(|v| v.checked_add(len))
                    .is_some_and(|need| out >= need)),
        "a batched read of {robots} robots × {len} readings (stride {stride}) needs a longer buffer than {out}"
    );
}

/// Where one reading of a sensor is taken, relative to the robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorPlace {
    /// Ring index (0 = nearest).
    pub ring: usize,
    /// Angle index (0 = leftmost).
    pub angle_index: usize,
    /// Distance from the robot centre, px (for rays: their length from the rim).
    pub distance: f64,
    /// Angle from straight ahead in radians, negative = left.
    pub angle: f64,
}

/// `n` angles in radians spread evenly over `fov_deg` degrees centred ahead,
/// left (negative) to right; a single angle looks straight ahead.
///
/// The one formula for sensor and substrate angles, so that a substrate node
/// and the sensor it stands for agree to the bit.
pub fn spread(n: usize, fov_deg: f64) -> impl Iterator<Item = f64> {
    let fov = fov_deg.to_radians();
    (0..n).map(move |j| {
        if n == 1 {
            0.0
        } else {
            -fov / 2.0 + fov * j as f64 / (n - 1) as f64
        }
    })
}

/// Checks a field of view in degrees (shared by every sensor layout).
fn check_fov(fov: f64) -> Result<(), crate::physics::ParamError> {
    crate::physics::check(
        "fov",
        fov,
        (0.0..=360.0).contains(&fov),
        "must be in [0, 360] degrees",
    )
}

/// Robot-frame offset of a point at `distance` and relative `angle`:
/// x = ahead, y = to the right.
fn local(distance: f64, angle: f64) -> DVec2 {
    let (sin, cos) = libm::sincos(angle);
    DVec2::new(distance * cos, distance * sin)
}

/// Robot `i`'s position and its ahead and right unit vectors.
#[inline]
fn frame(world: &World, i: usize) -> (DVec2, DVec2, DVec2) {
    let r = &world.robots[i];
    (r.pos, r.dir, r.right())
}
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_layout_spreads_angles_and_rings_evenly() {
        let s = SurfaceSensors::default();
        s.validate().unwrap();
        let p = s.places();
        assert_eq!(p.len(), 15);
        assert!((p[0].angle + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(p[2].angle.abs() < 1e-12);
        assert_eq!(p[0].distance, 10.0);
        assert_eq!(p[5].distance, 30.0);
        assert_eq!(p[14].distance, 50.0);
    }

    #[test]
    fn single_sensor_looks_ahead_midway() {
        let s = SurfaceSensors {
            rings: 1,
            angles: 1,
            ..Default::default()
        };
        let g = s.grid();
        assert!((g.offsets[0] - DVec2::new(30.0, 0.0)).length() < 1e-12);
    }

    #[test]
    fn bad_layouts_are_rejected() {
        assert_eq!(
            SurfaceSensors {
                rings: 0,
                ..Default::default()
            }
            .validate()
            .unwrap_err()
            .field,
            "rings"
        );
        assert_eq!(
            SurfaceSensors {
                d_max: 5.0,
                ..Default::default()
            }
            .validate()
            .unwrap_err()
            .field,
            "d_max"
        );
        assert_eq!(
            DistanceSensors {
                range: 0.0,
                ..Default::default()
            }
            .validate()
            .unwrap_err()
            .field,
            "range"
        );
    }
}

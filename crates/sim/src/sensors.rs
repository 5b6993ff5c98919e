//! Sensor layouts (DESIGN §6). The layouts are serde structs for configs;
//! `grid()` precomputes the robot-frame offsets the hot loop uses.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::physics::{ParamError, check};

/// Angles spread evenly over `fov_deg` (0 = ahead, negative = left), in radians.
fn spread(n: usize, fov_deg: f64) -> impl Iterator<Item = f64> {
    let fov = fov_deg.to_radians();
    (0..n).map(move |j| {
        if n == 1 {
            0.0
        } else {
            -fov / 2.0 + fov * j as f64 / (n - 1) as f64
        }
    })
}

/// Robot-frame offset of a point at `distance` and relative `angle`:
/// x = ahead, y = to the right.
fn local(distance: f64, angle: f64) -> DVec2 {
    let (sin, cos) = libm::sincos(angle);
    DVec2::new(distance * cos, distance * sin)
}

/// Surface sensors on a polar grid in front of the robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SurfaceSensors {
    /// Rings (distances) of surface sensors: the rows of the input sheet.
    ///
    /// Paper: 3, re-sampled to 3.
    pub rings: usize,
    /// Surface sensors per ring, spread evenly over the field of view.
    ///
    /// Paper: 5, re-sampled to 6.
    pub angles: usize,
    /// Field of view of the surface sensors, centred ahead (180 = 90° to each side).
    ///
    /// Unit: degrees. Paper: 180.
    pub fov: f64,
    /// Distance of the nearest ring from the robot's centre.
    ///
    /// Unit: px.
    pub d_min: f64,
    /// Distance of the farthest ring from the robot's centre.
    ///
    /// Unit: px.
    pub d_max: f64,
}

impl Default for SurfaceSensors {
    fn default() -> Self {
        SurfaceSensors {
            rings: 3,
            angles: 5,
            fov: 180.0,
            d_min: 10.0,
            d_max: 50.0,
        }
    }
}

/// A sensor's place relative to the robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorPlace {
    /// Ring index (0 = nearest).
    pub ring: usize,
    /// Angle index (0 = leftmost).
    pub angle_index: usize,
    /// Distance from the robot centre, px.
    pub distance: f64,
    /// Angle from straight ahead in radians, negative = left.
    pub angle: f64,
}

impl SurfaceSensors {
    /// Checks the layout; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "rings",
            self.rings as f64,
            (1..=10_000).contains(&self.rings),
            "must be in 1..=10000",
        )?;
        check(
            "angles",
            self.angles as f64,
            (1..=10_000).contains(&self.angles),
            "must be in 1..=10000",
        )?;
        check(
            "fov",
            self.fov,
            (0.0..=360.0).contains(&self.fov),
            "must be in [0, 360] degrees",
        )?;
        check("d_min", self.d_min, self.d_min >= 0.0, "must be >= 0")?;
        check(
            "d_max",
            self.d_max,
            self.d_max >= self.d_min,
            "must be >= d_min",
        )?;
        Ok(())
    }

    /// Number of sensors (`rings × angles`).
    pub fn len(&self) -> usize {
        self.rings * self.angles
    }

    /// Whether the layout has no sensor.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every sensor's place, ring-major (index = ring·angles + angle_index).
    /// One ring sits midway between `d_min` and `d_max`.
    pub fn places(&self) -> Vec<SensorPlace> {
        let mut out = Vec::with_capacity(self.len());
        for ring in 0..self.rings {
            let distance = if self.rings == 1 {
                (self.d_min + self.d_max) / 2.0
            } else {
                self.d_min + (self.d_max - self.d_min) * ring as f64 / (self.rings - 1) as f64
            };
            for (angle_index, angle) in spread(self.angles, self.fov).enumerate() {
                out.push(SensorPlace {
                    ring,
                    angle_index,
                    distance,
                    angle,
                });
            }
        }
        out
    }

    /// Precomputed robot-frame offsets for [`crate::World::read_surface`].
    pub fn grid(&self) -> SurfaceGrid {
        SurfaceGrid {
            offsets: self
                .places()
                .iter()
                .map(|p| local(p.distance, p.angle))
                .collect(),
        }
    }
}

/// Compiled surface-sensor layout: robot-frame offsets (x ahead, y right).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceGrid {
    /// Offsets in sensor order.
    pub offsets: Vec<DVec2>,
}

impl SurfaceGrid {
    /// Number of sensors.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there is no sensor.
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }
}

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
        check(
            "fov",
            self.fov,
            (0.0..=360.0).contains(&self.fov),
            "must be in [0, 360] degrees",
        )?;
        check("range", self.range, self.range > 0.0, "must be > 0")?;
        Ok(())
    }

    /// Ray angles from straight ahead in radians (negative = left), left to right.
    pub fn angles(&self) -> Vec<f64> {
        spread(self.rays, self.fov).collect()
    }

    /// Precomputed robot-frame directions for [`crate::World::read_distance`].
    pub fn grid(&self) -> DistanceGrid {
        DistanceGrid {
            dirs: self.angles().into_iter().map(|a| local(1.0, a)).collect(),
            range: self.range,
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
}

impl DistanceGrid {
    /// Number of rays.
    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    /// Whether there is no ray.
    pub fn is_empty(&self) -> bool {
        self.dirs.is_empty()
    }
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

//! Surface sensors: the paper's polar grid of friction readings in front of
//! the robot (road 1 … grass 0, 0 outside the arena).

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::{Sensor, SensorPlace, check_fov, frame, local, spread};
use crate::physics::{ParamError, check};
use crate::world::World;

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
        check_fov(self.fov)?;
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

    /// The compiled sensor the world reads.
    pub fn grid(&self) -> SurfaceGrid {
        let places = self.places();
        SurfaceGrid {
            offsets: places.iter().map(|p| local(p.distance, p.angle)).collect(),
            places,
            rings: self.rings,
        }
    }
}

/// Compiled surface-sensor layout: robot-frame offsets (x ahead, y right).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceGrid {
    /// Offsets in sensor order.
    pub offsets: Vec<DVec2>,
    places: Vec<SensorPlace>,
    rings: usize,
}

impl SurfaceGrid {
    /// World positions of robot `i`'s sensors (for drawing).
    pub fn positions(&self, world: &World, i: usize) -> Vec<DVec2> {
        let (p, ahead, right) = frame(world, i);
        self.offsets
            .iter()
            .map(|o| p + ahead * o.x + right * o.y)
            .collect()
    }
}

impl Sensor for SurfaceGrid {
    fn name(&self) -> &'static str {
        "surface"
    }

    fn rings(&self) -> usize {
        self.rings
    }

    fn places(&self) -> &[SensorPlace] {
        &self.places
    }

    #[inline]
    fn read(&self, world: &World, i: usize, out: &mut [f64]) {
        let (p, ahead, right) = frame(world, i);
        let st = &*world.statics;
        // Hoisted out of the loop: the compiler cannot prove `out` does not alias them.
        let (ras, readings) = (st.scenario.raster(), &*st.readings);
        let inv = st.inv_cell;
        let lim = st.limit;
        let (base, ax, rx) = (p * inv, ahead * inv, right * inv);
        for (o, v) in self.offsets.iter().zip(out.iter_mut()) {
            let c = base + ax * o.x + rx * o.y;
            // Non-short-circuit tests compile to one branch.
            *v = if (c.x >= 0.0) & (c.y >= 0.0) & (c.x < lim.x) & (c.y < lim.y) {
                // i32 conversions are cheaper than usize ones; the range test keeps them exact.
                readings[ras.get_in_arena(c.x as i32 as usize, c.y as i32 as usize) as usize]
            } else {
                0.0
            };
        }
    }
}

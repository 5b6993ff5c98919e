//! A blinded sensor: the places of a sensor the robots carry, reading one
//! constant whatever the world holds. A replay with the distance rays
//! blinded (`vivae replay --blind-rays`) feeds their sheet the reading of
//! "nothing in range", so that what the rays do for a champion shows as the
//! difference from the replay that sees.

use std::sync::Arc;

use vivae_sim::{Sensor, SensorPlace, World};

use crate::controller::sensors::SensorSheet;

/// A sensor's layout (name, rings, places) reading `reading` everywhere.
#[derive(Debug, Clone, PartialEq)]
pub struct Blinded {
    name: &'static str,
    rings: usize,
    places: Vec<SensorPlace>,
    reading: f64,
}

impl Blinded {
    /// `sensor`'s layout, every reading `reading` (in [0, 1]).
    pub fn of(sensor: &dyn Sensor, reading: f64) -> Blinded {
        Blinded {
            name: sensor.name(),
            rings: sensor.rings(),
            places: sensor.places().to_vec(),
            reading,
        }
    }

    /// The constant every reading is.
    pub fn reading(&self) -> f64 {
        self.reading
    }
}

/// Reads the constant: the world is not looked at.
impl Sensor for Blinded {
    fn name(&self) -> &'static str {
        self.name
    }

    fn rings(&self) -> usize {
        self.rings
    }

    fn places(&self) -> &[SensorPlace] {
        &self.places
    }

    fn read(&self, _world: &World, _robot: usize, out: &mut [f64]) {
        out[..self.places.len()].fill(self.reading);
    }
}

/// What a distance ray reads with nothing in range (`vivae_sim::DistanceGrid`:
/// `1 − d/range` of the nearest thing, 0 when there is none).
pub const NOTHING_SEEN: f64 = 0.0;

impl SensorSheet {
    /// This sheet with its sensor blinded: every reading `reading`, the
    /// sheet's nodes, CPPN output and scale as they were.
    pub fn blinded(&self, reading: f64) -> SensorSheet {
        SensorSheet {
            sensor: Arc::new(Blinded::of(&*self.sensor, reading)),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_sim::DistanceSensors;

    #[test]
    fn a_blinded_sensor_keeps_the_layout_and_reads_its_constant() {
        let rays = DistanceSensors::default().grid();
        let b = Blinded::of(&rays, NOTHING_SEEN);
        assert_eq!(
            (b.name(), b.rings(), b.places()),
            ("distance", 1, rays.places())
        );
        let scenario =
            crate::tasks::scenarios::load_scenario(Some(std::path::Path::new("corridor")))
                .unwrap()
                .scenario;
        let world = World::new(&scenario, &Default::default()).unwrap();
        let mut seen = [9.0; 6];
        rays.read(&world, 0, &mut seen);
        // The corridor's kerbs are within reach of its first robot.
        assert!(seen[..5].iter().any(|&v| v > 0.0), "{seen:?}");
        let mut blind = [9.0; 6];
        b.read(&world, 0, &mut blind);
        assert_eq!(blind, [0.0, 0.0, 0.0, 0.0, 0.0, 9.0]);
    }
}

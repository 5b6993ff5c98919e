//! Fitness functions: what an episode's score is.
//!
//! A [`Fitness`] makes one [`FitnessMeter`] per episode; the meter may look
//! at the world after every step and gives the score at the end. The paper's
//! fitness, [`AverageSpeed`], is the default of every experiment; another one
//! is a new file with a type implementing [`Fitness`], handed to
//! [`Episode::with_fitness`](crate::tasks::driving::episode::Episode::with_fitness).
//!
//! ```
//! use std::sync::Arc;
//! use vivae_lab::tasks::driving::fitness::{Fitness, FitnessMeter};
//! use vivae_sim::World;
//!
//! /// Average speed, minus one px/step for each robot-step spent off the road.
//! #[derive(Debug)]
//! struct StayOnRoad;
//!
//! struct Meter { off_road: u64 }
//!
//! impl FitnessMeter for Meter {
//!     fn observe(&mut self, world: &World) {
//!         self.off_road += (0..world.robots().len()).filter(|&i| !world.on_road(i)).count() as u64;
//!     }
//!     fn score(&self, world: &World, robot_steps: f64) -> f64 {
//!         let odometer: f64 = world.robots().iter().map(|r| r.odometer).sum();
//!         (odometer - self.off_road as f64) / robot_steps
//!     }
//! }
//!
//! impl Fitness for StayOnRoad {
//!     fn name(&self) -> &str { "stay_on_road" }
//!     fn meter(&self, _: &World) -> Box<dyn FitnessMeter> { Box::new(Meter { off_road: 0 }) }
//! }
//!
//! let config = vivae_lab::config::Config::default();
//! let scenario = vivae_lab::tasks::scenarios::load_scenario(None)?.scenario;
//! let plain = vivae_lab::tasks::driving::episode::Episode::new(&config, &scenario)?;
//! let strict = plain.clone().with_fitness(Arc::new(StayOnRoad));
//! let population = vivae_neat::Population::new(config.neat.clone(), plain.cppn_spec(), 1)?;
//! let genome = &population.genomes()[0];
//! assert!(strict.fitness(genome) <= plain.fitness(genome));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt;

use vivae_sim::World;

/// A fitness function over episodes (higher is better).
pub trait Fitness: Send + Sync + fmt::Debug {
    /// Short name (for configs and tables).
    fn name(&self) -> &str;

    /// Whether the meter looks at the world after every step (if not, the
    /// rollout skips the call).
    fn observes_steps(&self) -> bool {
        true
    }

    /// A fresh meter for one episode starting in `world`.
    fn meter(&self, world: &World) -> Box<dyn FitnessMeter>;
}

/// Measures one episode.
pub trait FitnessMeter {
    /// Looks at the world after a step.
    fn observe(&mut self, _world: &World) {}

    /// The episode's score, given the final world and the robot-steps simulated.
    fn score(&self, world: &World, robot_steps: f64) -> f64;
}

/// The paper's fitness: average speed, Σ odometer / (robots × steps), in px per step.
#[derive(Debug, Clone, Copy, Default)]
pub struct AverageSpeed;

impl FitnessMeter for AverageSpeed {
    fn score(&self, world: &World, robot_steps: f64) -> f64 {
        let odometer: f64 = world.robots().iter().map(|r| r.odometer).sum();
        odometer / robot_steps
    }
}

impl Fitness for AverageSpeed {
    fn name(&self) -> &str {
        "average_speed"
    }

    fn observes_steps(&self) -> bool {
        false
    }

    fn meter(&self, _: &World) -> Box<dyn FitnessMeter> {
        // A zero-sized meter: boxing it allocates nothing.
        Box::new(AverageSpeed)
    }
}

//! The driving episode as the substrate seam shows it
//! ([`crate::tasks::substrate::SubstrateEpisode`]): what export,
//! `drive-image`, a recorded episode and the road pack read of it.

use vivae_neat::Genome;
use vivae_sim::{DVec2, Scenario, World};

use crate::config::Config;
use crate::controller::es::RobotController;
use crate::controller::sensors::SensorSheet;
use crate::controller::substrate::WheelNeurons;
use crate::error::{EpisodeError, Result};
use crate::io::bad_input;
use crate::tasks::driving::episode::Episode;
use crate::tasks::driving::rollout::Drive;
use crate::tasks::substrate::{Recording, Replayed, SubstrateEpisode};

/// The driving episode of `config` on `scenario` (the driving entry's
/// [`crate::tasks::TaskEntry::substrate_episode`]).
pub fn episode(
    config: &Config,
    scenario: &Scenario,
) -> std::result::Result<Box<dyn SubstrateEpisode>, EpisodeError> {
    Ok(Box::new(Episode::new(config, scenario)?))
}

impl SubstrateEpisode for Episode {
    fn robot_controller(
        &self,
        genome: &Genome,
    ) -> std::result::Result<RobotController, EpisodeError> {
        Episode::robot_controller(self, genome)
    }

    fn sensors(&self) -> &[SensorSheet] {
        Episode::sensors(self)
    }

    fn surface_offsets(&self) -> &[DVec2] {
        &self.surface_grid().offsets
    }

    fn wheels(&self) -> WheelNeurons {
        Episode::wheels(self)
    }

    fn world(&self) -> &World {
        Episode::world(self)
    }

    fn robots(&self) -> usize {
        Episode::robots(self)
    }

    fn steps(&self) -> u32 {
        Episode::steps(self)
    }

    fn fitness(&self, genome: &Genome) -> f64 {
        Episode::fitness(self, genome)
    }

    fn replay(&self, controller: &RobotController) -> Replayed {
        let record = self.run(controller, true);
        Replayed {
            fitness: record.fitness,
            on_road: record.on_road,
            turns: (record.behaviour.as_ref()).map(|b| (b.left_turns, b.right_turns)),
        }
    }

    fn record(&self, controller: &RobotController, robot: usize, steps: u32) -> Result<Recording> {
        if robot >= self.robots() {
            return Err(bad_input(format!(
                "robot {robot}: the episode has {} robots",
                self.robots()
            )));
        }
        let ni = controller.num_inputs();
        let mut world = Episode::world(self).clone();
        let mut rollout = self.rollout(controller);
        let mut rec = Recording {
            inputs: ni,
            sensors: Vec::with_capacity(steps as usize * ni),
            wheels: Vec::with_capacity(steps as usize),
            poses: Vec::with_capacity(steps as usize),
        };
        for _ in 0..steps {
            // The pose the rollout reads the sensors at, at the start of its step.
            let r = &world.robots()[robot];
            rec.poses.push((r.pos, r.heading));
            rollout.step(&mut world, controller, None);
            rollout.extend_inputs(robot, &mut rec.sensors);
            rec.wheels.push(rollout.controls(robot));
        }
        Ok(rec)
    }
}

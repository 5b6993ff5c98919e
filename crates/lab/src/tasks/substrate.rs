//! What a task whose controller is a robot's substrate network (decoded
//! from a CPPN genome) offers the code that takes that controller out of a
//! run: its episode on one map at one resolution ([`SubstrateEpisode`]),
//! built by the entry's [`super::TaskEntry::substrate_episode`]. Export,
//! `drive-image`, the recorded episode and the road pack reach the task
//! only through it.

use std::fmt;

use vivae_neat::Genome;
use vivae_sim::{DVec2, Scenario, World};

use crate::config::Config;
use crate::controller::es::RobotController;
use crate::controller::sensors::SensorSheet;
use crate::controller::substrate::WheelNeurons;
use crate::error::{EpisodeError, Result};

/// Builds a task's [`SubstrateEpisode`] of `config` on `scenario` (its
/// first map, at the config's resolution).
pub type SubstrateEpisodeOf =
    fn(&Config, &Scenario) -> std::result::Result<Box<dyn SubstrateEpisode>, EpisodeError>;

/// One episode setup of robots driven by a substrate network: what its
/// robots read, which neurons drive their wheels, the world they start in,
/// and the episode run with a given controller.
pub trait SubstrateEpisode: fmt::Debug + Send + Sync {
    /// Decodes `genome` into this episode's controller; an error says why it does not fit.
    fn robot_controller(
        &self,
        genome: &Genome,
    ) -> std::result::Result<RobotController, EpisodeError>;

    /// The robots' sensors with their input sheets, in controller-input order.
    fn sensors(&self) -> &[SensorSheet];

    /// The surface sensors' robot-frame offsets (x ahead, y right), scenario px, in input order.
    fn surface_offsets(&self) -> &[DVec2];

    /// The wheel neurons of a dense (polar) controller's sheet.
    fn wheels(&self) -> WheelNeurons;

    /// The world at the start of an episode.
    fn world(&self) -> &World;

    /// Number of robots.
    fn robots(&self) -> usize;

    /// Simulation steps per episode.
    fn steps(&self) -> u32;

    /// The fitness of `genome`'s controller; 0 for a genome that does not fit.
    fn fitness(&self, genome: &Genome) -> f64;

    /// One episode driven by `controller`, summed up.
    fn replay(&self, controller: &RobotController) -> Replayed;

    /// Runs `steps` steps driven by `controller` (every robot, as evolution
    /// does) and records robot `robot`.
    fn record(&self, controller: &RobotController, robot: usize, steps: u32) -> Result<Recording>;
}

/// A boxed episode is one (as `std`'s `Read` is for a boxed reader): a
/// [`crate::export::choose::Chosen`]'s episode passes as `&chosen.episode`.
impl<T: SubstrateEpisode + ?Sized> SubstrateEpisode for Box<T> {
    fn robot_controller(
        &self,
        genome: &Genome,
    ) -> std::result::Result<RobotController, EpisodeError> {
        (**self).robot_controller(genome)
    }

    fn sensors(&self) -> &[SensorSheet] {
        (**self).sensors()
    }

    fn surface_offsets(&self) -> &[DVec2] {
        (**self).surface_offsets()
    }

    fn wheels(&self) -> WheelNeurons {
        (**self).wheels()
    }

    fn world(&self) -> &World {
        (**self).world()
    }

    fn robots(&self) -> usize {
        (**self).robots()
    }

    fn steps(&self) -> u32 {
        (**self).steps()
    }

    fn fitness(&self, genome: &Genome) -> f64 {
        (**self).fitness(genome)
    }

    fn replay(&self, controller: &RobotController) -> Replayed {
        (**self).replay(controller)
    }

    fn record(&self, controller: &RobotController, robot: usize, steps: u32) -> Result<Recording> {
        (**self).record(controller, robot, steps)
    }
}

/// An episode summed up: its fitness, and what its robots did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Replayed {
    /// The episode's fitness.
    pub fitness: f64,
    /// Fraction of robot-steps on road, when the task measures it.
    pub on_road: Option<f64>,
    /// Completed left and right turns, all robots, when the task counts them.
    pub turns: Option<(u32, u32)>,
}

/// One robot's episode as vivae ran it: what it read and did at every step.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// Inputs per step.
    pub inputs: usize,
    /// The controller's inputs, step after step (`steps × inputs`).
    pub sensors: Vec<f64>,
    /// The wheel commands of every step.
    pub wheels: Vec<[f64; 2]>,
    /// The robot's pose when it read its sensors: position and heading.
    pub poses: Vec<(DVec2, f64)>,
}

/// The substrate episode of `config` on `scenario`, by its task's entry;
/// refused (naming the tasks that have one) for a task without.
pub fn substrate_episode(
    config: &Config,
    scenario: &Scenario,
) -> Result<Box<dyn SubstrateEpisode>> {
    let entry = super::entry_of(config).map_err(|e| crate::io::bad_input(e.to_string()))?;
    let build = entry.substrate_episode.ok_or_else(|| {
        crate::io::bad_input(format!(
            "{} run has no substrate network to decode: runs of {} have one",
            crate::error::a(entry.name),
            super::names_with(|t| t.substrate_episode.is_some())
        ))
    })?;
    Ok(build(config, scenario)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::TaskName;
    use crate::tasks::scenarios::load_scenario;

    #[test]
    fn a_task_declares_its_episode_exactly_when_its_controller_is_a_substrate() {
        for t in crate::tasks::entries() {
            assert_eq!(t.substrate, t.substrate_episode.is_some(), "{}", t.name);
        }
    }

    #[test]
    fn a_task_without_a_substrate_episode_is_refused_by_name() {
        let scenario = load_scenario(None).unwrap().scenario;
        let cartpole = crate::tasks::default_config(Some(&TaskName("cartpole".into()))).unwrap();
        let e = substrate_episode(&cartpole, &scenario)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a cartpole run") && e.contains("runs of driving have one"),
            "{e}"
        );
        let driving = substrate_episode(&Config::default(), &scenario).unwrap();
        assert_eq!(driving.robots(), Config::default().experiment.robots);
        assert_eq!(driving.steps(), Config::default().experiment.steps);
    }

    #[test]
    fn only_a_driving_task_is_a_driving_training() {
        let driving = Config::default();
        let maps = crate::tasks::maps::load(&driving).unwrap();
        let task = crate::tasks::build(&driving, &maps).unwrap();
        assert!(crate::tasks::driving::training_of(task.as_ref()).is_some());
        let cartpole = crate::tasks::default_config(Some(&TaskName("cartpole".into()))).unwrap();
        let task = crate::tasks::build(&cartpole, &[]).unwrap();
        assert!(crate::tasks::driving::training_of(task.as_ref()).is_none());
    }
}

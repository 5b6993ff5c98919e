//! The controller's side of a rollout: what drives every robot of an episode
//! with one set of weights ([`Drive`]) and the robots' neuron states
//! ([`RobotStates`]), for the dense polar sheet and ES networks alike.

use vivae_neat::Network;
use vivae_neat::Precision;
use vivae_neat::hyperneat::{BatchState, SubstrateController};

use crate::controller::substrate::WheelNeurons;

/// A controller that drives every robot of an episode with one set of
/// weights and one state per robot: the dense polar sheet
/// ([`SubstrateController`]) or an ES network
/// ([`EsController`](crate::controller::es::EsController)).
pub trait Drive {
    /// Inputs per robot.
    fn num_inputs(&self) -> usize;
    /// Outputs per robot.
    fn num_outputs(&self) -> usize;
    /// Zero states for `robots` robots.
    fn robot_states(&self, robots: usize) -> RobotStates;
    /// One update of every robot: `inputs` and `outputs` hold the robots one
    /// after the other. A controller whose states hold its outputs (the
    /// dense sheet's, [`RobotStates::Polar`]) may leave `outputs` as it is:
    /// [`RobotStates::outputs`] reads a robot's from wherever they are.
    /// Allocation-free.
    fn step_robots(&self, states: &mut RobotStates, inputs: &[f64], outputs: &mut [f64]);
    /// Whether the controller steps in single precision and takes its
    /// inputs as f32 ([`Drive::step_robots_single`]): the fast precision.
    fn single_inputs(&self) -> bool {
        false
    }
    /// [`Drive::step_robots`] with f32 inputs, which the rollout reads when
    /// [`Drive::single_inputs`] holds. The default widens them into `wide`
    /// (as long as `inputs`) and steps on that. Allocation-free.
    fn step_robots_single(
        &self,
        states: &mut RobotStates,
        inputs: &[f32],
        wide: &mut [f64],
        outputs: &mut [f64],
    ) {
        for (w, &v) in wide.iter_mut().zip(inputs) {
            *w = f64::from(v);
        }
        self.step_robots(states, &wide[..inputs.len()], outputs);
    }
    /// Which outputs drive the wheels when they are not the substrate's wheel neurons.
    fn wheel_outputs(&self) -> Option<WheelNeurons> {
        None
    }
}

/// Every robot's neuron states, of the kind of controller that made them.
#[derive(Debug, Clone)]
pub enum RobotStates {
    /// The dense sheet's batched state.
    Polar(BatchState),
    /// An ES network's node values and scratch, robot after robot.
    Es {
        /// Node values.
        values: Vec<f64>,
        /// Scratch of the synchronous update.
        next: Vec<f64>,
    },
}

impl RobotStates {
    /// Robot `robot`'s outputs after a step: the dense sheet's from its
    /// states, another controller's from `outputs` (the buffer
    /// [`Drive::step_robots`] wrote, `per_robot` values a robot).
    pub fn outputs<'a>(&'a self, outputs: &'a [f64], per_robot: usize, robot: usize) -> &'a [f64] {
        match self {
            RobotStates::Polar(states) => states.state(robot),
            RobotStates::Es { .. } => &outputs[robot * per_robot..][..per_robot],
        }
    }

    /// The dense sheet's batched state (panics for another kind: the
    /// controller that steps them made them, in [`Rollout::new`]).
    fn polar(&mut self) -> &mut BatchState {
        let RobotStates::Polar(states) = self else {
            panic!("a polar controller steps polar states (Rollout::new built them)");
        };
        states
    }
}

impl Drive for SubstrateController {
    fn num_inputs(&self) -> usize {
        Network::num_inputs(self)
    }

    fn num_outputs(&self) -> usize {
        Network::num_outputs(self)
    }

    fn robot_states(&self, robots: usize) -> RobotStates {
        RobotStates::Polar(self.batch_state(robots))
    }

    /// Leaves `outputs` as it is: the states hold the new neuron values
    /// (copying them out was 1.7 % of the default run).
    fn step_robots(&self, states: &mut RobotStates, inputs: &[f64], _outputs: &mut [f64]) {
        self.step_batch(states.polar(), inputs);
    }

    fn single_inputs(&self) -> bool {
        self.precision() == Precision::Fast
    }

    fn step_robots_single(
        &self,
        states: &mut RobotStates,
        inputs: &[f32],
        _wide: &mut [f64],
        _outputs: &mut [f64],
    ) {
        self.step_batch_single(states.polar(), inputs);
    }
}

//! The one rollout loop: sensors → controller → wheels → `World::step`, for
//! every robot of an episode. Evolution, replay, the viewer and the Python
//! environments all step robots through it.

use vivae_neat::Network;
use vivae_neat::hyperneat::{BatchState, SubstrateController};
use vivae_sim::World;

use crate::sensors::{SensorSheet, read_sheets};
use crate::substrate::WheelNeurons;

/// The controller side of an episode in progress: every robot's neuron
/// states and the buffers between sensors, controller and wheels. The world
/// is the caller's, handed to [`Rollout::step`].
///
/// The robots share the controller's weights: one batched update per step
/// reads each weight once for all robots, and gives each robot exactly the
/// bits its own copy of the controller would. Stepping never allocates.
#[derive(Debug, Clone)]
pub struct Rollout {
    sensors: Vec<SensorSheet>,
    wheels: WheelNeurons,
    states: BatchState,
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    controls: Vec<[f64; 2]>,
    steps: u64,
}

impl Rollout {
    /// The start of an episode of `robots` robots carrying `sensors` (in
    /// controller-input order) and driven by `controller` through `wheels`
    /// (see [`Experiment::rollout`](crate::experiment::Experiment::rollout)).
    pub fn new(
        robots: usize,
        sensors: Vec<SensorSheet>,
        wheels: WheelNeurons,
        controller: &SubstrateController,
    ) -> Rollout {
        let n = robots;
        Rollout {
            sensors,
            wheels,
            states: controller.batch_state(n),
            inputs: vec![0.0; n * controller.num_inputs()],
            outputs: vec![0.0; n * controller.num_outputs()],
            controls: vec![[0.0; 2]; n],
            steps: 0,
        }
    }

    /// One step: every robot reads its sensors, the controller updates, the
    /// wheel neurons drive, the world moves. `manual` replaces one robot's
    /// wheel commands (its controller still updates, so letting go resumes it).
    pub fn step(
        &mut self,
        world: &mut World,
        controller: &SubstrateController,
        manual: Option<(usize, [f64; 2])>,
    ) {
        let (ni, nn) = (controller.num_inputs(), controller.num_outputs());
        if ni > 0 {
            for (i, inputs) in self.inputs.chunks_exact_mut(ni).enumerate() {
                read_sheets(&self.sensors, world, i, inputs);
            }
        }
        controller.activate_batch(&mut self.states, &self.inputs, &mut self.outputs);
        let wheels = self.wheels;
        for (c, out) in self.controls.iter_mut().zip(self.outputs.chunks_exact(nn)) {
            *c = [out[wheels.left], out[wheels.right]];
        }
        if let Some((robot, wheels)) = manual
            && let Some(c) = self.controls.get_mut(robot)
        {
            *c = wheels;
        }
        world.step(&self.controls);
        self.steps += 1;
    }

    /// Back to the start: every neuron state and output zero (the world is the caller's to reset).
    pub fn reset(&mut self, controller: &SubstrateController) {
        self.states = controller.batch_state(self.controls.len());
        self.outputs.fill(0.0);
        self.controls.fill([0.0; 2]);
        self.steps = 0;
    }

    /// Robot `robot`'s neuron activations after the last step.
    pub fn outputs(&self, robot: usize) -> &[f64] {
        let nn = self.outputs.len() / self.controls.len().max(1);
        &self.outputs[robot * nn..][..nn]
    }

    /// Robot `robot`'s wheel commands in the last step.
    pub fn controls(&self, robot: usize) -> [f64; 2] {
        self.controls[robot]
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

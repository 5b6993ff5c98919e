//! The one rollout loop: sensors → controller → wheels → `World::step`, for
//! every robot of an episode. Evolution, replay, the viewer and the Python
//! environments all step robots through it.

use vivae_sim::World;

use crate::controller::sensors::{SensorSheet, read_sheets_all, read_sheets_single_all};
use crate::controller::substrate::WheelNeurons;

// The controller side sits below the tasks, which ES-HyperNEAT's controller must not import.
pub use crate::controller::drive::{Drive, RobotStates};

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
    states: RobotStates,
    inputs: Vec<f64>,
    /// The inputs in f32 when the controller takes them so (fast
    /// precision; `inputs` is then the f64 sensors' scratch); else empty.
    single: Vec<f32>,
    /// The outputs of a controller whose states do not hold them (see
    /// [`RobotStates::outputs`]); empty for the dense sheet's.
    outputs: Vec<f64>,
    controls: Vec<[f64; 2]>,
    steps: u64,
}

impl Rollout {
    /// The start of an episode of `robots` robots carrying `sensors` (in
    /// controller-input order) and driven by `controller` through `wheels`
    /// (see [`Episode::rollout`](crate::tasks::driving::episode::Episode::rollout)).
    pub fn new(
        robots: usize,
        sensors: Vec<SensorSheet>,
        wheels: WheelNeurons,
        controller: &(impl Drive + ?Sized),
    ) -> Rollout {
        let n = robots;
        let states = controller.robot_states(n);
        Rollout {
            sensors,
            wheels: controller.wheel_outputs().unwrap_or(wheels),
            outputs: match states {
                RobotStates::Polar(_) => Vec::new(),
                RobotStates::Es { .. } => vec![0.0; n * controller.num_outputs()],
            },
            states,
            inputs: vec![0.0; n * controller.num_inputs()],
            single: if controller.single_inputs() {
                vec![0.0; n * controller.num_inputs()]
            } else {
                Vec::new()
            },
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
        controller: &(impl Drive + ?Sized),
        manual: Option<(usize, [f64; 2])>,
    ) {
        let ni = controller.num_inputs();
        let robots = self.controls.len();
        if controller.single_inputs() && self.single.len() == self.inputs.len() {
            if ni > 0 {
                read_sheets_single_all(
                    &self.sensors,
                    world,
                    robots,
                    &mut self.single,
                    &mut self.inputs,
                );
            }
            controller.step_robots_single(
                &mut self.states,
                &self.single,
                &mut self.inputs,
                &mut self.outputs,
            );
        } else {
            if ni > 0 {
                read_sheets_all(&self.sensors, world, robots, &mut self.inputs);
            }
            controller.step_robots(&mut self.states, &self.inputs, &mut self.outputs);
        }
        let (left, right) = (self.wheels.left, self.wheels.right);
        // One match a step, not one a robot.
        match &self.states {
            RobotStates::Polar(states) => {
                for (r, c) in self.controls.iter_mut().enumerate() {
                    let out = states.state(r);
                    *c = [out[left], out[right]];
                }
            }
            RobotStates::Es { .. } => {
                let outputs = self.outputs.chunks_exact(self.per_robot());
                for (c, out) in self.controls.iter_mut().zip(outputs) {
                    *c = [out[left], out[right]];
                }
            }
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
    pub fn reset(&mut self, controller: &(impl Drive + ?Sized)) {
        self.states = controller.robot_states(self.controls.len());
        self.outputs.fill(0.0);
        self.controls.fill([0.0; 2]);
        self.steps = 0;
    }

    /// Robot `robot`'s neuron activations after the last step.
    pub fn outputs(&self, robot: usize) -> &[f64] {
        self.states.outputs(&self.outputs, self.per_robot(), robot)
    }

    /// Outputs per robot in `outputs` (0 for the dense sheet, whose states hold them).
    fn per_robot(&self) -> usize {
        self.outputs.len() / self.controls.len().max(1)
    }

    /// Robot `robot`'s every node value after the last step (inputs, the two
    /// wheel neurons, then the hidden neurons) when an ES network drives;
    /// `None` for the dense sheet, whose neurons are [`Rollout::outputs`].
    pub fn node_values(&self, robot: usize) -> Option<&[f64]> {
        match &self.states {
            RobotStates::Es { values, .. } => {
                let n = values.len() / self.controls.len().max(1);
                values.get(robot * n..(robot + 1) * n)
            }
            RobotStates::Polar(_) => None,
        }
    }

    /// Appends robot `robot`'s controller inputs of the last step to `out`,
    /// as the controller took them (a fast controller's f32 readings
    /// widened, exactly).
    pub fn extend_inputs(&self, robot: usize, out: &mut Vec<f64>) {
        let ni = self.inputs.len() / self.controls.len().max(1);
        if self.single.is_empty() {
            out.extend_from_slice(&self.inputs[robot * ni..][..ni]);
        } else {
            out.extend(
                self.single[robot * ni..][..ni]
                    .iter()
                    .map(|&v| f64::from(v)),
            );
        }
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

//! What drives one side of the game: a plain NEAT network of the 11 inputs,
//! or (`[coevolution] hunter`/`prey = "hyperneat"`) a CPPN decoded onto a
//! substrate, as the driving task decodes its controllers
//! (`vivae_neat::hyperneat::decode_genome`).
//!
//! The substrate's input nodes sit where the sensors look, in the driving
//! substrate's CPPN coordinates (x to the right, y ahead): the opponent
//! radar's four slices on the unit circle at their centre angles (left,
//! ahead, right, behind; CPPN output 4, as the driving task's opponent
//! sheet) and the six rangefinders on it at theirs (output 3, as the
//! driving task's distance rays); the bias input is left out (each neuron
//! has its own bias, output 1). The neurons are the driving task's 3×3
//! polar sheet over 180°, fully recurrent (output 2); its left and right
//! wheel neurons (ρ = 2/3, the outermost angles) drive the wheels: their
//! states in [−1, 1] are the wheel speeds, given to the game as the turn
//! and forward in [0, 1] that [`crate::tasks::robot::wheels`] turns back
//! into those speeds. The weights are not normalised.

use vivae_neat::hyperneat::{HyperParams, SubstrateController, SubstrateLayout, decode_genome};
use vivae_neat::{Genome, GenomeSpec, Network, RecurrentNetwork};
use vivae_sim::{DistanceGrid, OpponentRadar, Sensor};

use crate::controller::polar::{
    CoordMode, DISTANCE_OUTPUT, OPPONENT_OUTPUT, PolarGrid, WheelNeurons,
};
use crate::controller::sensors::SensorSheet;
use crate::controller::substrate::{cppn_outputs, layout_of};
use crate::tasks::predator_prey::section::SideController;
use crate::tasks::predator_prey::{INPUTS, OUTPUTS};
use crate::tasks::robot;

/// Sensor inputs of the substrate: the radar's and the rangefinders' (no bias).
const SENSED: usize = INPUTS - 1;

/// The substrate both sides' HyperNEAT controllers are decoded onto.
#[derive(Debug, Clone, PartialEq)]
pub struct Substrate {
    layout: SubstrateLayout,
    wheels: WheelNeurons,
    cppn_outputs: usize,
}

impl Substrate {
    /// The substrate of the arena's `radar` and `rays`.
    pub fn new(radar: &OpponentRadar, rays: &DistanceGrid) -> Substrate {
        let sheet = |sensor: std::sync::Arc<dyn Sensor>, cppn_output: usize| SensorSheet {
            reference_len: sensor.len(),
            sensor,
            cppn_output,
            label: "",
        };
        let sheets = [
            sheet(std::sync::Arc::new(radar.clone()), OPPONENT_OUTPUT),
            sheet(std::sync::Arc::new(rays.clone()), DISTANCE_OUTPUT),
        ];
        let grid = PolarGrid {
            rings: 3,
            angles: 3,
        };
        let wheels = (grid.wheel_neurons()).unwrap_or(WheelNeurons { left: 3, right: 5 });
        Substrate {
            layout: layout_of(&sheets, &grid.nodes(180.0), CoordMode::Cartesian),
            wheels,
            cppn_outputs: cppn_outputs(&sheets),
        }
    }

    /// The decoder's layout.
    pub fn layout(&self) -> &SubstrateLayout {
        &self.layout
    }

    /// The genome layout of a side of kind `kind`: the plain NEAT network's
    /// ([`robot::spec`]) or a CPPN with this substrate's outputs.
    pub fn spec(&self, kind: SideController) -> GenomeSpec {
        match kind {
            SideController::Neat => robot::spec(),
            SideController::Hyperneat => GenomeSpec {
                outputs: self.cppn_outputs,
                ..GenomeSpec::cppn()
            },
        }
    }
}

/// One side's controller for one episode.
pub enum Brain {
    /// A plain NEAT network of the 11 inputs.
    Neat(RecurrentNetwork),
    /// A decoded substrate; its neuron states.
    Hyper(SubstrateController, WheelNeurons, [f64; 9]),
    /// A genome that does not decode (not of this substrate's CPPNs): stands still.
    Idle,
}

impl Brain {
    /// The controller of `genome`, a side of kind `kind`.
    pub fn new(
        kind: SideController,
        genome: &Genome,
        substrate: &Substrate,
        params: &HyperParams,
    ) -> Brain {
        match kind {
            SideController::Neat => Brain::Neat(RecurrentNetwork::from_genome(genome)),
            SideController::Hyperneat => match decode_genome(genome, &substrate.layout, params) {
                Ok(c) if c.num_neurons() == 9 => Brain::Hyper(c, substrate.wheels, [0.0; 9]),
                _ => Brain::Idle,
            },
        }
    }

    /// The outputs (turn, forward in [0, 1]) for `inputs`. Allocation-free.
    pub fn act(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        match self {
            Brain::Neat(net) => net.activate(inputs, outputs),
            Brain::Hyper(c, w, state) => {
                c.activate(&inputs[..SENSED], state);
                let (left, right) = (state[w.left], state[w.right]);
                // wheels(turn, forward) = [2f − 1 + 2t − 1, 2f − 1 − (2t − 1)] = [left, right].
                outputs[0] = ((left - right) / 2.0 + 1.0) / 2.0;
                outputs[1] = ((left + right) / 2.0 + 1.0) / 2.0;
            }
            Brain::Idle => outputs[..OUTPUTS].fill(0.5),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::predator_prey::RADAR_SLICES;
    use crate::tasks::robot::{RANGE, wheels};

    fn substrate() -> Substrate {
        let radar = OpponentRadar::new(RADAR_SLICES, 400.0).unwrap();
        let rays = DistanceGrid::at_angles(&robot::rangefinder_angles(), RANGE);
        Substrate::new(&radar, &rays)
    }

    #[test]
    fn the_substrate_puts_each_sensor_where_it_looks() {
        let s = substrate();
        let l = s.layout();
        let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() + (a[1] - b[1]).abs() < 1e-12;
        // Radar slices: left, ahead, right, behind (x right, y ahead).
        let radar = &l.inputs[0];
        assert_eq!(radar.cppn_output, OPPONENT_OUTPUT);
        for (c, want) in radar
            .coords
            .iter()
            .zip([[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0], [0.0, -1.0]])
        {
            assert!(close(*c, want), "{c:?} {want:?}");
        }
        // Rangefinders: left, 45° left, ahead, 45° right, right, behind.
        let rays = &l.inputs[1];
        assert_eq!((rays.cppn_output, rays.coords.len()), (DISTANCE_OUTPUT, 6));
        assert!(close(rays.coords[0], [-1.0, 0.0]) && close(rays.coords[2], [0.0, 1.0]));
        assert!(close(rays.coords[5], [0.0, -1.0]));
        assert_eq!((l.num_inputs(), l.neurons.len()), (SENSED, 9));
        assert_eq!(s.spec(SideController::Hyperneat).outputs, 5);
        assert_eq!(s.spec(SideController::Neat), robot::spec());
    }

    #[test]
    fn a_decoded_cppn_drives_its_wheel_neurons() {
        let s = substrate();
        let spec = s.spec(SideController::Hyperneat);
        let first = |spec: GenomeSpec| {
            let pop = vivae_neat::Population::new(vivae_neat::NeatParams::default(), spec, 3);
            pop.unwrap().genomes()[0].clone()
        };
        let genome = first(spec);
        let hyper = HyperParams::default();
        let mut brain = Brain::new(SideController::Hyperneat, &genome, &s, &hyper);
        let Brain::Hyper(c, w, _) = &brain else {
            panic!("not decoded")
        };
        let (mut copy, w) = (c.clone(), *w);
        let inputs = [0.3; INPUTS];
        let mut out = [0.0; OUTPUTS];
        brain.act(&inputs, &mut out);
        let mut state = [0.0; 9];
        copy.activate(&inputs[..SENSED], &mut state);
        let [l, r] = wheels(out[0], out[1]);
        assert!((l - state[w.left]).abs() < 1e-12 && (r - state[w.right]).abs() < 1e-12);
        assert!(out.iter().all(|o| (0.0..=1.0).contains(o)), "{out:?}");
        // A plain NEAT genome is no CPPN of this substrate: it stands still.
        let neat = first(robot::spec());
        let mut idle = Brain::new(SideController::Hyperneat, &neat, &s, &hyper);
        idle.act(&inputs, &mut out);
        assert_eq!(out, [0.5, 0.5]);
    }
}

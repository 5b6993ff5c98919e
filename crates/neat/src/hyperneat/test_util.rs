//! Helpers shared by the hyperneat unit tests.

use super::layout::{InputSheet, SubstrateLayout};
use crate::genome::Genome;
use crate::network::Network;

/// A hand-written CPPN: a closure from the 5 inputs to `N` outputs.
pub(crate) struct FnCppn<F, const N: usize>(pub(crate) F);

impl<F: FnMut(&[f64]) -> [f64; N], const N: usize> Network for FnCppn<F, N> {
    fn num_inputs(&self) -> usize {
        5
    }
    fn num_outputs(&self) -> usize {
        N
    }
    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        assert_eq!(inputs[4], 1.0, "bias input must be 1");
        outputs.copy_from_slice(&(self.0)(inputs));
    }
    fn reset(&mut self) {}
}

pub(crate) fn layout(inputs: Vec<[f64; 2]>, neurons: Vec<[f64; 2]>) -> SubstrateLayout {
    SubstrateLayout {
        inputs: vec![InputSheet {
            coords: inputs,
            cppn_output: 0,
        }],
        neurons,
        bias_output: 1,
        recurrent_output: 2,
    }
}

pub(crate) fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

/// A CPPN whose weights are a known function of the coordinates.
pub(crate) fn known(q: &[f64]) -> [f64; 3] {
    let (x1, y1, x2, y2) = (q[0], q[1], q[2], q[3]);
    [
        (x1 - x2).tanh(),
        0.5 * y1,
        (-((x1 - x2).powi(2) + (y1 - y2).powi(2))).exp() * (x1 - 0.5).signum(),
    ]
}

/// Random CPPN genomes grown by the NEAT mutations.
pub(crate) fn random_genomes(count: usize, seed: u64) -> Vec<Genome> {
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use crate::mutation::{
        mutate_activation, mutate_add_link, mutate_add_node, mutate_toggle_enable,
    };
    use crate::params::NeatParams;
    use rand::SeedableRng;
    let spec = GenomeSpec::cppn();
    let params = NeatParams::default();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    (0..count)
        .map(|i| {
            let mut tracker = InnovationTracker::new(8);
            let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
            for _ in 0..(i % 7) * 3 {
                mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
                mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
                mutate_activation(&mut g, &spec, &mut rng);
                mutate_toggle_enable(&mut g, &mut rng);
            }
            g
        })
        .collect()
}

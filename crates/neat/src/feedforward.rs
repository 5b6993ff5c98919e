//! The acyclic phenotype (the CPPN): flat arrays in topological order, one pass.

use crate::compile::{Plan, assert_io};
use crate::genome::Genome;
use crate::network::Network;

/// An acyclic network evaluated in one pass; no allocation per activation.
///
/// Only nodes from which an output can be reached are kept. Should the genome
/// contain a cycle (a recurrent genome), the links closing it are dropped.
/// The plan (node order, links and their sum order) is the crate's one
/// compiled-CPPN ordering, shared with the batched substrate decoder.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedForwardNetwork {
    /// Inputs first, then computed nodes in evaluation order, with their links.
    plan: Plan,
    /// One value per slot of the plan.
    values: Vec<f64>,
}

impl FeedForwardNetwork {
    /// Compiles a genome's enabled links into an evaluation plan.
    pub fn from_genome(genome: &Genome) -> FeedForwardNetwork {
        let plan = Plan::compile(genome);
        let values = vec![0.0; plan.slots()];
        FeedForwardNetwork { plan, values }
    }

    /// Makes this network the network of `genome`, reusing its memory: the
    /// same network as [`FeedForwardNetwork::from_genome`], without allocating
    /// once the arrays are large enough (for evaluating many genomes in turn).
    pub fn recompile(&mut self, genome: &Genome) {
        self.plan.recompile(genome);
        self.values.clear();
        self.values.resize(self.plan.slots(), 0.0);
    }

    /// Feeds `L` input vectors at once and writes the `L` output vectors:
    /// `inputs[i][lane]` is input `i` of vector `lane`, `outputs[o][lane]`
    /// receives output `o`. Gives exactly the bits of `L` calls of
    /// [`Network::activate`] (each lane adds the same terms in the same
    /// order); computing the lanes in lockstep lets their activation
    /// functions, long chains of dependent operations, overlap. `values` is
    /// the caller's scratch (resized as needed, so nothing is allocated once
    /// it is large enough).
    pub fn activate_lanes<const L: usize>(
        &self,
        inputs: &[[f64; L]],
        outputs: &mut [[f64; L]],
        values: &mut Vec<[f64; L]>,
    ) {
        let plan = &self.plan;
        assert_io(
            inputs.len(),
            outputs.len(),
            plan.num_inputs,
            plan.output_slots.len(),
        );
        values.clear();
        values.extend_from_slice(inputs);
        for (k, &act) in plan.acts.iter().enumerate() {
            let (sources, weights) = plan.links(k);
            let mut sum = [0.0; L];
            for (&src, &w) in sources.iter().zip(weights) {
                let v = &values[src as usize];
                for lane in 0..L {
                    sum[lane] += v[lane] * w;
                }
            }
            values.push(sum.map(|x| act.apply(x)));
            debug_assert_eq!(values.len(), plan.num_inputs + k + 1);
        }
        for (o, &s) in outputs.iter_mut().zip(&plan.output_slots) {
            *o = values[s as usize];
        }
    }

    /// Number of computed (hidden and output) nodes actually evaluated.
    pub fn num_computed(&self) -> usize {
        self.plan.acts.len()
    }

    /// Number of links actually evaluated.
    pub fn num_links(&self) -> usize {
        self.plan.conn_src.len()
    }
}

impl Network for FeedForwardNetwork {
    fn num_inputs(&self) -> usize {
        self.plan.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.plan.output_slots.len()
    }

    #[inline]
    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        self.plan.activate(inputs, outputs, &mut self.values, None);
    }

    fn reset(&mut self) {}
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::activation::Activation;
    use crate::test_genes::genome;

    #[test]
    fn computes_hand_made_network() {
        use Activation::*;
        // out(2) = bsig(0.5*x0 + 2*h), h(4) = gauss(x1 - x0), dead(5) feeds nothing.
        let g = genome(
            "0 input linear, 1 input linear, 2 output bipolar_sigmoid, 4 hidden gaussian, \
             5 hidden sine",
            "0: 0 -> 2 0.5, 1: 1 -> 2 9.0 off, 2: 1 -> 4 1.0, 3: 4 -> 2 2.0, 4: 0 -> 4 -1.0, \
             5: 0 -> 5 1.0",
        );
        let mut net = FeedForwardNetwork::from_genome(&g);
        assert_eq!(net.num_computed(), 2, "the dead-end node is pruned");
        let mut out = [0.0];
        for (x0, x1) in [(0.3, -0.7), (1.0, 1.0), (-2.0, 0.5)] {
            net.activate(&[x0, x1], &mut out);
            let h = Gaussian.apply(x1 - x0);
            let want = BipolarSigmoid.apply(0.5 * x0 + 2.0 * h);
            assert!((out[0] - want).abs() < 1e-15);
        }
    }

    #[test]
    fn cycles_do_not_hang_or_panic() {
        let g = genome(
            "0 input linear, 1 output linear, 2 hidden linear",
            "0: 0 -> 2 1.0, 1: 2 -> 1 1.0, 2: 1 -> 2 1.0, 3: 1 -> 1 1.0",
        );
        let mut net = FeedForwardNetwork::from_genome(&g);
        let mut out = [0.0];
        net.activate(&[2.0], &mut out);
        let first = out[0];
        net.activate(&[2.0], &mut out);
        assert_eq!(out[0], first, "stateless");
    }

    #[test]
    fn recompile_equals_a_fresh_network() {
        use crate::genome::GenomeSpec;
        use crate::innovation::InnovationTracker;
        use crate::mutation::{mutate_add_link, mutate_add_node};
        use crate::params::NeatParams;
        use rand::SeedableRng;
        let spec = GenomeSpec::cppn();
        let params = NeatParams::default();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let mut tracker = InnovationTracker::new(8);
        let mut genomes = vec![Genome::minimal(&spec, &params, &mut tracker, &mut rng)];
        for _ in 0..12 {
            let mut g = genomes.last().unwrap().clone();
            mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
            mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
            genomes.push(g);
        }
        // Large after small and small after large, with values left over.
        genomes.push(genomes[0].clone());
        let mut net = FeedForwardNetwork::from_genome(genomes.last().unwrap());
        let mut out = [0.0; 3];
        for g in &genomes {
            net.activate(&[0.1, 0.2, 0.3, 0.4, 1.0], &mut out);
            net.recompile(g);
            assert_eq!(net, FeedForwardNetwork::from_genome(g));
        }
    }

    #[test]
    fn lanes_give_the_bits_of_single_activations() {
        use crate::genome::GenomeSpec;
        use crate::innovation::InnovationTracker;
        use crate::mutation::{mutate_activation, mutate_add_link, mutate_add_node};
        use crate::params::NeatParams;
        use rand::{RngExt, SeedableRng};
        let spec = GenomeSpec::cppn();
        let params = NeatParams::default();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(8);
        let mut tracker = InnovationTracker::new(8);
        let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
        let mut scratch = Vec::new();
        for _ in 0..30 {
            mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
            mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
            mutate_activation(&mut g, &spec, &mut rng);
            let mut net = FeedForwardNetwork::from_genome(&g);
            let mut inputs = [[0.0; 4]; 5];
            for x in inputs.iter_mut().flatten() {
                *x = rng.random::<f64>() * 6.0 - 3.0;
            }
            let mut lanes = [[0.0; 4]; 3];
            net.activate_lanes(&inputs, &mut lanes, &mut scratch);
            for lane in 0..4 {
                let single: Vec<f64> = inputs.iter().map(|i| i[lane]).collect();
                let mut out = [0.0; 3];
                net.activate(&single, &mut out);
                for o in 0..3 {
                    assert_eq!(lanes[o][lane].to_bits(), out[o].to_bits());
                }
            }
        }
    }
}

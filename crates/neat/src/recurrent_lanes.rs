//! Recurrent networks of several genomes stepped together (TensorNEAT's
//! idea on CPU lanes): one step of all of them computes every node's sum,
//! then all their activation functions at once, as vector lanes.

use crate::activation::{Activation, apply_all};
use crate::genome::Genome;
use crate::network::Network;
use crate::recurrent::RecurrentNetwork;

/// The recurrent networks of up to [`RecurrentLanes::capacity`] genomes,
/// each stepped exactly as its own [`RecurrentNetwork`] (the same bits), all
/// in one pass per step.
///
/// A network of one or two nodes spends most of a step in one `exp`, a chain
/// of dependent operations; side by side, the `exp`s of several genomes'
/// networks share vector instructions. For tasks that step every network
/// the same number of times (or mask the ones that are done).
#[derive(Debug, Clone)]
pub struct RecurrentLanes {
    /// One network per lane used so far; the first `used` hold the current genomes.
    nets: Vec<RecurrentNetwork>,
    /// The most lanes.
    capacity: usize,
    /// Lanes in use.
    used: usize,
    /// The activation of every computed node of every used lane, lane after lane.
    acts: Vec<Activation>,
    /// Scratch: every computed node's sum, then its value, in `acts`' order.
    sums: Vec<f64>,
}

impl RecurrentLanes {
    /// Room for `capacity` genomes' networks (at least one).
    pub fn new(capacity: usize) -> RecurrentLanes {
        RecurrentLanes {
            nets: Vec::new(),
            capacity: capacity.max(1),
            used: 0,
            acts: Vec::new(),
            sums: Vec::new(),
        }
    }

    /// The most genomes one pass holds.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Genomes held now.
    pub fn lanes(&self) -> usize {
        self.used
    }

    /// Makes lane `l` the network of `genomes[l]`, states cleared, reusing
    /// memory (panics with more genomes than [`RecurrentLanes::capacity`]).
    pub fn recompile<'g>(&mut self, genomes: impl IntoIterator<Item = &'g Genome>) {
        self.used = 0;
        self.acts.clear();
        for g in genomes {
            assert!(self.used < self.capacity, "more genomes than lanes");
            if let Some(net) = self.nets.get_mut(self.used) {
                net.recompile(g);
            } else {
                self.nets.push(RecurrentNetwork::from_genome(g));
            }
            self.acts.extend_from_slice(&self.nets[self.used].plan.acts);
            self.used += 1;
        }
        self.sums.clear();
        self.sums.resize(self.acts.len(), 0.0);
    }

    /// The network in lane `l`.
    pub fn lane(&self, l: usize) -> &RecurrentNetwork {
        &self.nets[..self.used][l]
    }

    /// Clears the state of lane `l` (as [`Network::reset`] on its network).
    pub fn reset_lane(&mut self, l: usize) {
        self.nets[..self.used][l].reset();
    }

    /// Clears every lane's state.
    pub fn reset(&mut self) {
        for net in &mut self.nets[..self.used] {
            net.reset();
        }
    }

    /// One step of every lane: lane `l` reads `inputs[l]` and writes
    /// `outputs[l]`, exactly as its network's [`Network::activate`] would.
    pub fn activate(&mut self, inputs: &[&[f64]], outputs: &mut [&mut [f64]]) {
        assert!(
            inputs.len() == self.used && outputs.len() == self.used,
            "one input and one output slice per lane"
        );
        let mut at = 0;
        let lanes = self.nets[..self.used].iter_mut().zip(inputs);
        for ((net, input), output) in lanes.zip(outputs.iter()) {
            let computed = net.plan.acts.len();
            let sums = &mut self.sums[at..at + computed];
            net.plan
                .recurrent_sums(input, output.len(), &mut net.state, sums);
            at += computed;
        }
        apply_all(&self.acts, &mut self.sums);
        let mut at = 0;
        for (net, output) in self.nets[..self.used].iter_mut().zip(outputs) {
            let computed = net.plan.acts.len();
            let sums = &self.sums[at..at + computed];
            net.plan.recurrent_finish(&mut net.state, sums, output);
            at += computed;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use crate::params::NeatParams;
    use crate::test_genes::grown;
    use rand::{RngExt, SeedableRng};

    #[test]
    fn lanes_step_each_genome_as_its_own_network() {
        let spec = GenomeSpec {
            allow_recurrent: true,
            ..GenomeSpec::plain(3, 2)
        };
        let params = NeatParams::plain_neat();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut tracker = InnovationTracker::new(5);
        let mut lanes = RecurrentLanes::new(6);
        for round in 0..30 {
            let genomes: Vec<Genome> = (0..1 + round % 6)
                .map(|i| grown(&spec, &params, &mut tracker, &mut rng, (round + i) % 7))
                .collect();
            lanes.recompile(&genomes);
            let mut alone: Vec<RecurrentNetwork> =
                genomes.iter().map(RecurrentNetwork::from_genome).collect();
            for step in 0..12 {
                let inputs: Vec<[f64; 3]> = (0..genomes.len())
                    .map(|_| std::array::from_fn(|_| rng.random::<f64>() * 4.0 - 2.0))
                    .collect();
                let mut outs = vec![[0.0; 2]; genomes.len()];
                let ins: Vec<&[f64]> = inputs.iter().map(|i| &i[..]).collect();
                let mut out_refs: Vec<&mut [f64]> = outs.iter_mut().map(|o| &mut o[..]).collect();
                lanes.activate(&ins, &mut out_refs);
                for (l, net) in alone.iter_mut().enumerate() {
                    let mut want = [0.0; 2];
                    net.activate(&inputs[l], &mut want);
                    assert_eq!(
                        outs[l].map(f64::to_bits),
                        want.map(f64::to_bits),
                        "round {round} step {step} lane {l}"
                    );
                }
                if step == 5 {
                    // One lane restarts alone.
                    lanes.reset_lane(0);
                    alone[0].reset();
                }
            }
        }
    }
}

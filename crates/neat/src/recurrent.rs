//! The recurrent phenotype: synchronous update, state kept between calls.

use std::collections::BTreeMap;

use crate::activation::Activation;
use crate::compile::{assert_io, ids_of, links_of, weighted_sum};
use crate::genome::{Genome, NodeKind};
use crate::network::Network;

/// A recurrent network: every call sets the inputs, then every non-input node
/// computes `act(Σ w·state)` from the previous state at once (synchronous update).
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrentNetwork {
    num_inputs: usize,
    /// Current value of every slot (inputs first, then the other nodes by id).
    state: Vec<f64>,
    /// Scratch for the synchronous update of the non-input slots.
    next: Vec<f64>,
    acts: Vec<Activation>,
    conn_start: Vec<u32>,
    conn_src: Vec<u32>,
    conn_weight: Vec<f64>,
    output_slots: Vec<u32>,
}

impl RecurrentNetwork {
    /// Compiles a genome's enabled links (any topology) into a recurrent network.
    pub fn from_genome(genome: &Genome) -> RecurrentNetwork {
        let inputs = ids_of(genome, NodeKind::Input);
        let outputs = ids_of(genome, NodeKind::Output);
        let others: Vec<u32> = genome
            .nodes()
            .iter()
            .filter(|n| n.kind != NodeKind::Input)
            .map(|n| n.id)
            .collect();
        let mut slot = BTreeMap::new();
        for (k, &id) in inputs.iter().chain(&others).enumerate() {
            slot.insert(id, k as u32);
        }
        let mut acts = Vec::with_capacity(others.len());
        let mut conn_start = vec![0u32];
        let mut conn_src = Vec::new();
        let mut conn_weight = Vec::new();
        for &id in &others {
            acts.push(genome.node(id).map_or(Activation::Linear, |n| n.activation));
            for l in genome.links().iter().filter(|l| l.enabled && l.to == id) {
                if let Some(&s) = slot.get(&l.from) {
                    conn_src.push(s);
                    conn_weight.push(l.weight);
                }
            }
            conn_start.push(conn_src.len() as u32);
        }
        RecurrentNetwork {
            num_inputs: inputs.len(),
            state: vec![0.0; inputs.len() + others.len()],
            next: vec![0.0; others.len()],
            acts,
            conn_start,
            conn_src,
            conn_weight,
            output_slots: outputs.iter().map(|o| slot[o]).collect(),
        }
    }
}

impl Network for RecurrentNetwork {
    fn num_inputs(&self) -> usize {
        self.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.output_slots.len()
    }

    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        assert_io(
            inputs.len(),
            outputs.len(),
            self.num_inputs,
            self.output_slots.len(),
        );
        let n_in = self.num_inputs;
        self.state[..n_in].copy_from_slice(inputs);
        for (k, &act) in self.acts.iter().enumerate() {
            let (sources, weights) =
                links_of(&self.conn_start, &self.conn_src, &self.conn_weight, k);
            self.next[k] = act.apply(weighted_sum(sources, weights, &self.state));
        }
        self.state[n_in..].copy_from_slice(&self.next);
        for (o, &s) in outputs.iter_mut().zip(&self.output_slots) {
            *o = self.state[s as usize];
        }
    }

    fn reset(&mut self) {
        self.state.fill(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::{LinkGene, NodeGene};

    #[test]
    fn self_loop_integrates_and_reset_clears() {
        // out = linear(1·x + 1·out_prev): a running sum.
        let g = Genome::from_parts(
            vec![
                NodeGene {
                    id: 0,
                    kind: NodeKind::Input,
                    activation: Activation::Linear,
                },
                NodeGene {
                    id: 1,
                    kind: NodeKind::Output,
                    activation: Activation::Linear,
                },
            ],
            vec![
                LinkGene {
                    innovation: 0,
                    from: 0,
                    to: 1,
                    weight: 1.0,
                    enabled: true,
                },
                LinkGene {
                    innovation: 1,
                    from: 1,
                    to: 1,
                    weight: 1.0,
                    enabled: true,
                },
            ],
        )
        .unwrap();
        let mut net = RecurrentNetwork::from_genome(&g);
        let mut out = [0.0];
        for want in [1.0, 2.0, 3.0] {
            net.activate(&[1.0], &mut out);
            assert_eq!(out[0], want);
        }
        net.reset();
        net.activate(&[1.0], &mut out);
        assert_eq!(out[0], 1.0);
    }
}

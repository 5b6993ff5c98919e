//! The recurrent phenotype: synchronous update, state kept between calls.

use std::collections::BTreeMap;

use crate::activation::Activation;
use crate::compile::{Plan, ids_of};
use crate::genome::{Genome, NodeKind};
use crate::network::Network;

/// A recurrent network: every call sets the inputs, then every non-input node
/// computes `act(Σ w·state)` from the previous state at once (synchronous update).
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrentNetwork {
    /// Inputs first, then the other nodes by id, with all their links.
    plan: Plan,
    /// Current value of every slot.
    state: Vec<f64>,
    /// Scratch for the synchronous update of the non-input slots.
    next: Vec<f64>,
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
        let plan = Plan {
            num_inputs: inputs.len(),
            acts,
            conn_start,
            conn_src,
            conn_weight,
            output_slots: outputs.iter().map(|o| slot[o]).collect(),
            // Nothing is dropped: every link reads the previous state.
            cyclic: false,
        };
        RecurrentNetwork {
            state: vec![0.0; plan.slots()],
            next: vec![0.0; others.len()],
            plan,
        }
    }
}

impl Network for RecurrentNetwork {
    fn num_inputs(&self) -> usize {
        self.plan.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.plan.output_slots.len()
    }

    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let next = Some(&mut self.next[..]);
        self.plan.activate(inputs, outputs, &mut self.state, next);
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

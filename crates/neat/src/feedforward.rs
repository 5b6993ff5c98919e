//! The acyclic phenotype (the CPPN): flat arrays in topological order, one pass.

use std::collections::BTreeMap;

use crate::activation::Activation;
use crate::genome::{Genome, NodeKind};
use crate::network::Network;

/// An acyclic network evaluated in one pass; no allocation per activation.
///
/// Only nodes from which an output can be reached are kept. Should the genome
/// contain a cycle (a recurrent genome), the links closing it are dropped.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedForwardNetwork {
    num_inputs: usize,
    /// One value per slot: inputs first, then computed nodes in evaluation order.
    values: Vec<f64>,
    /// Activation of computed node k (slot `num_inputs + k`).
    acts: Vec<Activation>,
    /// Incoming links of computed node k are `conn_start[k]..conn_start[k + 1]`.
    conn_start: Vec<u32>,
    conn_src: Vec<u32>,
    conn_weight: Vec<f64>,
    /// Slot of each output, in output order.
    output_slots: Vec<u32>,
}

impl FeedForwardNetwork {
    /// Compiles a genome's enabled links into an evaluation plan.
    pub fn from_genome(genome: &Genome) -> FeedForwardNetwork {
        let inputs: Vec<u32> = ids_of(genome, NodeKind::Input);
        let outputs: Vec<u32> = ids_of(genome, NodeKind::Output);
        let enabled: Vec<_> = genome.links().iter().filter(|l| l.enabled).collect();

        // Nodes that can reach an output (reverse search over enabled links).
        let mut needed: BTreeMap<u32, bool> = BTreeMap::new();
        let mut stack: Vec<u32> = outputs.clone();
        for &o in &outputs {
            needed.insert(o, true);
        }
        while let Some(n) = stack.pop() {
            for l in enabled.iter().filter(|l| l.to == n) {
                if needed.insert(l.from, true).is_none() {
                    stack.push(l.from);
                }
            }
        }

        // Kahn's algorithm over needed non-input nodes, smallest id first.
        let is_input = |id: u32| inputs.binary_search(&id).is_ok();
        let mut indegree: BTreeMap<u32, usize> = needed
            .keys()
            .filter(|&&id| !is_input(id))
            .map(|&id| (id, 0))
            .collect();
        for l in &enabled {
            if !is_input(l.from)
                && needed.contains_key(&l.from)
                && let Some(d) = indegree.get_mut(&l.to)
            {
                *d += 1;
            }
        }
        let mut order = Vec::with_capacity(indegree.len());
        let mut ready: std::collections::BTreeSet<u32> = indegree
            .iter()
            .filter(|(_, d)| **d == 0)
            .map(|(&id, _)| id)
            .collect();
        let mut done = std::collections::BTreeSet::new();
        loop {
            let next = match ready.pop_first() {
                Some(n) => n,
                // A cycle: take the smallest remaining node; its back-links are dropped.
                None => match indegree.keys().find(|id| !done.contains(*id)) {
                    Some(&n) => n,
                    None => break,
                },
            };
            done.insert(next);
            order.push(next);
            for l in enabled.iter().filter(|l| l.from == next) {
                if done.contains(&l.to) {
                    continue;
                }
                if let Some(d) = indegree.get_mut(&l.to) {
                    *d -= 1;
                    if *d == 0 {
                        ready.insert(l.to);
                    }
                }
            }
        }

        let mut slot: BTreeMap<u32, u32> = BTreeMap::new();
        for (k, &id) in inputs.iter().enumerate() {
            slot.insert(id, k as u32);
        }
        for (k, &id) in order.iter().enumerate() {
            slot.insert(id, (inputs.len() + k) as u32);
        }
        let mut acts = Vec::with_capacity(order.len());
        let mut conn_start = Vec::with_capacity(order.len() + 1);
        let mut conn_src = Vec::new();
        let mut conn_weight = Vec::new();
        conn_start.push(0);
        for (k, &id) in order.iter().enumerate() {
            let my_slot = (inputs.len() + k) as u32;
            acts.push(genome.node(id).map_or(Activation::Linear, |n| n.activation));
            for l in enabled.iter().filter(|l| l.to == id) {
                // Only sources evaluated earlier; anything else would close a cycle.
                if let Some(&s) = slot.get(&l.from)
                    && s < my_slot
                {
                    conn_src.push(s);
                    conn_weight.push(l.weight);
                }
            }
            conn_start.push(conn_src.len() as u32);
        }
        let output_slots = outputs.iter().map(|o| slot[o]).collect();
        FeedForwardNetwork {
            num_inputs: inputs.len(),
            values: vec![0.0; inputs.len() + order.len()],
            acts,
            conn_start,
            conn_src,
            conn_weight,
            output_slots,
        }
    }

    /// Number of computed (hidden and output) nodes actually evaluated.
    pub fn num_computed(&self) -> usize {
        self.acts.len()
    }

    /// Number of links actually evaluated.
    pub fn num_links(&self) -> usize {
        self.conn_src.len()
    }
}

pub(crate) fn ids_of(genome: &Genome, kind: NodeKind) -> Vec<u32> {
    genome
        .nodes()
        .iter()
        .filter(|n| n.kind == kind)
        .map(|n| n.id)
        .collect()
}

impl Network for FeedForwardNetwork {
    fn num_inputs(&self) -> usize {
        self.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.output_slots.len()
    }

    #[inline]
    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        assert_eq!(inputs.len(), self.num_inputs, "wrong number of inputs");
        assert_eq!(
            outputs.len(),
            self.output_slots.len(),
            "wrong number of outputs"
        );
        let n_in = self.num_inputs;
        self.values[..n_in].copy_from_slice(inputs);
        for (k, &act) in self.acts.iter().enumerate() {
            let (s, e) = (self.conn_start[k] as usize, self.conn_start[k + 1] as usize);
            let mut sum = 0.0;
            for (&src, &w) in self.conn_src[s..e].iter().zip(&self.conn_weight[s..e]) {
                sum += self.values[src as usize] * w;
            }
            self.values[n_in + k] = act.apply(sum);
        }
        for (o, &s) in outputs.iter_mut().zip(&self.output_slots) {
            *o = self.values[s as usize];
        }
    }

    fn reset(&mut self) {}
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::{LinkGene, NodeGene};

    fn node(id: u32, kind: NodeKind, activation: Activation) -> NodeGene {
        NodeGene {
            id,
            kind,
            activation,
        }
    }

    fn link(innovation: u32, from: u32, to: u32, weight: f64, enabled: bool) -> LinkGene {
        LinkGene {
            innovation,
            from,
            to,
            weight,
            enabled,
        }
    }

    #[test]
    fn computes_hand_made_network() {
        use Activation::*;
        use NodeKind::*;
        // out(2) = bsig(0.5*x0 + 2*h), h(4) = gauss(x1 - x0), dead(5) feeds nothing.
        let g = Genome::from_parts(
            vec![
                node(0, Input, Linear),
                node(1, Input, Linear),
                node(2, Output, BipolarSigmoid),
                node(4, Hidden, Gaussian),
                node(5, Hidden, Sine),
            ],
            vec![
                link(0, 0, 2, 0.5, true),
                link(1, 1, 2, 9.0, false),
                link(2, 1, 4, 1.0, true),
                link(3, 4, 2, 2.0, true),
                link(4, 0, 4, -1.0, true),
                link(5, 0, 5, 1.0, true),
            ],
        )
        .unwrap();
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
        use Activation::*;
        use NodeKind::*;
        let g = Genome::from_parts(
            vec![
                node(0, Input, Linear),
                node(1, Output, Linear),
                node(2, Hidden, Linear),
            ],
            vec![
                link(0, 0, 2, 1.0, true),
                link(1, 2, 1, 1.0, true),
                link(2, 1, 2, 1.0, true),
                link(3, 1, 1, 1.0, true),
            ],
        )
        .unwrap();
        let mut net = FeedForwardNetwork::from_genome(&g);
        let mut out = [0.0];
        net.activate(&[2.0], &mut out);
        let first = out[0];
        net.activate(&[2.0], &mut out);
        assert_eq!(out[0], first, "stateless");
    }
}

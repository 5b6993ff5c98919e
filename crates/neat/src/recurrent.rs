//! The recurrent phenotype: synchronous update, state kept between calls.

use crate::compile::Plan;
use crate::genome::{Genome, NodeKind};
use crate::network::Network;

/// A recurrent network: every call sets the inputs, then every non-input node
/// computes `act(Σ w·state)` from the previous state at once (synchronous update).
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrentNetwork {
    /// Inputs first, then the other nodes by id, with all their links.
    pub(crate) plan: Plan,
    /// Current value of every slot.
    pub(crate) state: Vec<f64>,
    /// Scratch for the synchronous update of the non-input slots.
    next: Vec<f64>,
    /// Scratch of a compile: each node's slot, in node-id order.
    slots: Vec<u32>,
}

impl RecurrentNetwork {
    /// Compiles a genome's enabled links (any topology) into a recurrent network.
    pub fn from_genome(genome: &Genome) -> RecurrentNetwork {
        let mut net = RecurrentNetwork::empty();
        net.recompile(genome);
        net
    }

    /// A network of no nodes, to [`recompile`](Self::recompile) genomes into.
    pub(crate) fn empty() -> RecurrentNetwork {
        RecurrentNetwork {
            plan: Plan::default(),
            state: Vec::new(),
            next: Vec::new(),
            slots: Vec::new(),
        }
    }

    /// Makes this network the network of `genome`, state cleared, reusing
    /// its memory: the same network as [`RecurrentNetwork::from_genome`],
    /// without allocating once the arrays are large enough (for evaluating
    /// many genomes in turn).
    pub fn recompile(&mut self, genome: &Genome) {
        let nodes = genome.nodes();
        let n_in = nodes.iter().filter(|n| n.kind == NodeKind::Input).count();
        // Slots: inputs first, then the other nodes, each group by id (the
        // genome's node order).
        self.slots.clear();
        let (mut next_in, mut next_other) = (0u32, n_in as u32);
        for n in nodes {
            let counter = if n.kind == NodeKind::Input {
                &mut next_in
            } else {
                &mut next_other
            };
            self.slots.push(*counter);
            *counter += 1;
        }
        let slot_of = |id: u32| {
            let i = nodes.binary_search_by_key(&id, |n| n.id).ok()?;
            Some(self.slots[i])
        };
        let plan = &mut self.plan;
        plan.num_inputs = n_in;
        plan.acts.clear();
        let others = nodes.iter().filter(|n| n.kind != NodeKind::Input);
        plan.acts.extend(others.map(|n| n.activation));
        // Each node's incoming links in innovation order (a counting sort by
        // target: the order `from_genome` has always summed them in).
        let computed = plan.acts.len();
        plan.conn_start.clear();
        plan.conn_start.resize(computed + 1, 0);
        let incoming = |l: &&crate::genome::LinkGene| l.enabled;
        let target = |l: &crate::genome::LinkGene| {
            let from = slot_of(l.from)?;
            let to = slot_of(l.to)?.checked_sub(n_in as u32)?;
            Some((from, to as usize))
        };
        for (_, to) in genome.links().iter().filter(incoming).filter_map(target) {
            plan.conn_start[to + 1] += 1;
        }
        for k in 0..computed {
            plan.conn_start[k + 1] += plan.conn_start[k];
        }
        let total = plan.conn_start[computed] as usize;
        plan.conn_src.clear();
        plan.conn_src.resize(total, 0);
        plan.conn_weight.clear();
        plan.conn_weight.resize(total, 0.0);
        // `conn_start[to]` serves as target `to`'s cursor while its links are
        // placed, ending at the start of `to + 1`; shifting by one restores it.
        for l in genome.links().iter().filter(incoming) {
            if let Some((from, to)) = target(l) {
                let at = plan.conn_start[to] as usize;
                plan.conn_src[at] = from;
                plan.conn_weight[at] = l.weight;
                plan.conn_start[to] += 1;
            }
        }
        plan.conn_start.copy_within(0..computed, 1);
        plan.conn_start[0] = 0;
        plan.output_slots.clear();
        let outputs = nodes.iter().filter(|n| n.kind == NodeKind::Output);
        plan.output_slots
            .extend(outputs.filter_map(|n| slot_of(n.id)));
        // Nothing is dropped: every link reads the previous state.
        plan.cyclic = false;
        self.state.clear();
        self.state.resize(plan.slots(), 0.0);
        self.next.clear();
        self.next.resize(computed, 0.0);
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
    use std::collections::BTreeMap;

    use super::*;
    use crate::activation::Activation;
    use crate::compile::ids_of;
    use crate::genome::{GenomeSpec, LinkGene, NodeGene};
    use crate::innovation::InnovationTracker;
    use crate::params::NeatParams;
    use crate::test_genes::grown;
    use rand::SeedableRng;

    /// The map-based compiler this network started with: the definition
    /// `recompile` must reproduce exactly.
    fn plan_reference(genome: &Genome) -> Plan {
        let inputs = ids_of(genome, NodeKind::Input);
        let outputs = ids_of(genome, NodeKind::Output);
        let others: Vec<u32> = (genome.nodes().iter())
            .filter(|n| n.kind != NodeKind::Input)
            .map(|n| n.id)
            .collect();
        let mut slot = BTreeMap::new();
        for (k, &id) in inputs.iter().chain(&others).enumerate() {
            slot.insert(id, k as u32);
        }
        let mut plan = Plan {
            num_inputs: inputs.len(),
            conn_start: vec![0],
            ..Plan::default()
        };
        for &id in &others {
            plan.acts
                .push(genome.node(id).map_or(Activation::Linear, |n| n.activation));
            for l in genome.links().iter().filter(|l| l.enabled && l.to == id) {
                if let Some(&s) = slot.get(&l.from) {
                    plan.conn_src.push(s);
                    plan.conn_weight.push(l.weight);
                }
            }
            plan.conn_start.push(plan.conn_src.len() as u32);
        }
        plan.output_slots = outputs.iter().map(|o| slot[o]).collect();
        plan
    }

    #[test]
    fn recompile_gives_the_reference_plan_and_a_fresh_network() {
        let spec = GenomeSpec {
            allow_recurrent: true,
            ..GenomeSpec::plain(4, 3)
        };
        let params = NeatParams::plain_neat();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let mut tracker = InnovationTracker::new(7);
        let mut reused =
            RecurrentNetwork::from_genome(&Genome::minimal(&spec, &params, &mut tracker, &mut rng));
        for round in 0..40 {
            let g = grown(&spec, &params, &mut tracker, &mut rng, round % 9);
            let fresh = RecurrentNetwork::from_genome(&g);
            assert_eq!(fresh.plan, plan_reference(&g), "round {round}");
            // A network that held a larger or smaller genome, then recompiled.
            let mut out = [0.0; 3];
            reused.activate(&[0.5, -1.0, 2.0, 1.0], &mut out);
            reused.recompile(&g);
            assert_eq!(reused.plan, fresh.plan);
            assert_eq!(reused.state, fresh.state);
            let (mut a, mut b, mut f) = ([0.0; 3], [0.0; 3], fresh.clone());
            for _ in 0..5 {
                reused.activate(&[0.5, -1.0, 2.0, 1.0], &mut a);
                f.activate(&[0.5, -1.0, 2.0, 1.0], &mut b);
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
            }
        }
    }

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

//! Compiling a genome into an acyclic evaluation plan.
//!
//! The one reachability analysis and topological ordering of the crate: the
//! feed-forward network and hyperneat's batched CPPN both evaluate this plan,
//! so they add the same terms in the same order and give the same bits.

use std::collections::{BTreeMap, BTreeSet};

use crate::activation::Activation;
use crate::genome::{Genome, NodeKind};

/// A genome's enabled links as flat arrays in evaluation order.
///
/// Slots `0..num_inputs` are the inputs (by id); slot `num_inputs + k` is
/// computed node `k`. Only nodes from which an output can be reached are kept.
/// Should the enabled links contain a cycle, the links closing it are dropped
/// and [`Plan::cyclic`] is set.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Plan {
    /// Number of input slots.
    pub num_inputs: usize,
    /// Activation of computed node `k`.
    pub acts: Vec<Activation>,
    /// Incoming links of computed node `k` are `conn_start[k]..conn_start[k + 1]`.
    pub conn_start: Vec<u32>,
    /// Source slot of each link (always a slot evaluated earlier).
    pub conn_src: Vec<u32>,
    /// Weight of each link.
    pub conn_weight: Vec<f64>,
    /// Slot of each output, in output order.
    pub output_slots: Vec<u32>,
    /// Whether links were dropped to break a cycle.
    pub cyclic: bool,
}

impl Plan {
    /// Compiles the enabled links of `genome`.
    pub fn compile(genome: &Genome) -> Plan {
        let inputs = ids_of(genome, NodeKind::Input);
        let outputs = ids_of(genome, NodeKind::Output);
        let enabled: Vec<_> = genome.links().iter().filter(|l| l.enabled).collect();

        // Nodes that can reach an output (reverse search over enabled links).
        let mut needed: BTreeSet<u32> = outputs.iter().copied().collect();
        let mut stack: Vec<u32> = outputs.clone();
        while let Some(n) = stack.pop() {
            for l in enabled.iter().filter(|l| l.to == n) {
                if needed.insert(l.from) {
                    stack.push(l.from);
                }
            }
        }

        // Kahn's algorithm over needed non-input nodes, smallest id first.
        let is_input = |id: u32| inputs.binary_search(&id).is_ok();
        let mut indegree: BTreeMap<u32, usize> = needed
            .iter()
            .filter(|&&id| !is_input(id))
            .map(|&id| (id, 0))
            .collect();
        for l in &enabled {
            if !is_input(l.from)
                && needed.contains(&l.from)
                && let Some(d) = indegree.get_mut(&l.to)
            {
                *d += 1;
            }
        }
        let mut order = Vec::with_capacity(indegree.len());
        let mut ready: BTreeSet<u32> = indegree
            .iter()
            .filter(|(_, d)| **d == 0)
            .map(|(&id, _)| id)
            .collect();
        let mut done = BTreeSet::new();
        let mut cyclic = false;
        loop {
            let next = match ready.pop_first() {
                Some(n) => n,
                // A cycle: take the smallest remaining node; its back-links are dropped.
                None => match indegree.keys().find(|id| !done.contains(*id)) {
                    Some(&n) => {
                        cyclic = true;
                        n
                    }
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
            // In genome (innovation) order: the order every evaluator sums in.
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
        Plan {
            num_inputs: inputs.len(),
            acts,
            conn_start,
            conn_src,
            conn_weight,
            output_slots,
            cyclic,
        }
    }

    /// Incoming links of computed node `k`: source slots and weights.
    pub fn links(&self, k: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.conn_start[k] as usize, self.conn_start[k + 1] as usize);
        (&self.conn_src[s..e], &self.conn_weight[s..e])
    }

    /// The computed nodes output `output` depends on (itself included), in evaluation order.
    pub fn dependencies(&self, output: usize) -> Vec<usize> {
        let mut needed = vec![false; self.acts.len()];
        let Some(k) = (self.output_slots[output] as usize).checked_sub(self.num_inputs) else {
            return Vec::new();
        };
        needed[k] = true;
        // Sources always come earlier, so one backward sweep finds every ancestor.
        for k in (0..=k).rev() {
            if needed[k] {
                for &src in self.links(k).0 {
                    if let Some(j) = (src as usize).checked_sub(self.num_inputs) {
                        needed[j] = true;
                    }
                }
            }
        }
        (0..needed.len()).filter(|&k| needed[k]).collect()
    }
}

/// Ids of the nodes of `kind`, ascending.
pub(crate) fn ids_of(genome: &Genome, kind: NodeKind) -> Vec<u32> {
    genome
        .nodes()
        .iter()
        .filter(|n| n.kind == kind)
        .map(|n| n.id)
        .collect()
}

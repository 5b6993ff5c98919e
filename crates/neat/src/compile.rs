//! Compiling a genome into an acyclic evaluation plan.
//!
//! The one reachability analysis and topological ordering of the crate: the
//! feed-forward network and hyperneat's batched CPPN both evaluate this plan,
//! so they add the same terms in the same order and give the same bits.

use std::cell::RefCell;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::activation::Activation;
use crate::genome::{Genome, NodeGene, NodeKind};

/// A genome's enabled links as flat arrays in evaluation order.
///
/// Slots `0..num_inputs` are the inputs (by id); slot `num_inputs + k` is
/// computed node `k`. Only nodes from which an output can be reached are kept.
/// Should the enabled links contain a cycle, the links closing it are dropped
/// and [`Plan::cyclic`] is set.
#[derive(Debug, Clone, PartialEq, Default)]
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
        let mut plan = Plan::default();
        plan.recompile(genome);
        plan
    }

    /// Replaces this plan by the plan of `genome`, reusing its memory.
    ///
    /// The compiler's working arrays are kept per thread, so compiling
    /// allocates at most the plan's own arrays (and nothing once they are
    /// large enough).
    pub fn recompile(&mut self, genome: &Genome) {
        SCRATCH.with(|scratch| match scratch.try_borrow_mut() {
            Ok(mut scratch) => self.build(genome, &mut scratch),
            // Only reachable if compiling ever re-entered itself on one thread.
            Err(_) => self.build(genome, &mut Scratch::default()),
        });
    }

    /// The compiler. Works on node positions (nodes are sorted by id, so the
    /// smallest position is the smallest id) with flat adjacency lists: the
    /// same reachability, the same smallest-id-first topological order and
    /// the same per-node link order (innovation order) as the set-based
    /// definition (kept in the tests), in time linear in the genome's size
    /// plus a heap for the ready nodes.
    fn build(&mut self, genome: &Genome, s: &mut Scratch) {
        let nodes = genome.nodes();
        s.collect_links(genome);
        s.mark_needed(nodes);
        let cyclic = s.order_members(nodes);
        let num_inputs = s.assign_slots(nodes);
        self.write(nodes, s, num_inputs, cyclic);
    }

    /// Writes the plan from the compiled scratch: the computed nodes in
    /// evaluation order with their incoming links, then the output slots.
    fn write(&mut self, nodes: &[NodeGene], s: &Scratch, num_inputs: usize, cyclic: bool) {
        let (enabled, order, slot) = (&s.enabled, &s.order, &s.slot);
        self.num_inputs = num_inputs;
        self.cyclic = cyclic;
        self.acts.clear();
        self.conn_start.clear();
        self.conn_src.clear();
        self.conn_weight.clear();
        self.conn_start.push(0);
        for (k, &n) in order.iter().enumerate() {
            let my_slot = (num_inputs + k) as u32;
            self.acts.push(nodes[n as usize].activation);
            // In genome (innovation) order: the order every evaluator sums in.
            for &e in s.incoming.of(n as usize) {
                let (from, _, weight) = enabled[e as usize];
                let src = slot[from as usize];
                // Only sources evaluated earlier; anything else would close a cycle.
                if src < my_slot {
                    self.conn_src.push(src);
                    self.conn_weight.push(weight);
                }
            }
            self.conn_start.push(self.conn_src.len() as u32);
        }
        self.output_slots.clear();
        self.output_slots.extend(
            (0..nodes.len())
                .filter(|&k| nodes[k].kind == NodeKind::Output)
                .map(|k| slot[k]),
        );
    }

    /// Slots in all: the inputs and the computed nodes.
    pub fn slots(&self) -> usize {
        self.num_inputs + self.acts.len()
    }

    /// One activation of a network evaluating this plan, the sparse loop of
    /// every network of the crate (the [`Network`] contract): `inputs` into
    /// the first slots of `values`, then each computed node `k`'s
    /// `act(Σ w·value)` read from `values`, written to `values[num_inputs + k]`
    /// at once (feed-forward: later nodes read it) or, given `next`, to
    /// `next[k]`, copied to `values` once all are computed (a synchronous,
    /// recurrent update); then the output slots into `outputs`.
    ///
    /// [`Network`]: crate::network::Network
    #[inline(always)]
    pub fn activate(
        &self,
        inputs: &[f64],
        outputs: &mut [f64],
        values: &mut [f64],
        next: Option<&mut [f64]>,
    ) {
        match next {
            None => {
                let n_in = self.num_inputs;
                assert_io(inputs.len(), outputs.len(), n_in, self.output_slots.len());
                copy_short(&mut values[..n_in], inputs);
                for (k, &act) in self.acts.iter().enumerate() {
                    let (sources, weights) = self.links(k);
                    values[n_in + k] = act.apply(weighted_sum(sources, weights, values));
                }
                self.read_outputs(values, outputs);
            }
            Some(next) => {
                // Every node reads the previous state, so all sums come
                // first and their activations go together (same bits).
                self.recurrent_sums(inputs, outputs.len(), values, next);
                crate::activation::apply_all(&self.acts, next);
                self.recurrent_finish(values, next, outputs);
            }
        }
    }

    /// The first half of a synchronous update: `inputs` into the first
    /// slots of `values` (checked against this plan and `num_outputs`
    /// outputs), then each computed node's `Σ w·value` into `next`.
    #[inline(always)]
    pub fn recurrent_sums(
        &self,
        inputs: &[f64],
        num_outputs: usize,
        values: &mut [f64],
        next: &mut [f64],
    ) {
        let n_in = self.num_inputs;
        assert_io(inputs.len(), num_outputs, n_in, self.output_slots.len());
        copy_short(&mut values[..n_in], inputs);
        for (k, n) in next.iter_mut().enumerate() {
            let (sources, weights) = self.links(k);
            *n = weighted_sum(sources, weights, values);
        }
    }

    /// The second half, once `next` holds the activated sums: `next` into
    /// the computed slots of `values`, then the output slots into `outputs`.
    #[inline(always)]
    pub fn recurrent_finish(&self, values: &mut [f64], next: &[f64], outputs: &mut [f64]) {
        copy_short(&mut values[self.num_inputs..], next);
        self.read_outputs(values, outputs);
    }

    /// The output slots of `values` into `outputs`.
    #[inline(always)]
    fn read_outputs(&self, values: &[f64], outputs: &mut [f64]) {
        for (o, &s) in outputs.iter_mut().zip(&self.output_slots) {
            *o = values[s as usize];
        }
    }

    /// Incoming links of computed node `k`: source slots and weights.
    #[inline(always)]
    pub fn links(&self, k: usize) -> (&[u32], &[f64]) {
        links_of(&self.conn_start, &self.conn_src, &self.conn_weight, k)
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

/// The compiler's working arrays (see [`Plan::recompile`]).
#[derive(Debug, Default)]
struct Scratch {
    /// Node id → position in the genome being compiled (see `collect_links`).
    position_of: Vec<u32>,
    enabled: Vec<(u32, u32, f64)>,
    incoming: Adjacency,
    outgoing: Adjacency,
    needed: Vec<bool>,
    stack: Vec<u32>,
    member: Vec<bool>,
    indegree: Vec<u32>,
    ready: BinaryHeap<Reverse<u32>>,
    done: Vec<bool>,
    order: Vec<u32>,
    slot: Vec<u32>,
}

impl Scratch {
    /// Enabled links as (source, target, weight) node positions, in
    /// innovation order, and grouped by target (`incoming`) and by source
    /// (`outgoing`).
    fn collect_links(&mut self, genome: &Genome) {
        let nodes = genome.nodes();
        let nn = nodes.len();
        // Node id → position: a direct table while ids are not much larger
        // than the genome (entries of other genomes left in it are caught by
        // checking the id found), else a binary search.
        let max_id = nodes.last().map_or(0, |n| n.id as usize);
        let direct = max_id < 8 * nn + 1024;
        if direct {
            if self.position_of.len() <= max_id {
                self.position_of.resize(max_id + 1, u32::MAX);
            }
            for (k, n) in nodes.iter().enumerate() {
                self.position_of[n.id as usize] = k as u32;
            }
        }
        let position_of = &self.position_of;
        let position = |id: u32| -> Option<u32> {
            if direct {
                let p = *position_of.get(id as usize)?;
                (nodes.get(p as usize)?.id == id).then_some(p)
            } else {
                nodes
                    .binary_search_by_key(&id, |n| n.id)
                    .ok()
                    .map(|p| p as u32)
            }
        };
        // A checked genome has every link's nodes; anything else is skipped.
        self.enabled.clear();
        for l in genome.links().iter().filter(|l| l.enabled) {
            if let (Some(from), Some(to)) = (position(l.from), position(l.to)) {
                self.enabled.push((from, to, l.weight));
            }
        }
        let enabled = &self.enabled;
        // Counting sorts: stable, so each node's incoming links stay in
        // innovation order.
        self.incoming.group(nn, enabled.iter().map(|&(_, t, _)| t));
        self.outgoing.group(nn, enabled.iter().map(|&(f, _, _)| f));
    }

    /// Marks the nodes that can reach an output (reverse search over
    /// enabled links).
    fn mark_needed(&mut self, nodes: &[NodeGene]) {
        let needed = &mut self.needed;
        needed.clear();
        needed.resize(nodes.len(), false);
        self.stack.clear();
        for (k, n) in nodes.iter().enumerate() {
            if n.kind == NodeKind::Output {
                needed[k] = true;
                self.stack.push(k as u32);
            }
        }
        while let Some(n) = self.stack.pop() {
            for &e in self.incoming.of(n as usize) {
                let from = self.enabled[e as usize].0;
                if !needed[from as usize] {
                    needed[from as usize] = true;
                    self.stack.push(from);
                }
            }
        }
    }

    /// Kahn's algorithm over needed non-input nodes (members), smallest id
    /// first, into `order`. Returns whether a cycle had to be broken.
    fn order_members(&mut self, nodes: &[NodeGene]) -> bool {
        let nn = nodes.len();
        let enabled = &self.enabled;
        let needed = &self.needed;
        let member = &mut self.member;
        member.clear();
        member.extend((0..nn).map(|k| needed[k] && nodes[k].kind != NodeKind::Input));
        let indegree = &mut self.indegree;
        indegree.clear();
        indegree.resize(nn, 0);
        for &(f, t, _) in enabled {
            if member[f as usize] && member[t as usize] {
                indegree[t as usize] += 1;
            }
        }
        let ready = &mut self.ready;
        ready.clear();
        ready.extend(
            (0..nn)
                .filter(|&k| member[k] && indegree[k] == 0)
                .map(|k| Reverse(k as u32)),
        );
        let done = &mut self.done;
        done.clear();
        done.resize(nn, false);
        let order = &mut self.order;
        order.clear();
        let mut cyclic = false;
        // The smallest member not yet done only ever moves up.
        let mut smallest_left = 0usize;
        loop {
            let next = match ready.pop() {
                Some(Reverse(n)) => n as usize,
                // A cycle: take the smallest remaining node; its back-links are dropped.
                None => {
                    while smallest_left < nn && (done[smallest_left] || !member[smallest_left]) {
                        smallest_left += 1;
                    }
                    if smallest_left == nn {
                        break;
                    }
                    cyclic = true;
                    smallest_left
                }
            };
            done[next] = true;
            order.push(next as u32);
            for &e in self.outgoing.of(next) {
                let to = enabled[e as usize].1 as usize;
                if done[to] || !member[to] {
                    continue;
                }
                indegree[to] -= 1;
                if indegree[to] == 0 {
                    ready.push(Reverse(to as u32));
                }
            }
        }
        cyclic
    }

    /// Slots: inputs by id, then computed nodes in evaluation order.
    /// Returns the number of inputs.
    fn assign_slots(&mut self, nodes: &[NodeGene]) -> usize {
        let slot = &mut self.slot;
        slot.clear();
        slot.resize(nodes.len(), u32::MAX);
        let mut num_inputs = 0usize;
        for k in (0..nodes.len()).filter(|&k| nodes[k].kind == NodeKind::Input) {
            slot[k] = num_inputs as u32;
            num_inputs += 1;
        }
        for (k, &n) in self.order.iter().enumerate() {
            slot[n as usize] = (num_inputs + k) as u32;
        }
        num_inputs
    }
}

thread_local! {
    /// One compiler scratch per thread: compiling many genomes allocates nothing.
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Links grouped by one end: the links of node `k` are `list[start[k]..start[k + 1]]`
/// (indices into the enabled-link list, ascending).
#[derive(Debug, Default)]
struct Adjacency {
    start: Vec<u32>,
    list: Vec<u32>,
}

impl Adjacency {
    /// Groups links `0..` by `ends` (one node position per link), keeping their order.
    fn group(&mut self, nodes: usize, ends: impl Iterator<Item = u32> + Clone) {
        // Counting sort. Counts go two places up so that after the prefix
        // sum `start[e + 1]` is where group `e` begins; filling advances it to
        // where group `e` ends, which is where group `e + 1` begins.
        let start = &mut self.start;
        start.clear();
        start.resize(nodes + 2, 0);
        for e in ends.clone() {
            start[e as usize + 2] += 1;
        }
        for k in 0..=nodes {
            start[k + 1] += start[k];
        }
        self.list.clear();
        self.list.resize(start[nodes + 1] as usize, 0);
        for (i, e) in ends.enumerate() {
            let at = &mut start[e as usize + 1];
            self.list[*at as usize] = i as u32;
            *at += 1;
        }
    }

    /// The links of node `k`.
    fn of(&self, k: usize) -> &[u32] {
        &self.list[self.start[k] as usize..self.start[k + 1] as usize]
    }
}

/// Panics unless a network of `num_inputs` inputs and `num_outputs` outputs
/// is given `inputs` values and room for `outputs` (the [`Network`] contract).
///
/// [`Network`]: crate::network::Network
#[inline(always)]
pub(crate) fn assert_io(inputs: usize, outputs: usize, num_inputs: usize, num_outputs: usize) {
    assert_eq!(inputs, num_inputs, "wrong number of inputs");
    assert_eq!(outputs, num_outputs, "wrong number of outputs");
}

/// Incoming links of node `k` in the compressed sparse layout every network
/// of the crate uses (node k's links at `conn_start[k]..conn_start[k + 1]`):
/// their source slots and weights.
#[inline(always)]
pub(crate) fn links_of<'a, W>(
    conn_start: &[u32],
    conn_src: &'a [u32],
    conn_weight: &'a [W],
    k: usize,
) -> (&'a [u32], &'a [W]) {
    let (s, e) = (conn_start[k] as usize, conn_start[k + 1] as usize);
    (&conn_src[s..e], &conn_weight[s..e])
}

/// `dst.copy_from_slice(src)`, without a call to `memcpy` up to 16 values:
/// a network's inputs or computed nodes are a handful, and a call each
/// step was a tenth of a small recurrent network's time (one value: a
/// bias-only input or a single node) or 8 % (prey capture's 14 inputs).
/// Up to 16 values are two fixed-size copies, which compile to a few
/// vector moves: the first and the last `K` values, overlapping when fewer
/// than `2K` (`memcpy`'s own trick).
#[inline(always)]
pub(crate) fn copy_short<T: Copy>(dst: &mut [T], src: &[T]) {
    /// The first and last `K` of `src` (`K ≤ src.len() ≤ 2K`) into `dst`.
    #[inline(always)]
    fn ends<T: Copy, const K: usize>(dst: &mut [T], src: &[T]) {
        let n = src.len();
        let head: [T; K] = src[..K].try_into().expect("K values");
        let tail: [T; K] = src[n - K..].try_into().expect("K values");
        dst[..K].copy_from_slice(&head);
        dst[n - K..].copy_from_slice(&tail);
    }
    assert_eq!(dst.len(), src.len(), "copy between slices of one length");
    match src.len() {
        0 => {}
        1 => dst[0] = src[0],
        2..=3 => ends::<T, 2>(dst, src),
        4..=7 => ends::<T, 4>(dst, src),
        8..=16 => ends::<T, 8>(dst, src),
        _ => dst.copy_from_slice(src),
    }
}

/// Σ `weights[i] · values[sources[i]]`, added in link order from 0: the one
/// sum order of the networks' activation, so that they give the same bits.
#[inline(always)]
pub(crate) fn weighted_sum(sources: &[u32], weights: &[f64], values: &[f64]) -> f64 {
    let mut sum = 0.0;
    for (&src, &w) in sources.iter().zip(weights) {
        sum += values[src as usize] * w;
    }
    sum
}

/// Ids of the nodes of `kind`, ascending.
#[cfg(test)]
pub(crate) fn ids_of(genome: &Genome, kind: NodeKind) -> Vec<u32> {
    genome
        .nodes()
        .iter()
        .filter(|n| n.kind == kind)
        .map(|n| n.id)
        .collect()
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};

    use super::*;

    #[test]
    fn copy_short_copies_every_length() {
        for n in 0..40 {
            let src: Vec<f64> = (0..n).map(|k| k as f64 + 0.5).collect();
            let mut dst = vec![f64::NAN; n];
            copy_short(&mut dst, &src);
            assert_eq!(dst, src, "{n} values");
        }
    }
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use crate::mutation::{mutate_add_link, mutate_add_node, mutate_toggle_enable};
    use crate::params::NeatParams;
    use rand::SeedableRng;

    /// The set-based compiler this module started with: the definition the
    /// fast one must reproduce exactly.
    fn compile_reference(genome: &Genome) -> Plan {
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

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

        /// Same plan (order, slots, links and their order, cycle flag) as the
        /// reference, for grown genomes with disabled links and, when
        /// recurrent, cycles and self-loops.
        #[test]
        fn compile_matches_reference(
            seed in proptest::prelude::any::<u64>(),
            ops in proptest::collection::vec(0u8..4, 0..80),
            recurrent in proptest::prelude::any::<bool>(),
        ) {
            let spec = GenomeSpec { allow_recurrent: recurrent, ..GenomeSpec::cppn() };
            let params = NeatParams::default();
            let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
            let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
            let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
            for op in ops {
                match op {
                    0 => {
                        mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
                    }
                    1 | 2 => {
                        mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
                    }
                    _ => {
                        mutate_toggle_enable(&mut g, &mut rng);
                    }
                }
                proptest::prop_assert_eq!(Plan::compile(&g), compile_reference(&g));
            }
        }
    }
}

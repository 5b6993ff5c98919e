//! Recurrent networks of several genomes stepped together (TensorNEAT's
//! idea on CPU lanes): one step of all of them computes every node's sum,
//! then all their activation functions at once, as vector lanes.

use crate::activation::{Activation, apply_all};
use crate::compile::{assert_io, copy_short, weighted_sum};
use crate::genome::Genome;
use crate::recurrent::RecurrentNetwork;

/// The recurrent networks of up to [`RecurrentLanes::capacity`] genomes,
/// each stepped exactly as its own [`RecurrentNetwork`] (the same bits), all
/// in one pass per step.
///
/// A network of one or two nodes spends most of a step in one `exp`, a chain
/// of dependent operations; side by side, the `exp`s of several genomes'
/// networks share vector instructions. For tasks that step every network
/// the same number of times (or mask the ones that are done).
///
/// The lanes' networks are held as one: every lane's slots in one array,
/// every computed node's links in one list whose sources index that array.
/// A step then walks the nodes of all lanes in one loop, with none of the
/// per-network work (its arrays, its checks) that is most of a step of a
/// network this small.
#[derive(Debug, Clone)]
pub struct RecurrentLanes {
    /// The most lanes.
    capacity: usize,
    /// Where each used lane lives in the arrays below.
    lanes: Vec<Lane>,
    /// Compiles a genome (its plan is copied into the arrays below).
    compiler: RecurrentNetwork,
    /// Every used lane's slots (its inputs, then its computed nodes), lane after lane.
    values: Vec<f64>,
    /// Computed node `k`'s links are `starts[k]..starts[k + 1]` of `sources` and `weights`.
    starts: Vec<u32>,
    /// Each link's source: an index into `values`.
    sources: Vec<u32>,
    /// Each link's weight.
    weights: Vec<f64>,
    /// Every lane's output slots (indices into `values`), lane after lane.
    outputs: Vec<u32>,
    /// The activation of every computed node of every used lane, lane after lane.
    acts: Vec<Activation>,
    /// Scratch: every computed node's sum, then its value, in `acts`' order.
    sums: Vec<f64>,
}

/// One lane's place in the arrays of [`RecurrentLanes`].
#[derive(Debug, Clone, Copy)]
struct Lane {
    /// Its first slot in `values`.
    slot0: usize,
    /// Its inputs (the first slots).
    inputs: usize,
    /// Its computed nodes (the slots after the inputs; `acts[node0..]`).
    computed: usize,
    /// Its first computed node in `acts` and `sums`.
    node0: usize,
    /// Its first output in `outputs`.
    out0: usize,
    /// Its outputs.
    outs: usize,
}

impl RecurrentLanes {
    /// Room for `capacity` genomes' networks (at least one).
    pub fn new(capacity: usize) -> RecurrentLanes {
        RecurrentLanes {
            capacity: capacity.max(1),
            lanes: Vec::new(),
            compiler: RecurrentNetwork::empty(),
            values: Vec::new(),
            starts: vec![0],
            sources: Vec::new(),
            weights: Vec::new(),
            outputs: Vec::new(),
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
        self.lanes.len()
    }

    /// Makes lane `l` the network of `genomes[l]`, states cleared, reusing
    /// memory (panics with more genomes than [`RecurrentLanes::capacity`]).
    pub fn recompile<'g>(&mut self, genomes: impl IntoIterator<Item = &'g Genome>) {
        self.clear();
        for g in genomes {
            self.push(g);
        }
    }

    /// Holds no lane (memory kept).
    pub fn clear(&mut self) {
        self.lanes.clear();
        self.values.clear();
        self.starts.clear();
        self.starts.push(0);
        self.sources.clear();
        self.weights.clear();
        self.outputs.clear();
        self.acts.clear();
        self.sums.clear();
    }

    /// Adds `genome`'s network as the last lane, its state cleared; the other
    /// lanes keep theirs (panics when all [`RecurrentLanes::capacity`] lanes are held).
    pub fn push(&mut self, genome: &Genome) {
        assert!(self.lanes.len() < self.capacity, "more genomes than lanes");
        // The network `RecurrentNetwork` would step, moved into the shared arrays.
        self.compiler.recompile(genome);
        let plan = &self.compiler.plan;
        let slot0 = self.values.len();
        let lane = Lane {
            slot0,
            inputs: plan.num_inputs,
            computed: plan.acts.len(),
            node0: self.acts.len(),
            out0: self.outputs.len(),
            outs: plan.output_slots.len(),
        };
        self.values.resize(slot0 + plan.slots(), 0.0);
        for k in 0..plan.acts.len() {
            let (sources, weights) = plan.links(k);
            self.sources
                .extend(sources.iter().map(|&s| slot0 as u32 + s));
            self.weights.extend_from_slice(weights);
            self.starts.push(self.sources.len() as u32);
        }
        self.acts.extend_from_slice(&plan.acts);
        self.outputs
            .extend(plan.output_slots.iter().map(|&s| slot0 as u32 + s));
        self.sums.resize(self.acts.len(), 0.0);
        self.lanes.push(lane);
    }

    /// Drops lane `l`; the lanes after it move down one place, states and
    /// all (so a task whose genomes finish at different times can keep every
    /// lane busy: drop a finished one, [`push`](Self::push) the next genome).
    /// Panics if there is no lane `l`, as [`Vec::remove`] does.
    pub fn remove(&mut self, l: usize) {
        let lane = self.lanes.remove(l);
        let slots = lane.inputs + lane.computed;
        let (k0, k1) = (lane.node0, lane.node0 + lane.computed);
        let (link0, link1) = (self.starts[k0] as usize, self.starts[k1] as usize);
        let links = (link1 - link0) as u32;
        self.values.drain(lane.slot0..lane.slot0 + slots);
        self.sources.drain(link0..link1);
        self.weights.drain(link0..link1);
        self.starts.drain(k0 + 1..=k1);
        self.acts.drain(k0..k1);
        self.sums.truncate(self.acts.len());
        self.outputs.drain(lane.out0..lane.out0 + lane.outs);
        // Everything after the lane (only later lanes' slots are named
        // there) sits `slots` slots, `links` links, `computed` nodes and
        // `outs` outputs lower now.
        let slots32 = slots as u32;
        for s in self.sources[link0..]
            .iter_mut()
            .chain(&mut self.outputs[lane.out0..])
        {
            *s -= slots32;
        }
        for st in &mut self.starts[k0 + 1..] {
            *st -= links;
        }
        for later in &mut self.lanes[l..] {
            later.slot0 -= slots;
            later.node0 -= lane.computed;
            later.out0 -= lane.outs;
        }
    }

    /// Clears the state of lane `l` (as [`Network::reset`](crate::Network::reset) on its network).
    pub fn reset_lane(&mut self, l: usize) {
        let lane = self.lanes[l];
        self.values[lane.slot0..][..lane.inputs + lane.computed].fill(0.0);
    }

    /// Clears every lane's state.
    pub fn reset(&mut self) {
        self.values.fill(0.0);
    }

    /// One step of every lane: lane `l` reads `inputs[l]` and writes
    /// `outputs[l]`, exactly as its network's [`Network::activate`](crate::Network::activate) would.
    pub fn activate(&mut self, inputs: &[&[f64]], outputs: &mut [&mut [f64]]) {
        assert!(
            inputs.len() == self.lanes.len() && outputs.len() == self.lanes.len(),
            "one input and one output slice per lane"
        );
        for ((lane, input), output) in self.lanes.iter().zip(inputs).zip(outputs.iter()) {
            assert_io(input.len(), output.len(), lane.inputs, lane.outs);
            copy_short(&mut self.values[lane.slot0..][..lane.inputs], input);
        }
        // Every lane's sums read the previous state, in each node's link order.
        let values = &self.values;
        for (k, sum) in self.sums.iter_mut().enumerate() {
            let (s, e) = (self.starts[k] as usize, self.starts[k + 1] as usize);
            *sum = weighted_sum(&self.sources[s..e], &self.weights[s..e], values);
        }
        apply_all(&self.acts, &mut self.sums);
        for (lane, output) in self.lanes.iter().zip(outputs) {
            let computed = &mut self.values[lane.slot0 + lane.inputs..][..lane.computed];
            copy_short(computed, &self.sums[lane.node0..][..lane.computed]);
            let slots = &self.outputs[lane.out0..][..lane.outs];
            for (o, &s) in output.iter_mut().zip(slots) {
                *o = self.values[s as usize];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use crate::network::Network;
    use crate::params::NeatParams;
    use crate::test_genes::grown;
    use rand::{RngExt, SeedableRng};

    /// One step of random inputs (3 a lane) through `lanes` and through each
    /// lane's own network in `alone`: the same output bits, or a panic naming `what`.
    fn step_both(
        lanes: &mut RecurrentLanes,
        alone: &mut [RecurrentNetwork],
        rng: &mut rand_pcg::Pcg64,
        what: &str,
    ) {
        let inputs: Vec<[f64; 3]> = (0..alone.len())
            .map(|_| std::array::from_fn(|_| rng.random::<f64>() * 4.0 - 2.0))
            .collect();
        let mut outs = vec![[0.0; 2]; alone.len()];
        let ins: Vec<&[f64]> = inputs.iter().map(|i| &i[..]).collect();
        let mut out_refs: Vec<&mut [f64]> = outs.iter_mut().map(|o| &mut o[..]).collect();
        lanes.activate(&ins, &mut out_refs);
        for (l, net) in alone.iter_mut().enumerate() {
            let mut want = [0.0; 2];
            net.activate(&inputs[l], &mut want);
            assert_eq!(
                outs[l].map(f64::to_bits),
                want.map(f64::to_bits),
                "{what} lane {l}"
            );
        }
    }

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
                step_both(
                    &mut lanes,
                    &mut alone,
                    &mut rng,
                    &format!("round {round} step {step}"),
                );
                if step == 5 {
                    // One lane restarts alone.
                    lanes.reset_lane(0);
                    alone[0].reset();
                }
            }
        }
    }

    /// Lanes dropped and added mid-run (genomes of every size, the dropped
    /// lane anywhere) leave every other lane stepping as its own network.
    #[test]
    fn removing_and_pushing_lanes_keeps_every_other_lanes_bits() {
        let spec = GenomeSpec {
            allow_recurrent: true,
            ..GenomeSpec::plain(3, 2)
        };
        let params = NeatParams::plain_neat();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(12);
        let mut tracker = InnovationTracker::new(5);
        let mut lanes = RecurrentLanes::new(5);
        let mut alone: Vec<RecurrentNetwork> = Vec::new();
        let mut made = 0;
        let mut grow = |rng: &mut rand_pcg::Pcg64| {
            made += 1;
            grown(&spec, &params, &mut tracker, rng, made % 7)
        };
        for _ in 0..5 {
            let g = grow(&mut rng);
            lanes.push(&g);
            alone.push(RecurrentNetwork::from_genome(&g));
        }
        for step in 0..200 {
            let n = alone.len();
            step_both(&mut lanes, &mut alone, &mut rng, &format!("step {step}"));
            if step % 3 == 2 && n > 0 {
                let l = rng.random_range(0..n);
                lanes.remove(l);
                alone.remove(l);
            }
            if step % 4 == 3 && alone.len() < lanes.capacity() {
                let g = grow(&mut rng);
                lanes.push(&g);
                alone.push(RecurrentNetwork::from_genome(&g));
            }
            assert_eq!(lanes.lanes(), alone.len());
        }
        // Emptied and refilled, it is as new.
        while lanes.lanes() > 0 {
            lanes.remove(0);
        }
        let g = grow(&mut rng);
        lanes.push(&g);
        let mut fresh = RecurrentLanes::new(5);
        fresh.recompile([&g]);
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        lanes.activate(&[&[0.5, -1.0, 2.0]], &mut [&mut a]);
        fresh.activate(&[&[0.5, -1.0, 2.0]], &mut [&mut b]);
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
}

//! A substrate network of positioned nodes and explicit links (ES-HyperNEAT
//! and layered substrates decode into it).

use super::error::HyperError;
use crate::activation::bipolar_sigmoid;
use crate::network::Network;

/// One link of a [`SparseNetwork`]; node indices are inputs, then outputs, then hidden nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SparseLink {
    /// Source node index.
    pub source: usize,
    /// Target node index (never an input).
    pub target: usize,
    /// Link weight (finite, never 0).
    pub weight: f64,
}

/// A network of input, output and hidden nodes joined by explicit links.
///
/// Every non-input node computes `σ(b + Σ w·x)`, σ the bipolar sigmoid (as
/// in [`SubstrateController`](super::SubstrateController)). When the links
/// form no cycle, one `activate` propagates the inputs through the whole
/// network in topological order (a feed-forward net); otherwise every
/// non-input node is updated synchronously once per `activate` from the
/// previous states (a recurrent net, like the substrate controller).
#[derive(Debug, Clone, PartialEq)]
pub struct SparseNetwork {
    num_inputs: usize,
    num_outputs: usize,
    /// Positions of the hidden nodes, in node order.
    hidden: Vec<[f64; 2]>,
    /// Bias of each non-input node (outputs then hidden), 0 = none.
    bias: Vec<f64>,
    /// Links sorted by (target, source).
    links: Vec<SparseLink>,
    /// `links[starts[n]..starts[n + 1]]` are the links into node `n`.
    starts: Vec<usize>,
    /// Non-input nodes in evaluation order (topological when acyclic).
    order: Vec<usize>,
    recurrent: bool,
    values: Vec<f64>,
    next: Vec<f64>,
}

impl SparseNetwork {
    /// A network from its parts; `bias` has one entry per output and hidden node.
    pub fn new(
        num_inputs: usize,
        num_outputs: usize,
        hidden: Vec<[f64; 2]>,
        bias: Vec<f64>,
        mut links: Vec<SparseLink>,
    ) -> Result<SparseNetwork, HyperError> {
        let n = num_inputs + num_outputs + hidden.len();
        if num_outputs == 0 {
            return Err(HyperError::NoNeurons);
        }
        if bias.len() != n - num_inputs {
            return Err(HyperError::Inconsistent(
                "one bias per output and hidden node",
            ));
        }
        if bias.iter().any(|b| !b.is_finite()) {
            return Err(HyperError::Inconsistent("non-finite bias"));
        }
        for l in &links {
            if l.source >= n || l.target >= n || l.target < num_inputs {
                return Err(HyperError::Inconsistent(
                    "link end out of range or into an input",
                ));
            }
            if !l.weight.is_finite() || l.weight == 0.0 {
                return Err(HyperError::Inconsistent(
                    "link weight not finite and non-zero",
                ));
            }
        }
        links.sort_by_key(|l| (l.target, l.source));
        if links
            .windows(2)
            .any(|w| (w[0].target, w[0].source) == (w[1].target, w[1].source))
        {
            return Err(HyperError::Inconsistent("duplicate link"));
        }
        let mut starts = vec![0; n + 1];
        for l in &links {
            starts[l.target + 1] += 1;
        }
        for i in 0..n {
            starts[i + 1] += starts[i];
        }
        let order = topological_order(num_inputs, n, &links);
        let recurrent = order.is_none();
        Ok(SparseNetwork {
            num_inputs,
            num_outputs,
            hidden,
            bias,
            links,
            starts,
            order: order.unwrap_or_else(|| (num_inputs..n).collect()),
            recurrent,
            values: vec![0.0; n],
            next: vec![0.0; n],
        })
    }

    /// Positions of the hidden nodes (node `num_inputs + num_outputs + k` is `hidden()[k]`).
    pub fn hidden(&self) -> &[[f64; 2]] {
        &self.hidden
    }

    /// Number of hidden nodes.
    pub fn num_hidden(&self) -> usize {
        self.hidden.len()
    }

    /// The links, sorted by (target, source).
    pub fn links(&self) -> &[SparseLink] {
        &self.links
    }

    /// Biases of the outputs then the hidden nodes (0 = none).
    pub fn biases(&self) -> &[f64] {
        &self.bias
    }

    /// Whether the links form a cycle (the network then updates synchronously).
    pub fn is_recurrent(&self) -> bool {
        self.recurrent
    }

    /// Number of nodes (inputs, outputs, hidden): the length of a state for [`SparseNetwork::activate_in`].
    pub fn num_nodes(&self) -> usize {
        self.num_inputs + self.num_outputs + self.hidden.len()
    }

    /// One activation as [`Network::activate`] does it, but on the node
    /// states `values` and scratch `next` (each [`SparseNetwork::num_nodes`]
    /// long, zero at the start) instead of the network's own: one network's
    /// weights can then drive many robots, each with its own state.
    pub fn activate_in(
        &self,
        values: &mut [f64],
        next: &mut [f64],
        inputs: &[f64],
        outputs: &mut [f64],
    ) {
        assert_eq!(inputs.len(), self.num_inputs, "one value per input");
        assert_eq!(outputs.len(), self.num_outputs, "one value per output");
        assert_eq!(values.len(), self.num_nodes(), "one state per node");
        assert_eq!(next.len(), self.num_nodes(), "one scratch value per node");
        values[..self.num_inputs].copy_from_slice(inputs);
        if self.recurrent {
            for &node in &self.order {
                next[node] = bipolar_sigmoid(self.net_input(node, values));
            }
            values[self.num_inputs..].copy_from_slice(&next[self.num_inputs..]);
        } else {
            for &node in &self.order {
                values[node] = bipolar_sigmoid(self.net_input(node, values));
            }
        }
        outputs.copy_from_slice(&values[self.num_inputs..self.num_inputs + self.num_outputs]);
    }

    /// Sum of `bias + Σ w·x` into node `node`, the inputs of the links read from `values`.
    #[inline]
    fn net_input(&self, node: usize, values: &[f64]) -> f64 {
        let mut s = self.bias[node - self.num_inputs];
        for l in &self.links[self.starts[node]..self.starts[node + 1]] {
            s += l.weight * values[l.source];
        }
        s
    }
}

/// Non-input nodes in a topological order (Kahn, smallest index first), `None` on a cycle.
fn topological_order(num_inputs: usize, n: usize, links: &[SparseLink]) -> Option<Vec<usize>> {
    let mut indegree = vec![0usize; n];
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
    for l in links {
        indegree[l.target] += 1;
        out[l.source].push(l.target);
    }
    let mut ready: std::collections::BTreeSet<usize> =
        (0..n).filter(|&i| indegree[i] == 0).collect();
    let mut order = Vec::with_capacity(n - num_inputs);
    while let Some(i) = ready.pop_first() {
        if i >= num_inputs {
            order.push(i);
        }
        for &t in &out[i] {
            indegree[t] -= 1;
            if indegree[t] == 0 {
                ready.insert(t);
            }
        }
    }
    (order.len() == n - num_inputs).then_some(order)
}

impl Network for SparseNetwork {
    fn num_inputs(&self) -> usize {
        self.num_inputs
    }

    fn num_outputs(&self) -> usize {
        self.num_outputs
    }

    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        let mut values = std::mem::take(&mut self.values);
        let mut next = std::mem::take(&mut self.next);
        self.activate_in(&mut values, &mut next, inputs, outputs);
        self.values = values;
        self.next = next;
    }

    fn reset(&mut self) {
        self.values.fill(0.0);
        self.next.fill(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn link(source: usize, target: usize, weight: f64) -> SparseLink {
        SparseLink {
            source,
            target,
            weight,
        }
    }

    #[test]
    fn feed_forward_chain_propagates_in_one_activation() {
        // in0 → hidden(3) → out(2), in1 → out directly; node 2 is the output.
        let mut net = SparseNetwork::new(
            2,
            1,
            vec![[0.0, 0.0]],
            vec![0.1, -0.2],
            vec![link(3, 2, 2.0), link(0, 3, 1.5), link(1, 2, -1.0)],
        )
        .unwrap();
        assert!(!net.is_recurrent());
        let mut out = [0.0];
        net.activate(&[0.5, 0.25], &mut out);
        let h = bipolar_sigmoid(-0.2 + 1.5 * 0.5);
        let expected = bipolar_sigmoid(0.1 - 0.25 + 2.0 * h);
        assert_eq!(out[0], expected);
    }

    #[test]
    fn a_cycle_makes_a_synchronous_recurrent_network() {
        // hidden 2 ↔ output 1: a cycle.
        let mut net = SparseNetwork::new(
            1,
            1,
            vec![[0.0, 0.0]],
            vec![0.0, 0.0],
            vec![link(0, 2, 1.0), link(2, 1, 1.0), link(1, 2, 1.0)],
        )
        .unwrap();
        assert!(net.is_recurrent());
        let mut out = [0.0];
        // Step 1: the output reads the hidden state of step 0 (0).
        net.activate(&[1.0], &mut out);
        assert_eq!(out[0], 0.0);
        net.activate(&[1.0], &mut out);
        assert_eq!(out[0], bipolar_sigmoid(bipolar_sigmoid(1.0)));
        net.reset();
        net.activate(&[1.0], &mut out);
        assert_eq!(out[0], 0.0);
    }

    #[test]
    fn inconsistent_parts_are_refused() {
        let bad = |links| SparseNetwork::new(1, 1, vec![], vec![0.0], links).is_err();
        assert!(bad(vec![link(1, 0, 1.0)]), "link into an input");
        assert!(bad(vec![link(0, 5, 1.0)]), "out of range");
        assert!(bad(vec![link(0, 1, 0.0)]), "zero weight");
        assert!(bad(vec![link(0, 1, 1.0), link(0, 1, 2.0)]), "duplicate");
        assert!(SparseNetwork::new(1, 1, vec![], vec![], vec![]).is_err());
        assert!(SparseNetwork::new(1, 0, vec![], vec![], vec![]).is_err());
    }
}

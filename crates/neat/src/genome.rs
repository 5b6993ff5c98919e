//! Genomes: node genes and link genes with historical markings.

use std::collections::BTreeSet;

use rand::{Rng, RngExt};
use serde::{Deserialize, Serialize};

use crate::activation::Activation;
use crate::error::{GenomeError, NeatError};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;

/// What the genomes of a run look like: inputs, outputs and allowed node functions.
///
/// There is no separate bias node kind: as in Stanley's NEAT and the paper's CPPN
/// inputs `(x1, y1, x2, y2, 1)`, the bias is an ordinary input the caller holds at a
/// constant value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GenomeSpec {
    /// Number of input nodes (including any constant bias input).
    pub inputs: usize,
    /// Number of output nodes.
    pub outputs: usize,
    /// Activation function of every output node.
    pub output_activation: Activation,
    /// Functions a hidden node may have (chosen at random on creation and mutation).
    pub hidden_activations: Vec<Activation>,
    /// Whether add-link may create recurrent links (cycles, self-loops).
    pub allow_recurrent: bool,
}

impl GenomeSpec {
    /// The paper's CPPN: inputs `(x1, y1, x2, y2, 1)`, three bipolar-sigmoid outputs,
    /// the six Table I hidden functions, feed-forward only.
    pub fn cppn() -> GenomeSpec {
        GenomeSpec {
            inputs: 5,
            outputs: 3,
            output_activation: Activation::BipolarSigmoid,
            hidden_activations: Activation::CPPN_SET.to_vec(),
            allow_recurrent: false,
        }
    }

    /// A plain NEAT network: `inputs` (include a constant bias input if you
    /// want one) and `outputs` with Stanley's steepened sigmoid everywhere,
    /// feed-forward only. The spec [`NeatParams::plain_neat`](crate::NeatParams::plain_neat) is tuned for.
    pub fn plain(inputs: usize, outputs: usize) -> GenomeSpec {
        GenomeSpec {
            inputs,
            outputs,
            output_activation: Activation::Sigmoid,
            hidden_activations: vec![Activation::Sigmoid],
            allow_recurrent: false,
        }
    }

    /// Checks that the spec describes a usable genome.
    pub fn validate(&self) -> Result<(), NeatError> {
        if self.inputs == 0 {
            return Err(NeatError::InvalidSpec(
                "inputs = 0: need at least one input".into(),
            ));
        }
        if self.outputs == 0 {
            return Err(NeatError::InvalidSpec(
                "outputs = 0: need at least one output".into(),
            ));
        }
        if self.hidden_activations.is_empty() {
            return Err(NeatError::InvalidSpec(
                "hidden_activations is empty: need at least one function".into(),
            ));
        }
        if self.inputs + self.outputs > u32::MAX as usize / 2 {
            return Err(NeatError::InvalidSpec(format!(
                "{} inputs + {} outputs is too many",
                self.inputs, self.outputs
            )));
        }
        Ok(())
    }
}

/// The role of a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// Receives an external input (the bias is an input held constant by the caller).
    Input,
    /// Added by the add-node mutation (or in a start genome with `start_hidden`).
    Hidden,
    /// Produces an external output.
    Output,
}

impl NodeKind {
    /// The kind's name as written in JSON (`input`, `hidden`, `output`).
    pub fn name(self) -> &'static str {
        match self {
            NodeKind::Input => "input",
            NodeKind::Hidden => "hidden",
            NodeKind::Output => "output",
        }
    }

    /// The kind a node with this id has in genomes of `spec`: inputs are
    /// `0..inputs`, outputs follow, every later id is hidden.
    pub fn of_id(id: u32, spec: &GenomeSpec) -> NodeKind {
        let id = id as usize;
        if id < spec.inputs {
            NodeKind::Input
        } else if id < spec.inputs + spec.outputs {
            NodeKind::Output
        } else {
            NodeKind::Hidden
        }
    }
}

/// A node gene: id (shared across the population for the same structural origin),
/// role and activation function.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NodeGene {
    /// Node id; inputs are `0..inputs`, outputs follow, hidden nodes come from the tracker.
    pub id: u32,
    /// The node's role.
    pub kind: NodeKind,
    /// The node's activation function (ignored for inputs).
    pub activation: Activation,
}

/// A link gene with its historical marking.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinkGene {
    /// Innovation number: identical `(from, to)` ⇔ identical innovation within a run.
    pub innovation: u32,
    /// Source node id.
    pub from: u32,
    /// Target node id.
    pub to: u32,
    /// Connection weight.
    pub weight: f64,
    /// Disabled links are kept in the genome but not expressed.
    pub enabled: bool,
}

/// A NEAT genome: nodes sorted by id, links sorted by innovation.
///
/// Deserialising checks every invariant of [`Genome::check`] (through
/// [`RawGenome`]), so a `Genome` read from JSON is always valid.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawGenome")]
pub struct Genome {
    pub(crate) nodes: Vec<NodeGene>,
    pub(crate) links: Vec<LinkGene>,
}

/// Written out for `clone_from`, which reuses the target's gene arrays
/// (breeding copies parents into retired genomes; the derived one would
/// allocate anew).
impl Clone for Genome {
    fn clone(&self) -> Genome {
        Genome {
            nodes: self.nodes.clone(),
            links: self.links.clone(),
        }
    }

    fn clone_from(&mut self, source: &Genome) {
        self.nodes.clone_from(&source.nodes);
        self.links.clone_from(&source.links);
    }
}

/// A genome's genes as read, not yet checked; `Genome::try_from` validates them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RawGenome {
    /// Node genes, in any order.
    pub nodes: Vec<NodeGene>,
    /// Link genes, in any order.
    pub links: Vec<LinkGene>,
}

impl TryFrom<RawGenome> for Genome {
    type Error = GenomeError;

    /// Sorts the genes and checks every invariant of [`Genome::check`].
    fn try_from(raw: RawGenome) -> Result<Genome, GenomeError> {
        let RawGenome {
            mut nodes,
            mut links,
        } = raw;
        nodes.sort_by_key(|n| n.id);
        links.sort_by_key(|l| l.innovation);
        let g = Genome { nodes, links };
        g.check()?;
        Ok(g)
    }
}

impl Genome {
    /// A genome of no genes, to be filled (breeding reuses genomes' memory).
    pub(crate) fn empty() -> Genome {
        Genome {
            nodes: Vec::new(),
            links: Vec::new(),
        }
    }

    /// The start genome: inputs fully connected to outputs with random
    /// weights, or through `params.start_hidden` hidden nodes.
    pub fn minimal<R: Rng + ?Sized>(
        spec: &GenomeSpec,
        params: &NeatParams,
        tracker: &mut InnovationTracker,
        rng: &mut R,
    ) -> Genome {
        let n_in = spec.inputs as u32;
        let n_out = spec.outputs as u32;
        let n_hidden = params.start_hidden as u32;
        let mut nodes = Vec::with_capacity((n_in + n_out + n_hidden) as usize);
        for id in 0..n_in {
            nodes.push(NodeGene {
                id,
                kind: NodeKind::Input,
                activation: Activation::Linear,
            });
        }
        for k in 0..n_out {
            nodes.push(NodeGene {
                id: n_in + k,
                kind: NodeKind::Output,
                activation: spec.output_activation,
            });
        }
        // The start's hidden nodes have the same ids in every genome (the
        // first hidden ids), so that crossover aligns them.
        let first_hidden = n_in + n_out;
        let hidden = first_hidden..first_hidden + n_hidden;
        for id in hidden.clone() {
            tracker.absorb_node(id);
            nodes.push(NodeGene {
                id,
                kind: NodeKind::Hidden,
                activation: spec.hidden_activations[0],
            });
        }
        // Every node of one layer linked to every node of the next.
        let full = |from: std::ops::Range<u32>, to: std::ops::Range<u32>| {
            from.flat_map(move |f| to.clone().map(move |t| (f, t)))
        };
        let (inputs, outputs) = (0..n_in, n_in..first_hidden);
        let pairs: Vec<(u32, u32)> = if hidden.is_empty() {
            full(inputs, outputs).collect()
        } else {
            full(inputs, hidden.clone())
                .chain(full(hidden, outputs))
                .collect()
        };
        let mut links: Vec<LinkGene> = pairs
            .into_iter()
            .map(|(from, to)| LinkGene {
                innovation: tracker.link_innovation(from, to),
                from,
                to,
                weight: random_weight(params, rng),
                enabled: true,
            })
            .collect();
        links.sort_by_key(|l| l.innovation);
        Genome { nodes, links }
    }

    /// Builds a genome from explicit genes, checking every invariant (for tests and tools).
    pub fn from_parts(nodes: Vec<NodeGene>, links: Vec<LinkGene>) -> Result<Genome, NeatError> {
        Ok(Genome::try_from(RawGenome { nodes, links })?)
    }

    /// Node genes, sorted by id.
    pub fn nodes(&self) -> &[NodeGene] {
        &self.nodes
    }

    /// Link genes, sorted by innovation number.
    pub fn links(&self) -> &[LinkGene] {
        &self.links
    }

    /// Number of input nodes.
    pub fn num_inputs(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Input)
            .count()
    }

    /// Number of output nodes.
    pub fn num_outputs(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Output)
            .count()
    }

    /// Number of hidden nodes.
    pub fn num_hidden(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Hidden)
            .count()
    }

    /// Number of enabled links.
    pub fn num_enabled_links(&self) -> usize {
        self.links.iter().filter(|l| l.enabled).count()
    }

    /// The node gene with this id, if any.
    pub fn node(&self, id: u32) -> Option<&NodeGene> {
        self.nodes
            .binary_search_by_key(&id, |n| n.id)
            .ok()
            .map(|i| &self.nodes[i])
    }

    /// Whether a node with this id exists.
    pub fn has_node(&self, id: u32) -> bool {
        self.nodes.binary_search_by_key(&id, |n| n.id).is_ok()
    }

    /// Whether a link `from → to` exists (enabled or not).
    pub fn has_link(&self, from: u32, to: u32) -> bool {
        self.links.iter().any(|l| l.from == from && l.to == to)
    }

    /// Inserts a node keeping the id order.
    pub(crate) fn insert_node(&mut self, node: NodeGene) {
        let pos = self.nodes.partition_point(|n| n.id < node.id);
        self.nodes.insert(pos, node);
    }

    /// Inserts a link keeping the innovation order.
    pub(crate) fn insert_link(&mut self, link: LinkGene) {
        let pos = self
            .links
            .partition_point(|l| l.innovation < link.innovation);
        self.links.insert(pos, link);
    }

    /// Whether `target` is reachable from `start` along any link (enabled or not).
    ///
    /// Feed-forward genomes consider disabled links too, so that re-enabling a link
    /// (toggle or crossover) can never close a cycle.
    pub(crate) fn reaches(&self, start: u32, target: u32) -> bool {
        if start == target {
            return true;
        }
        // Visited marks by node position (nodes are sorted by id); a link to
        // an id that is not a node cannot lead anywhere further.
        let position = |id: u32| self.nodes.binary_search_by_key(&id, |n| n.id).ok();
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![start];
        while let Some(n) = stack.pop() {
            for l in self.links.iter().filter(|l| l.from == n) {
                if l.to == target {
                    return true;
                }
                if let Some(p) = position(l.to)
                    && !seen[p]
                {
                    seen[p] = true;
                    stack.push(l.to);
                }
            }
        }
        false
    }

    /// Checks the structural invariants: sorted unique node ids and innovations,
    /// no duplicate `(from, to)`, every link's nodes exist, no link into an
    /// input, finite weights.
    pub fn check(&self) -> Result<(), GenomeError> {
        for w in self.nodes.windows(2) {
            if w[0].id == w[1].id {
                return Err(GenomeError::DuplicateNode(w[1].id));
            }
            if w[0].id > w[1].id {
                return Err(GenomeError::NodeOrder(w[1].id));
            }
        }
        for w in self.links.windows(2) {
            if w[0].innovation == w[1].innovation {
                return Err(GenomeError::DuplicateInnovation(w[1].innovation));
            }
            if w[0].innovation > w[1].innovation {
                return Err(GenomeError::InnovationOrder(w[1].innovation));
            }
        }
        let mut pairs = BTreeSet::new();
        for l in &self.links {
            if !pairs.insert((l.from, l.to)) {
                return Err(GenomeError::DuplicateLink {
                    from: l.from,
                    to: l.to,
                });
            }
            let (Some(_), Some(to)) = (self.node(l.from), self.node(l.to)) else {
                return Err(GenomeError::MissingNode {
                    innovation: l.innovation,
                    from: l.from,
                    to: l.to,
                });
            };
            if to.kind == NodeKind::Input {
                return Err(GenomeError::LinkIntoInput {
                    innovation: l.innovation,
                    to: l.to,
                });
            }
            if !l.weight.is_finite() {
                return Err(GenomeError::NonFiniteWeight {
                    innovation: l.innovation,
                });
            }
        }
        Ok(())
    }
}

/// A uniform random weight in `[-r, r]`, `r = min(initial range, amplitude)`.
pub(crate) fn random_weight<R: Rng + ?Sized>(params: &NeatParams, rng: &mut R) -> f64 {
    let r = params.initial_weight_range.min(params.weight_amplitude);
    (rng.random::<f64>() * 2.0 - 1.0) * r
}

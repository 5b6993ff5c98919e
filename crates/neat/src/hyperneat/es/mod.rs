//! ES-HyperNEAT (Risi & Stanley 2012): the CPPN decides where hidden
//! neurons go and how many there are.
//!
//! Around each node the substrate plane `[−1, 1]²` is cut into a quadtree,
//! finer where the CPPN's weight pattern from (or to) that node varies
//! ([`EsParams::initial_depth`], [`EsParams::max_depth`],
//! [`EsParams::division_threshold`]). Pruning then keeps the points that lie
//! on a *band* — where the pattern differs from the neighbours on both sides
//! ([`EsParams::variance_threshold`], [`EsParams::band_threshold`]) — and
//! each such point expresses a link and becomes a hidden neuron. Discovery
//! runs outward from the inputs, then [`EsParams::iteration_level`] times
//! from the hidden neurons just found, and finally inward to the outputs
//! (from known nodes only); hidden neurons not on a path from an input to an
//! output are dropped with their links. Without [`EsParams::recurrent`]
//! every link goes one way along y ([`EsParams::flow`]: upward, source y <
//! target y, unless the outputs sit below the inputs), so the network is
//! feed-forward.
//!
//! Weights use the plain HyperNEAT expression rule ([`EsParams::expression`]),
//! or LEO when [`EsLayout::leo_output`] is set ([`express_link`](super::express_link)).
//! The result is a [`SparseNetwork`].
//!
//! [`decode_es`] is the reference: the paper's recursive algorithms, one CPPN
//! query at a time, over any [`Network`]. [`decode_es_genome`] builds each
//! quadtree level by level and batches its queries through [`BatchCppn`]; a
//! test proves both give the same network bit for bit.

mod discover;
mod fast;
mod params;
mod query;
mod reference;

use serde::{Deserialize, Serialize};

pub use params::{EsParams, Flow, MAX_DEPTH, MAX_ITERATION_LEVEL};

use super::batch::BatchCppn;
use super::error::HyperError;
use super::layout::{CPPN_INPUTS, check_finite, check_link_outputs};
use super::sparse::SparseNetwork;
use crate::feedforward::FeedForwardNetwork;
use crate::genome::Genome;
use crate::network::Network;
use discover::discover;
use query::{Exploration, Found, OneByOne};

/// The fixed part of an ES-HyperNEAT substrate: input and output positions
/// and which CPPN outputs give weights, biases and link expression.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EsLayout {
    /// Input node positions, in network-input order.
    pub inputs: Vec<[f64; 2]>,
    /// Output node positions, in network-output order.
    pub outputs: Vec<[f64; 2]>,
    /// CPPN output giving link weights (queried target first, then source).
    pub weight_output: usize,
    /// CPPN output giving output and hidden biases (queried with source (0, 0)); none if
    /// `None` (or absent: a missing `Option` field reads as `None`).
    pub bias_output: Option<usize>,
    /// CPPN output for LEO: a link exists iff it is > 0; `None` (or absent): the weight
    /// threshold decides.
    pub leo_output: Option<usize>,
}

impl EsLayout {
    /// Checks output indices against the CPPN's, and that positions are
    /// finite, distinct and that there is at least one output.
    pub fn check(&self, cppn_outputs: usize) -> Result<(), HyperError> {
        if self.outputs.is_empty() {
            return Err(HyperError::NoNeurons);
        }
        let outputs = (self.weight_output, self.bias_output, self.leo_output);
        check_link_outputs(outputs, cppn_outputs)?;
        let nodes = self.inputs.iter().map(|c| ("input", c));
        let nodes = nodes.chain(self.outputs.iter().map(|c| ("output", c)));
        check_finite(nodes.clone())?;
        let mut seen = std::collections::BTreeSet::new();
        for (_, c) in nodes {
            if !seen.insert([(c[0] + 0.0).to_bits(), (c[1] + 0.0).to_bits()]) {
                return Err(HyperError::Inconsistent(
                    "two input/output nodes at one position",
                ));
            }
        }
        Ok(())
    }
}

/// Decodes `cppn` into an ES-HyperNEAT network: the reference implementation,
/// one query at a time (works with any network, stateful or not).
pub fn decode_es(
    cppn: &mut impl Network,
    layout: &EsLayout,
    params: &EsParams,
) -> Result<SparseNetwork, HyperError> {
    if cppn.num_inputs() != CPPN_INPUTS {
        return Err(HyperError::CppnInputs(cppn.num_inputs()));
    }
    let mut q = OneByOne::new(cppn);
    let (output, p) = (layout.weight_output, params);
    discover(
        &mut q,
        layout,
        params,
        |q, fixed, found: &mut Vec<Found>| {
            reference::explore(
                &mut Exploration {
                    q,
                    output,
                    fixed,
                    p,
                },
                found,
            )
        },
    )
}

/// Decodes a CPPN genome: batched queries ([`BatchCppn`]) for acyclic
/// genomes, [`decode_es`] with a [`FeedForwardNetwork`] otherwise. The result
/// equals `decode_es(&mut FeedForwardNetwork::from_genome(genome), ..)`.
pub fn decode_es_genome(
    genome: &Genome,
    layout: &EsLayout,
    params: &EsParams,
) -> Result<SparseNetwork, HyperError> {
    let Some(mut cppn) = BatchCppn::new(genome) else {
        return decode_es(&mut FeedForwardNetwork::from_genome(genome), layout, params);
    };
    if cppn.num_inputs() != CPPN_INPUTS {
        return Err(HyperError::CppnInputs(cppn.num_inputs()));
    }
    let mut explorer = fast::Explorer::default();
    let (output, p) = (layout.weight_output, params);
    discover(
        &mut cppn,
        layout,
        params,
        |q, fixed, found: &mut Vec<Found>| {
            explorer.explore(
                &mut Exploration {
                    q,
                    output,
                    fixed,
                    p,
                },
                found,
            )
        },
    )
}

#[cfg(test)]
mod tests;

//! Genes written out by hand, for the unit tests' small genomes.

use crate::activation::Activation;
use crate::genome::{LinkGene, NodeGene, NodeKind};

/// A node gene.
pub(crate) fn node(id: u32, kind: NodeKind, activation: Activation) -> NodeGene {
    NodeGene {
        id,
        kind,
        activation,
    }
}

/// A link gene, enabled or not.
pub(crate) fn link_if(innovation: u32, from: u32, to: u32, weight: f64, enabled: bool) -> LinkGene {
    LinkGene {
        innovation,
        from,
        to,
        weight,
        enabled,
    }
}

/// An enabled link gene.
pub(crate) fn link(innovation: u32, from: u32, to: u32, weight: f64) -> LinkGene {
    link_if(innovation, from, to, weight, true)
}

//! Genes written out by hand, and grown genomes, for the unit tests.

use rand::Rng;

use crate::activation::Activation;
use crate::genome::{Genome, GenomeSpec, LinkGene, NodeGene, NodeKind};
use crate::innovation::InnovationTracker;
use crate::mutation::{mutate_add_link, mutate_add_node, mutate_toggle_enable};
use crate::params::NeatParams;

/// A minimal genome of `spec` grown by `rounds` rounds of add-node, add-link
/// and toggle-a-link mutations.
pub(crate) fn grown<R: Rng>(
    spec: &GenomeSpec,
    params: &NeatParams,
    tracker: &mut InnovationTracker,
    rng: &mut R,
    rounds: usize,
) -> Genome {
    let mut g = Genome::minimal(spec, params, tracker, rng);
    for _ in 0..rounds {
        mutate_add_node(&mut g, spec, tracker, rng);
        mutate_add_link(&mut g, spec, params, tracker, rng);
        mutate_toggle_enable(&mut g, rng);
    }
    g
}

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

/// A genome written out in one line per part: `nodes` as
/// `"id kind activation, ..."` (serde's snake_case names, e.g.
/// `"0 input linear, 2 output bipolar_sigmoid"`), `links` as
/// `"innovation: from -> to weight, ..."`, a link followed by `off` disabled.
pub(crate) fn genome(nodes: &str, links: &str) -> Genome {
    let name = |s: &str| format!("\"{s}\"");
    let nodes = nodes.split(',').map(|n| {
        let [id, kind, act] = words(n);
        let kind: NodeKind = serde_json::from_str(&name(kind)).expect("a node kind");
        let act: Activation = serde_json::from_str(&name(act)).expect("an activation");
        node(id.parse().expect("a node id"), kind, act)
    });
    let links = links.split(',').map(|l| {
        let l = l.replace([':'], " ").replace("->", " ");
        let enabled = !l.trim_end().ends_with("off");
        let [innovation, from, to, weight] = words(l.trim_end().trim_end_matches("off"));
        let int = |s: &str| s.parse().expect("an innovation or node id");
        link_if(
            int(innovation),
            int(from),
            int(to),
            weight.parse().expect("a weight"),
            enabled,
        )
    });
    Genome::from_parts(nodes.collect(), links.collect()).expect("a valid genome")
}

/// The `N` words of `s`.
fn words<const N: usize>(s: &str) -> [&str; N] {
    let words: Vec<&str> = s.split_whitespace().collect();
    words
        .try_into()
        .unwrap_or_else(|w| panic!("{N} words expected: {w:?}"))
}

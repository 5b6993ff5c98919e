//! Add-node: splitting an enabled link.

use rand::{Rng, RngExt};

use crate::genome::{Genome, GenomeSpec, LinkGene, NodeGene, NodeKind};
use crate::innovation::InnovationTracker;

/// Splits a random enabled link `a → b` into `a → n` (weight 1) and `n → b` (the old
/// weight), disabling the original; `n` gets a random function from the spec.
/// Returns false when the genome has no enabled link.
pub fn mutate_add_node<R: Rng + ?Sized>(
    genome: &mut Genome,
    spec: &GenomeSpec,
    tracker: &mut InnovationTracker,
    rng: &mut R,
) -> bool {
    let enabled = genome.links.iter().filter(|l| l.enabled).count();
    if enabled == 0 {
        return false;
    }
    let pick = rng.random_range(0..enabled);
    let idx = genome
        .links
        .iter()
        .enumerate()
        .filter(|(_, l)| l.enabled)
        .nth(pick)
        .map(|(i, _)| i)
        .expect("pick < enabled count");
    let old = genome.links[idx];
    genome.links[idx].enabled = false;
    let id = tracker.split_node(old.innovation, |id| genome.has_node(id));
    let activation = spec.hidden_activations[rng.random_range(0..spec.hidden_activations.len())];
    genome.insert_node(NodeGene {
        id,
        kind: NodeKind::Hidden,
        activation,
    });
    genome.insert_link(LinkGene {
        innovation: tracker.link_innovation(old.from, id),
        from: old.from,
        to: id,
        weight: 1.0,
        enabled: true,
    });
    genome.insert_link(LinkGene {
        innovation: tracker.link_innovation(id, old.to),
        from: id,
        to: old.to,
        weight: old.weight,
        enabled: true,
    });
    true
}

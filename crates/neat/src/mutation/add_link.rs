//! Add-link: connecting two unconnected nodes (feed-forward or, where allowed, recurrent).

use rand::{Rng, RngExt};

use crate::genome::{Genome, GenomeSpec, LinkGene, NodeKind, random_weight};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;

/// Adds a link between a random unconnected pair, trying `add_link_attempts` times.
/// Without `allow_recurrent` the source is never an output and the link must not close
/// a cycle. Returns false when no pair was found.
pub fn mutate_add_link<R: Rng + ?Sized>(
    genome: &mut Genome,
    spec: &GenomeSpec,
    params: &NeatParams,
    tracker: &mut InnovationTracker,
    rng: &mut R,
) -> bool {
    let n = genome.nodes.len();
    for _ in 0..params.add_link_attempts {
        let from = genome.nodes[rng.random_range(0..n)];
        let to = genome.nodes[rng.random_range(0..n)];
        if to.kind == NodeKind::Input {
            continue;
        }
        // Both tests only reject (no randomness is drawn), so the cheap one
        // goes first.
        if genome.has_link(from.id, to.id) {
            continue;
        }
        if !spec.allow_recurrent
            && (from.kind == NodeKind::Output || genome.reaches(to.id, from.id))
        {
            continue;
        }
        let link = LinkGene {
            innovation: tracker.link_innovation(from.id, to.id),
            from: from.id,
            to: to.id,
            weight: random_weight(params, rng),
            enabled: true,
        };
        genome.insert_link(link);
        return true;
    }
    false
}

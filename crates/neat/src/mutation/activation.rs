//! Changing the activation function of a hidden node (CPPN node-function mutation).

use rand::{Rng, RngExt};

use crate::genome::{Genome, GenomeSpec, NodeKind};

/// Gives one random hidden node a different function from `spec.hidden_activations`.
/// Returns false when there is no hidden node or only one allowed function.
pub fn mutate_activation<R: Rng + ?Sized>(
    genome: &mut Genome,
    spec: &GenomeSpec,
    rng: &mut R,
) -> bool {
    let hidden = genome
        .nodes
        .iter()
        .filter(|n| n.kind == NodeKind::Hidden)
        .count();
    if hidden == 0 || spec.hidden_activations.len() < 2 {
        return false;
    }
    let pick = rng.random_range(0..hidden);
    let node = genome
        .nodes
        .iter_mut()
        .filter(|n| n.kind == NodeKind::Hidden)
        .nth(pick)
        .expect("pick < hidden count");
    let others: Vec<_> = spec
        .hidden_activations
        .iter()
        .copied()
        .filter(|&a| a != node.activation)
        .collect();
    if others.is_empty() {
        return false;
    }
    node.activation = others[rng.random_range(0..others.len())];
    true
}

//! Mutation operators, one file each, and the per-offspring mutation schedule.

mod activation;
mod add_link;
mod add_node;
mod toggle_enable;
mod weights;

pub use activation::mutate_activation;
pub use add_link::mutate_add_link;
pub use add_node::mutate_add_node;
pub use toggle_enable::mutate_toggle_enable;
pub use weights::{gaussian, mutate_weights};

use rand::{Rng, RngExt};

use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;

/// Applies Stanley's schedule: a structural mutation (add-node, else add-link) or,
/// failing both rolls, the non-structural ones (weights, toggle, activation).
pub fn mutate<R: Rng + ?Sized>(
    genome: &mut Genome,
    spec: &GenomeSpec,
    params: &NeatParams,
    tracker: &mut InnovationTracker,
    rng: &mut R,
) {
    if rng.random_bool(params.add_node_probability) {
        mutate_add_node(genome, spec, tracker, rng);
    } else if rng.random_bool(params.add_link_probability) {
        mutate_add_link(genome, spec, params, tracker, rng);
    } else {
        if rng.random_bool(params.weight_mutation_probability) {
            mutate_weights(genome, params, rng);
        }
        if rng.random_bool(params.toggle_enable_probability) {
            mutate_toggle_enable(genome, rng);
        }
        if rng.random_bool(params.activation_mutation_probability) {
            mutate_activation(genome, spec, rng);
        }
    }
}

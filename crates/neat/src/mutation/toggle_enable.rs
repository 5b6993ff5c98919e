//! Toggling one link's enabled flag.

use rand::{Rng, RngExt};

use crate::genome::Genome;

/// Flips the enabled flag of one random link. Feed-forward genomes stay acyclic
/// because add-link checks cycles over disabled links too.
pub fn mutate_toggle_enable<R: Rng + ?Sized>(genome: &mut Genome, rng: &mut R) -> bool {
    if genome.links.is_empty() {
        return false;
    }
    let i = rng.random_range(0..genome.links.len());
    genome.links[i].enabled = !genome.links[i].enabled;
    true
}

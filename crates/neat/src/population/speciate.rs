//! Speciation: each genome joins the first species whose representative is
//! within the compatibility threshold, or founds a new one.

use rand::RngExt;

use crate::distance::{Compatibility, GeneTable};
use crate::genome::Genome;
use crate::species::Species;

use super::Population;

impl Population {
    /// Assigns `genomes` to species: each joins the first species whose representative
    /// (a random member of `old`, or the stored one) is within the threshold, else founds
    /// a new species. Empty species are dropped.
    pub(super) fn speciate(&mut self, genomes: &[Genome], old: &[Genome]) {
        for s in &mut self.species {
            if !old.is_empty() && !s.members.is_empty() {
                let m = s.members[self.rng.random_range(0..s.members.len())];
                s.representative = old[m].clone();
            }
            s.members.clear();
        }
        // Every genome meets many representatives: lay each out once (the
        // representatives in one table, the genome being placed in another).
        let compatible = Compatibility::new(&self.params, self.threshold);
        let mut reps = GeneTable::new();
        for s in &self.species {
            reps.push(&s.representative, &self.params);
        }
        let mut this = GeneTable::new();
        for (i, g) in genomes.iter().enumerate() {
            this.clear();
            this.push(g, &self.params);
            let found =
                (0..self.species.len()).find(|&k| compatible.within(this.view(0), reps.view(k)));
            match found {
                Some(k) => self.species[k].members.push(i),
                None => {
                    reps.push(g, &self.params);
                    self.species.push(Species {
                        id: self.next_species_id,
                        representative: g.clone(),
                        members: vec![i],
                        created: self.generation + u32::from(!old.is_empty()),
                        best_fitness: None,
                        last_improved: self.generation + u32::from(!old.is_empty()),
                    });
                    self.next_species_id += 1;
                }
            }
        }
        self.species.retain(|s| !s.members.is_empty());
    }
}

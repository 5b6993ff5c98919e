//! Reproduction: the next generation from the evaluated one (species
//! stagnation, fitness sharing, offspring allocation, elitism, crossover and
//! mutation), then speciation.

use rand::RngExt;

use std::cell::RefCell;

use crate::crossover::crossover_into;
use crate::genome::Genome;
use crate::mutation::mutate;
use crate::species::Species;
use crate::stats::argmax;

use super::Population;

impl Population {
    /// Produces the next generation: species stagnation, explicit fitness sharing,
    /// offspring allocation, elitism, crossover and mutation, then speciation.
    /// Genomes never evaluated count as fitness 0.
    pub fn next_generation(&mut self) {
        let fitness = self
            .fitness
            .take()
            .unwrap_or_else(|| vec![0.0; self.genomes.len()]);
        let champion = argmax(&fitness).unwrap_or(0);
        let refocus = self.refocus_due();
        self.update_species_records(&fitness, champion);
        let champ_species = self
            .species
            .iter()
            .position(|s| s.members.contains(&champion));
        let alloc = if refocus {
            self.refocused = Some(self.generation);
            self.refocus_allocation(&fitness)
        } else {
            self.allocate(&fitness, champ_species)
        };
        let next = self.reproduce(&fitness, &alloc, champ_species, refocus);

        // Speciate the new generation against representatives of the old one.
        let old = std::mem::take(&mut self.genomes);
        self.speciate(&next, &old);
        self.genomes = next;
        retire(old);
        self.generation += 1;
        self.adjust_threshold();
    }

    /// Species records and stagnation: updates each species' best fitness,
    /// then drops the species stagnant for `stagnation_limit` generations
    /// (never the champion's).
    fn update_species_records(&mut self, fitness: &[f64], champion: usize) {
        let generation = self.generation;
        for s in &mut self.species {
            let best = s
                .members
                .iter()
                .map(|&m| fitness[m])
                .fold(f64::NEG_INFINITY, f64::max);
            if s.best_fitness.is_none_or(|b| best > b) {
                s.best_fitness = Some(best);
                s.last_improved = generation;
            }
        }
        let limit = self.params.stagnation_limit;
        self.species
            .retain(|s| s.members.contains(&champion) || s.stagnation(generation) < limit);
    }

    /// Whether the population's best fitness has not risen for
    /// `population_stagnation_limit` generations (counted from the last
    /// refocus, if later).
    fn refocus_due(&self) -> bool {
        let (Some(limit), Some(best)) = (self.params.population_stagnation_limit, &self.best_ever)
        else {
            return false;
        };
        let since = best.generation.max(self.refocused.unwrap_or(0));
        self.generation.saturating_sub(since) >= limit
    }

    /// Stanley's delta coding: the two species with the best members get half
    /// the population each (the best one all of it when it is alone), every
    /// other species none; the two count as improved now, so that species
    /// stagnation does not remove them next.
    fn refocus_allocation(&mut self, fitness: &[f64]) -> Vec<usize> {
        let best = |s: &Species| {
            s.members
                .iter()
                .map(|&m| fitness[m])
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let mut order: Vec<usize> = (0..self.species.len()).collect();
        order.sort_by(|&a, &b| {
            best(&self.species[b])
                .total_cmp(&best(&self.species[a]))
                .then(a.cmp(&b))
        });
        let mut alloc = vec![0; self.species.len()];
        let total = self.params.population_size;
        match order[..] {
            [] => {}
            [only] => alloc[only] = total,
            [first, second, ..] => {
                alloc[first] = total / 2;
                alloc[second] = total - total / 2;
            }
        }
        for &k in order.iter().take(2) {
            self.species[k].last_improved = self.generation;
        }
        alloc
    }

    /// Offspring per species: explicit fitness sharing, then at least one
    /// child for the champion's species (taken from the largest allocation).
    fn allocate(&self, fitness: &[f64], champ_species: Option<usize>) -> Vec<usize> {
        // Explicit fitness sharing: a species' share is the sum of its members' f/|S|,
        // i.e. its mean fitness. Negative fitness is shifted so that the lowest is 0.
        let min = fitness.iter().copied().fold(0.0, f64::min);
        let shares: Vec<f64> = self
            .species
            .iter()
            .map(|s| {
                s.members.iter().map(|&m| fitness[m] - min).sum::<f64>() / s.members.len() as f64
            })
            .collect();
        let mut alloc = allocate_offspring(&shares, self.params.population_size);
        if let Some(c) = champ_species
            && alloc[c] == 0
            && let Some(donor) = (0..alloc.len()).max_by_key(|&i| (alloc[i], usize::MAX - i))
        {
            alloc[donor] -= 1;
            alloc[c] += 1;
        }
        alloc
    }

    /// Reproduction, species by species: each species' elites, then
    /// `alloc[si]` children in all bred from its best members (when
    /// `refocus`: one copy of its champion, then mutated copies of it).
    fn reproduce(
        &mut self,
        fitness: &[f64],
        alloc: &[usize],
        champ_species: Option<usize>,
        refocus: bool,
    ) -> Vec<Genome> {
        let mut next: Vec<Genome> = Vec::with_capacity(self.params.population_size);
        // Each species' members, best first.
        let pools: Vec<Vec<usize>> = self
            .species
            .iter()
            .map(|s| {
                let mut sorted = s.members.clone();
                sorted.sort_by(|&a, &b| fitness[b].total_cmp(&fitness[a]).then(a.cmp(&b)));
                sorted
            })
            .collect();
        for (si, sorted) in pools.iter().enumerate() {
            let n_off = alloc[si];
            if n_off == 0 {
                continue;
            }
            let len = sorted.len();
            let elites = if refocus {
                1
            } else {
                self.elites(len, Some(si) == champ_species).min(n_off)
            };
            for &m in &sorted[..elites] {
                next.push(copy_of(&self.genomes[m]));
            }
            if refocus {
                for _ in elites..n_off {
                    let mut child = copy_of(&self.genomes[sorted[0]]);
                    mutate(
                        &mut child,
                        &self.spec,
                        &self.params,
                        &mut self.tracker,
                        &mut self.rng,
                    );
                    next.push(child);
                }
                continue;
            }
            let keep =
                ((self.params.survival_threshold * len as f64).ceil() as usize).clamp(1, len);
            let pool = &sorted[..keep];
            for _ in elites..n_off {
                let child = self.offspring(pool, si, &pools, fitness);
                next.push(child);
            }
        }
        next
    }

    /// How many of a species of `len` members are copied unchanged (before
    /// capping at its offspring count): at least one for the champion's.
    fn elites(&self, len: usize, has_champion: bool) -> usize {
        let elites = if len >= self.params.elitism_min_species_size {
            (self.params.elitism_fraction * len as f64).ceil() as usize
        } else {
            0
        };
        if has_champion { elites.max(1) } else { elites }
    }

    /// Moves the compatibility threshold towards `target_species`, if set.
    fn adjust_threshold(&mut self) {
        if let Some(target) = self.params.target_species {
            let n = self.species.len();
            if n < target {
                self.threshold =
                    (self.threshold - self.params.threshold_step).max(self.params.threshold_min);
            } else if n > target {
                self.threshold += self.params.threshold_step;
            }
        }
    }

    /// One child of species `si` bred from `pool` (its best members).
    fn offspring(
        &mut self,
        pool: &[usize],
        si: usize,
        pools: &[Vec<usize>],
        fitness: &[f64],
    ) -> Genome {
        let params = &self.params;
        let rng = &mut self.rng;
        let a = pool[rng.random_range(0..pool.len())];
        let mut child = if rng.random_bool(params.mating_probability) {
            let interspecies =
                pools.len() > 1 && rng.random_bool(params.interspecies_mating_probability);
            let b = if interspecies {
                let mut other = rng.random_range(0..pools.len() - 1);
                if other >= si {
                    other += 1;
                }
                let p = &pools[other];
                let top = ((params.survival_threshold * p.len() as f64).ceil() as usize)
                    .clamp(1, p.len());
                Some(p[rng.random_range(0..top)])
            } else if pool.len() > 1 {
                let mut b = pool[rng.random_range(0..pool.len() - 1)];
                if b == a {
                    b = pool[pool.len() - 1];
                }
                Some(b)
            } else {
                None
            };
            match b {
                Some(b) => {
                    let mut c = recycled();
                    let parents = [
                        (&self.genomes[a], fitness[a]),
                        (&self.genomes[b], fitness[b]),
                    ];
                    crossover_into(parents, params, rng, &mut c);
                    if rng.random_bool(params.mate_only_probability) {
                        return c;
                    }
                    c
                }
                None => copy_of(&self.genomes[a]),
            }
        } else {
            copy_of(&self.genomes[a])
        };
        mutate(&mut child, &self.spec, params, &mut self.tracker, rng);
        child
    }
}

/// The most retired genomes a thread keeps for their memory.
const RETIRED_MAX: usize = 4096;

thread_local! {
    /// Genomes of generations gone by, kept for their memory: a generation's
    /// offspring are written into them, so breeding allocates nothing once
    /// a population has bred twice (allocating and freeing each child's two
    /// arrays was a tenth of a run whose evaluations are a microsecond).
    static RETIRED: RefCell<Vec<Genome>> = const { RefCell::new(Vec::new()) };
}

/// Keeps the genomes of a generation gone by for their memory (up to [`RETIRED_MAX`]).
fn retire(old: Vec<Genome>) {
    RETIRED.with_borrow_mut(|r| {
        let room = RETIRED_MAX.saturating_sub(r.len());
        r.extend(old.into_iter().take(room));
    });
}

/// A retired genome to overwrite, or a new empty one.
fn recycled() -> Genome {
    RETIRED
        .with_borrow_mut(Vec::pop)
        .unwrap_or_else(Genome::empty)
}

/// A copy of `g`, in a retired genome's memory when there is one.
fn copy_of(g: &Genome) -> Genome {
    let mut copy = recycled();
    copy.clone_from(g);
    copy
}

/// Splits `total` offspring among species in proportion to `shares` (largest remainder,
/// ties to the earlier species); always sums exactly to `total`. All-zero shares split
/// evenly.
pub fn allocate_offspring(shares: &[f64], total: usize) -> Vec<usize> {
    if shares.is_empty() {
        return Vec::new();
    }
    let sum: f64 = shares.iter().filter(|s| s.is_finite() && **s > 0.0).sum();
    let quotas: Vec<f64> = if sum > 0.0 {
        shares
            .iter()
            .map(|&s| {
                if s.is_finite() && s > 0.0 {
                    s / sum * total as f64
                } else {
                    0.0
                }
            })
            .collect()
    } else {
        vec![total as f64 / shares.len() as f64; shares.len()]
    };
    let mut alloc: Vec<usize> = quotas.iter().map(|q| q.floor() as usize).collect();
    let assigned: usize = alloc.iter().sum();
    let mut rest = total.saturating_sub(assigned);
    let mut order: Vec<usize> = (0..shares.len()).collect();
    order.sort_by(|&a, &b| {
        let ra = quotas[a] - quotas[a].floor();
        let rb = quotas[b] - quotas[b].floor();
        rb.total_cmp(&ra).then(a.cmp(&b))
    });
    let mut k = 0;
    while rest > 0 {
        alloc[order[k % order.len()]] += 1;
        rest -= 1;
        k += 1;
    }
    // Floating error could over-assign by one; take it back from the largest.
    while alloc.iter().sum::<usize>() > total {
        let i = (0..alloc.len()).max_by_key(|&i| alloc[i]).unwrap_or(0);
        alloc[i] -= 1;
    }
    alloc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::GenomeSpec;
    use crate::params::NeatParams;

    #[test]
    fn breeding_into_retired_genomes_is_invisible() {
        let params = NeatParams {
            population_size: 40,
            ..NeatParams::plain_neat()
        };
        let spec = GenomeSpec::plain(3, 2);
        fn fitness(g: &Genome, _: crate::EvalContext) -> f64 {
            g.links().iter().map(|l| l.weight.abs()).sum::<f64>() + g.num_hidden() as f64
        }
        fn evolve(pops: &mut [Population]) {
            for _ in 0..15 {
                for p in pops.iter_mut() {
                    p.evaluate(fitness);
                    p.next_generation();
                }
            }
        }
        // Alone, on a thread whose pool starts empty.
        let alone = std::thread::spawn({
            let (params, spec) = (params.clone(), spec.clone());
            move || {
                let mut p = [Population::new(params, spec, 9).unwrap()];
                evolve(&mut p);
                p[0].to_json().unwrap()
            }
        })
        .join()
        .unwrap();
        // Beside another population, each breeding into genomes the other retired.
        let mut both = [
            Population::new(params.clone(), spec.clone(), 9).unwrap(),
            Population::new(params, spec, 4).unwrap(),
        ];
        evolve(&mut both);
        assert_eq!(both[0].to_json().unwrap(), alone);
        assert!(RETIRED.with_borrow(|r| !r.is_empty()));
    }

    #[test]
    fn allocation_sums_exactly() {
        assert_eq!(allocate_offspring(&[1.0, 1.0, 1.0], 100), vec![34, 33, 33]);
        assert_eq!(allocate_offspring(&[0.0, 0.0], 5), vec![3, 2]);
        assert_eq!(allocate_offspring(&[3.0, 1.0], 8), vec![6, 2]);
        assert_eq!(allocate_offspring(&[], 8), Vec::<usize>::new());
    }

    /// Parameters under which a mutated copy is an exact copy.
    fn frozen(limit: Option<u32>) -> NeatParams {
        NeatParams {
            population_size: 40,
            compatibility_threshold: 0.5,
            add_node_probability: 0.0,
            add_link_probability: 0.0,
            weight_mutation_probability: 0.0,
            toggle_enable_probability: 0.0,
            activation_mutation_probability: 0.0,
            population_stagnation_limit: limit,
            ..NeatParams::plain_neat()
        }
    }

    #[test]
    fn population_stagnation_refocuses_on_two_champions() {
        let mut pop = Population::new(frozen(Some(2)), GenomeSpec::plain(3, 1), 7).unwrap();
        // Constant fitness: the best never rises after generation 0.
        for _ in 0..2 {
            pop.evaluate(|_, _| 1.0);
            assert!(pop.species().len() >= 2, "the test needs two species");
            pop.next_generation();
        }
        assert_eq!(pop.refocused, None);
        pop.evaluate(|_, _| 1.0);
        let champions: Vec<Genome> = pop.species()[..2]
            .iter()
            .map(|s| pop.genomes()[s.members[0]].clone())
            .collect();
        pop.next_generation();
        assert_eq!(pop.refocused, Some(2));
        for (k, champion) in champions.iter().enumerate() {
            let copies = pop.genomes().iter().filter(|g| *g == champion).count();
            assert_eq!(copies, 20, "champion {k}");
        }
        // The refocus survives a checkpoint; one dated after the current generation is refused.
        let json = pop.to_json().unwrap();
        assert_eq!(Population::from_json(&json).unwrap(), pop);
        let future = json.replace("\"refocused\":2", "\"refocused\":99");
        assert_ne!(future, json);
        let e = Population::from_json(&future).unwrap_err().to_string();
        assert!(e.contains("refocused") && e.contains("99"), "{e}");
    }

    #[test]
    fn without_population_stagnation_limit_nothing_is_refocused_or_written() {
        let mut pop = Population::new(frozen(None), GenomeSpec::plain(3, 1), 7).unwrap();
        for _ in 0..30 {
            pop.evaluate(|_, _| 1.0);
            pop.next_generation();
        }
        assert_eq!(pop.refocused, None);
        let json = pop.to_json().unwrap();
        assert!(!json.contains("refocused") && !json.contains("population_stagnation_limit"));
    }
}

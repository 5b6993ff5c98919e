//! The XOR task (Stanley & Miikkulainen 2002, "Evolving neural networks
//! through augmenting topologies", Evolutionary Computation 10(2), Sec. 4.2, p. 112):
//! population 150, fitness (4 − Σ|error|)², solved when all four outputs are
//! on the right side of 0.5; evaluations counted up to and including the
//! first genome that solves (as if evaluated one by one).

use crate::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Population};

/// The four cases as lanes: `INPUTS[i][case]` is input `i` (the last is the
/// bias) of case `case`, `TARGETS[case]` its target.
const INPUTS: [[f64; 4]; 3] = [[0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 0.0, 1.0], [1.0; 4]];
const TARGETS: [f64; 4] = [0.0, 1.0, 1.0, 0.0];

/// The task's fitness of `g` and whether all four cases are on the right
/// side of 0.5; `net` is any network, recompiled for `g` in place, and
/// `scratch` its lane values (no allocation per genome). The four cases run
/// as lanes of one pass: the same bits as four activations, their activation
/// functions overlapping.
pub fn score(net: &mut FeedForwardNetwork, scratch: &mut Vec<[f64; 4]>, g: &Genome) -> (f64, bool) {
    net.recompile(g);
    let mut out = [[0.0; 4]];
    net.activate_lanes(&INPUTS, &mut out, scratch);
    let mut err = 0.0;
    let mut solved = true;
    for (&y, target) in out[0].iter().zip(TARGETS) {
        err += (y - target).abs();
        solved &= (y > 0.5) == (target > 0.5);
    }
    ((4.0 - err).powi(2), solved)
}

/// One XOR run: `(evaluations until the first solving genome, its hidden
/// nodes)`, or `None` when unsolved after `max_generations`.
pub fn run_xor(params: &NeatParams, seed: u64, max_generations: u32) -> Option<(usize, usize)> {
    run_xor_observed(params, seed, max_generations, |_| {})
}

/// [`run_xor`], telling `observe` each generation's population once its
/// fitnesses are set (the example's `XOR_TRACE`).
pub fn run_xor_observed(
    params: &NeatParams,
    seed: u64,
    max_generations: u32,
    mut observe: impl FnMut(&Population),
) -> Option<(usize, usize)> {
    let mut pop =
        Population::new(params.clone(), GenomeSpec::plain(3, 1), seed).expect("valid parameters");
    let mut net = FeedForwardNetwork::from_genome(&pop.genomes()[0]);
    let mut scratch = Vec::new();
    for _ in 0..max_generations {
        // One network per genome gives both its fitness and whether it solves;
        // evaluated in order on this thread (150 tiny networks are far too
        // little work to be worth waking a thread pool for).
        let mut fitness = Vec::with_capacity(pop.genomes().len());
        let mut first_solver = None;
        for (i, g) in pop.genomes().iter().enumerate() {
            let (f, solved) = score(&mut net, &mut scratch, g);
            fitness.push(f);
            if solved && first_solver.is_none() {
                first_solver = Some(i);
            }
        }
        pop.set_fitnesses(fitness).expect("one fitness per genome");
        observe(&pop);
        if let Some(i) = first_solver {
            // Evaluations counted as if genomes were evaluated one by one.
            let gen_evals = pop.generation() as usize * pop.params().population_size;
            return Some((gen_evals + i + 1, pop.genomes()[i].num_hidden()));
        }
        pop.next_generation();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_neat_solves_xor_and_counts_evaluations_up_to_the_solver() {
        let (evals, hidden) = run_xor(&NeatParams::plain_neat(), 1, 500).expect("seed 1 solves");
        assert!(evals > 150 && hidden >= 1, "{evals} {hidden}");
        let mut generations = 0;
        let again = run_xor_observed(&NeatParams::plain_neat(), 1, 500, |_| generations += 1);
        assert_eq!(again, Some((evals, hidden)), "deterministic");
        assert_eq!(evals.div_ceil(150), generations);
        assert_eq!(
            run_xor(&NeatParams::plain_neat(), 1, 1),
            None,
            "one generation is too few"
        );
    }
}

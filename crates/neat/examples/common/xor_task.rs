//! The XOR task (Stanley & Miikkulainen 2002), shared by the `xor` example and
//! the `xor_run` benchmark so that both measure the same work.

use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Population};

/// The four cases as lanes: `INPUTS[i][case]` is input `i` (the last is the
/// bias) of case `case`, `TARGETS[case]` its target.
const INPUTS: [[f64; 4]; 3] = [[0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 0.0, 1.0], [1.0; 4]];
const TARGETS: [f64; 4] = [0.0, 1.0, 1.0, 0.0];

/// Fitness and whether all four cases are on the right side of 0.5; `net` is
/// any network, recompiled for `g` in place, and `scratch` its lane values
/// (no allocation per genome). The four cases run as lanes of one pass: the
/// same bits as four activations, their activation functions overlapping.
fn evaluate(net: &mut FeedForwardNetwork, scratch: &mut Vec<[f64; 4]>, g: &Genome) -> (f64, bool) {
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
            let (f, solved) = evaluate(&mut net, &mut scratch, g);
            fitness.push(f);
            if solved && first_solver.is_none() {
                first_solver = Some(i);
            }
        }
        pop.set_fitnesses(fitness).expect("one fitness per genome");
        if std::env::var_os("XOR_TRACE").is_some() {
            eprintln!("{:?}", pop.stats());
        }
        if let Some(i) = first_solver {
            // Evaluations counted as if genomes were evaluated one by one.
            let gen_evals = pop.generation() as usize * pop.params().population_size;
            return Some((gen_evals + i + 1, pop.genomes()[i].num_hidden()));
        }
        pop.next_generation();
    }
    None
}

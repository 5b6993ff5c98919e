//! The XOR task of the `xor` example and the `xor_run` benchmark: the
//! library's (`vivae_neat::benchmarks::xor`, which `vivae reproduce xor` runs
//! too), with the example's `XOR_TRACE` (each generation's stats on stderr).

use vivae_neat::NeatParams;
use vivae_neat::benchmarks::xor::run_xor_observed;

/// One XOR run: `(evaluations until the first solving genome, its hidden
/// nodes)`, or `None` when unsolved after `max_generations`.
pub fn run_xor(params: &NeatParams, seed: u64, max_generations: u32) -> Option<(usize, usize)> {
    let trace = std::env::var_os("XOR_TRACE").is_some();
    run_xor_observed(params, seed, max_generations, |pop| {
        if trace {
            eprintln!("{:?}", pop.stats());
        }
    })
}

//! Evaluation context: what a fitness function is told about the genome it scores.

use serde::{Deserialize, Serialize};

/// Identifies one evaluation; `seed` is the evaluation's own random seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct EvalContext {
    /// Generation being evaluated.
    pub generation: u32,
    /// Index of the genome in the population.
    pub index: usize,
    /// `eval_seed(run_seed, generation, index)`: independent of thread scheduling.
    pub seed: u64,
}

/// One splitmix64 step (Steele, Lea & Flood): a strong 64-bit mixer.
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The seed of evaluation `(generation, index)` in the run seeded with `run_seed`.
pub fn eval_seed(run_seed: u64, generation: u32, index: usize) -> u64 {
    splitmix64(splitmix64(splitmix64(run_seed) ^ u64::from(generation)) ^ index as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_differ_by_every_argument() {
        let s = eval_seed(1, 2, 3);
        assert_eq!(s, eval_seed(1, 2, 3));
        assert_ne!(s, eval_seed(0, 2, 3));
        assert_ne!(s, eval_seed(1, 3, 3));
        assert_ne!(s, eval_seed(1, 2, 4));
        assert_ne!(eval_seed(0, 0, 1), eval_seed(0, 1, 0));
    }
}

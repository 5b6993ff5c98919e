//! The binary 11-multiplexer as SharpNEAT 4 scores it
//! (`BinaryElevenMultiplexerEvaluatorDouble`): input 0 is a bias of 1, inputs
//! 1..=3 the address bits and 4..=11 the data bits of case `i` (bit `k` of `i`
//! is input `k + 1`); the output is clamped to [0, 1] and each of the 2,048
//! cases adds `1 - (1 - y)²` when the addressed bit is 1 and `1 - y²` when it
//! is 0, so a perfect network scores 2,048.

use vivae_neat::{FeedForwardNetwork, Network};

/// Cases of the 11-multiplexer.
pub const MUX_CASES: usize = 2048;

/// Whether case `i`'s output should be 1: the data bit its address selects.
pub fn mux_target(i: usize) -> bool {
    (1 << (3 + (i & 0x7))) & i != 0
}

/// The fitness of `net` (12 inputs, 1 output), in [0, 2048].
// The definition, one case at a time: the tests hold the example's
// `mux_fitness_lanes` to its bits.
#[allow(dead_code)]
pub fn mux_fitness(net: &mut impl Network) -> f64 {
    let mut inputs = [0.0; 12];
    let mut out = [0.0];
    let mut fitness = 0.0;
    inputs[0] = 1.0;
    for i in 0..MUX_CASES {
        for (k, x) in inputs[1..].iter_mut().enumerate() {
            *x = ((i >> k) & 1) as f64;
        }
        net.reset();
        net.activate(&inputs, &mut out);
        let y = out[0].clamp(0.0, 1.0);
        fitness += if mux_target(i) {
            1.0 - (1.0 - y) * (1.0 - y)
        } else {
            1.0 - y * y
        };
    }
    fitness
}

/// Cases computed together by [`mux_fitness_lanes`].
pub const MUX_LANES: usize = 16;

/// [`mux_fitness`] of a feed-forward `net` with [`MUX_LANES`] cases as the
/// lanes of one pass: the same bits (each lane adds the same terms in the
/// same order, and the cases are summed in the same order), the lanes'
/// sigmoids overlapping. `scratch` is the caller's, reused across genomes.
pub fn mux_fitness_lanes(net: &FeedForwardNetwork, scratch: &mut Vec<[f64; MUX_LANES]>) -> f64 {
    let mut inputs = [[0.0; MUX_LANES]; 12];
    inputs[0] = [1.0; MUX_LANES];
    let mut out = [[0.0; MUX_LANES]];
    let mut fitness = 0.0;
    for base in (0..MUX_CASES).step_by(MUX_LANES) {
        for lane in 0..MUX_LANES {
            for (k, x) in inputs[1..].iter_mut().enumerate() {
                x[lane] = (((base + lane) >> k) & 1) as f64;
            }
        }
        net.activate_lanes(&inputs, &mut out, scratch);
        for (lane, y) in out[0].iter().enumerate() {
            let y = y.clamp(0.0, 1.0);
            fitness += if mux_target(base + lane) {
                1.0 - (1.0 - y) * (1.0 - y)
            } else {
                1.0 - y * y
            };
        }
    }
    fitness
}

//! Every genome the operators can grow survives JSON unchanged (bit for bit),
//! and the order its genes are listed in does not matter.

use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use vivae_neat::mutation::{
    mutate_activation, mutate_add_link, mutate_add_node, mutate_toggle_enable, mutate_weights,
};
use vivae_neat::{Genome, GenomeSpec, InnovationTracker, NeatParams, RawGenome};

/// A genome grown from the minimal one by `ops` (0..5 = add-node, add-link,
/// weights, toggle, activation).
fn grown(seed: u64, ops: &[u8], recurrent: bool) -> Genome {
    let spec = GenomeSpec {
        allow_recurrent: recurrent,
        ..GenomeSpec::cppn()
    };
    let params = NeatParams::default();
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
    let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
    for op in ops {
        match op {
            0 => {
                mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
            }
            1 => {
                mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
            }
            2 => mutate_weights(&mut g, &params, &mut rng),
            3 => {
                mutate_toggle_enable(&mut g, &mut rng);
            }
            _ => {
                mutate_activation(&mut g, &spec, &mut rng);
            }
        }
    }
    g
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn genomes_round_trip_bit_identically(
        seed in any::<u64>(),
        ops in prop::collection::vec(0u8..5, 0..80),
        recurrent in any::<bool>(),
    ) {
        let g = grown(seed, &ops, recurrent);
        let json = serde_json::to_string(&g).unwrap();
        let back: Genome = serde_json::from_str(&json).unwrap();
        prop_assert_eq!(&back, &g);
        for (a, b) in back.links().iter().zip(g.links()) {
            prop_assert_eq!(a.weight.to_bits(), b.weight.to_bits());
        }
        prop_assert_eq!(serde_json::to_string(&back).unwrap(), json);
    }

    #[test]
    fn gene_order_in_the_file_does_not_matter(
        seed in any::<u64>(),
        ops in prop::collection::vec(0u8..5, 0..60),
        rotate in any::<prop::sample::Index>(),
    ) {
        let g = grown(seed, &ops, false);
        let mut raw: RawGenome = serde_json::from_str(&serde_json::to_string(&g).unwrap()).unwrap();
        raw.nodes.reverse();
        let k = rotate.index(raw.links.len());
        raw.links.rotate_left(k);
        prop_assert_eq!(Genome::try_from(raw).unwrap(), g);
    }
}

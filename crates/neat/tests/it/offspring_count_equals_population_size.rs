//! Reproduction always yields exactly the configured population size.

use proptest::prelude::*;
use vivae_neat::{GenomeSpec, NeatParams, Population, allocate_offspring};

proptest! {
    #[test]
    fn allocation_sums_to_total(shares in prop::collection::vec(0.0f64..1e6, 1..40), total in 0usize..2000) {
        let a = allocate_offspring(&shares, total);
        prop_assert_eq!(a.len(), shares.len());
        prop_assert_eq!(a.iter().sum::<usize>(), total);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn every_generation_has_population_size(seed in any::<u64>(), size in 1usize..60, threshold in 0.0f64..4.0) {
        let params = NeatParams {
            population_size: size,
            compatibility_threshold: threshold,
            add_node_probability: 0.3,
            ..NeatParams::default()
        };
        let mut pop = Population::new(params, GenomeSpec::cppn(), seed).unwrap();
        for _ in 0..8 {
            pop.evaluate(|g, ctx| (ctx.seed % 97) as f64 + g.links().len() as f64);
            pop.next_generation();
            prop_assert_eq!(pop.genomes().len(), size);
            let members: usize = pop.species().iter().map(|s| s.members.len()).sum();
            prop_assert_eq!(members, size);
        }
    }
}

#[test]
fn population_size_can_change_between_generations() {
    let mut pop = Population::new(NeatParams::default(), GenomeSpec::cppn(), 5).unwrap();
    pop.evaluate(|g, _| g.links()[0].weight);
    let bigger = NeatParams {
        population_size: 130,
        ..NeatParams::default()
    };
    pop.set_params(bigger).unwrap();
    pop.next_generation();
    assert_eq!(pop.genomes().len(), 130);
    let bad = NeatParams {
        population_size: 0,
        ..NeatParams::default()
    };
    assert!(pop.set_params(bad).is_err());
}

//! ES-HyperNEAT on CPPNs grown by real evolution (NEAT generations, LEO
//! seeds): the batched decode equals the reference bit for bit, decoding is
//! deterministic, and the networks run.

use rand::SeedableRng;
use vivae_neat::hyperneat::es::{EsLayout, EsParams, decode_es, decode_es_genome};
use vivae_neat::hyperneat::leo_seeded_genome;
use vivae_neat::{
    FeedForwardNetwork, Genome, GenomeSpec, InnovationTracker, NeatParams, Network, Population,
};

/// Genomes after `generations` of NEAT on an arbitrary fitness (CPPN size),
/// from a LEO-seeded generation 0.
fn evolved(generations: u32, seed: u64) -> Vec<Genome> {
    let spec = GenomeSpec {
        outputs: 3,
        ..GenomeSpec::cppn()
    };
    let params = NeatParams {
        population_size: 30,
        ..NeatParams::paper_cppn()
    };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let mut tracker = InnovationTracker::new(8);
    let genomes = (0..params.population_size)
        .map(|_| leo_seeded_genome(&spec, &params, &mut tracker, &mut rng, 2))
        .collect();
    let mut pop = Population::from_genomes(params, spec, genomes, seed).unwrap();
    for _ in 0..generations {
        let fitness = pop
            .genomes()
            .iter()
            .map(|g| 1.0 + g.num_enabled_links() as f64)
            .collect();
        pop.set_fitnesses(fitness).unwrap();
        pop.next_generation();
    }
    pop.genomes().to_vec()
}

fn layout(leo: bool) -> EsLayout {
    EsLayout {
        inputs: (0..6).map(|i| [-1.0 + 0.4 * i as f64, -1.0]).collect(),
        outputs: vec![[-0.5, 1.0], [0.5, 1.0]],
        weight_output: 0,
        bias_output: Some(1),
        leo_output: leo.then_some(2),
    }
}

#[test]
fn es_hyperneat_batched_decode_matches_reference_on_evolved_cppns() {
    let params = [
        EsParams::default(),
        EsParams {
            initial_depth: 2,
            max_depth: 4,
            recurrent: true,
            iteration_level: 2,
            ..EsParams::default()
        },
    ];
    let mut links = 0;
    for (genome, g) in evolved(15, 4).iter().enumerate() {
        for (k, p) in params.iter().enumerate() {
            let l = layout((genome + k) % 2 == 0);
            let fast = decode_es_genome(g, &l, p).unwrap();
            let reference = decode_es(&mut FeedForwardNetwork::from_genome(g), &l, p).unwrap();
            assert_eq!(fast, reference, "genome {genome}, params {k}");
            assert_eq!(fast, decode_es_genome(g, &l, p).unwrap());
            links += fast.links().len();
            let mut net = fast;
            let mut out = [0.0; 2];
            for step in 0..3 {
                let x: Vec<f64> = (0..6).map(|i| ((i + step) % 2) as f64).collect();
                net.activate(&x, &mut out);
                assert!(out.iter().all(|v| v.is_finite() && v.abs() < 1.0));
            }
        }
    }
    assert!(links > 0, "evolved CPPNs should express some links");
}

//! A short XOR run with a fixed seed finds a solution.

use vivae_neat::{Activation, FeedForwardNetwork, GenomeSpec, NeatParams, Network, Population};

const CASES: [([f64; 3], f64); 4] = [
    ([0.0, 0.0, 1.0], 0.0),
    ([0.0, 1.0, 1.0], 1.0),
    ([1.0, 0.0, 1.0], 1.0),
    ([1.0, 1.0, 1.0], 0.0),
];

#[test]
fn xor_solves_with_fixed_seed() {
    let params = NeatParams {
        population_size: 150,
        weight_amplitude: 8.0,
        compatibility_threshold: 3.0,
        c_excess: 1.0,
        c_disjoint: 1.0,
        c_weight: 0.4,
        add_node_probability: 0.03,
        add_link_probability: 0.05,
        weight_perturb_power: 2.5,
        ..NeatParams::default()
    };
    let spec = GenomeSpec {
        inputs: 3,
        outputs: 1,
        output_activation: Activation::Sigmoid,
        hidden_activations: vec![Activation::Sigmoid],
        allow_recurrent: false,
    };
    let mut pop = Population::new(params, spec, 1).unwrap();
    let score = |g: &vivae_neat::Genome| {
        let mut net = FeedForwardNetwork::from_genome(g);
        let mut out = [0.0];
        let (mut err, mut ok) = (0.0, true);
        for (x, t) in CASES {
            net.activate(&x, &mut out);
            err += (out[0] - t).abs();
            ok &= (out[0] > 0.5) == (t > 0.5);
        }
        ((4.0 - err) * (4.0 - err), ok)
    };
    for _ in 0..300 {
        pop.evaluate(|g, _| score(g).0);
        if let Some(g) = pop.genomes().iter().find(|g| score(g).1) {
            assert!(g.num_hidden() >= 1, "XOR needs a hidden node");
            return;
        }
        pop.next_generation();
    }
    panic!("XOR not solved in 300 generations");
}

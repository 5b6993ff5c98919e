//! Determinism: the same seed gives a bit-identical run; a different seed does not.

use vivae_neat::{GenomeSpec, NeatParams, Population};

fn fitness(g: &vivae_neat::Genome, seed: u64) -> f64 {
    // Depends on structure, weights and the evaluation seed.
    g.links().iter().map(|l| l.weight.sin()).sum::<f64>()
        + g.num_hidden() as f64
        + (seed % 13) as f64 * 0.01
}

fn run(seed: u64) -> Population {
    let params = NeatParams {
        target_species: Some(5),
        ..NeatParams::default()
    };
    let mut pop = Population::new(params, GenomeSpec::cppn(), seed).unwrap();
    for _ in 0..15 {
        pop.evaluate(|g, ctx| fitness(g, ctx.seed));
        pop.next_generation();
    }
    pop
}

#[test]
fn same_seed_twice_is_identical() {
    let a = run(42);
    let b = run(42);
    assert_eq!(a, b);
    assert_eq!(a.to_json().unwrap(), b.to_json().unwrap());
    assert_ne!(a.genomes(), run(43).genomes());
}
